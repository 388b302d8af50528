fn main() {
    gbump::interrupt::install();
    if let Err(e) = gbump::cli::run() {
        gbump::render::output::remove_made_folders(&[gbump::work_lock::LOCK_NAME]);
        eprintln!("gbump: error: {}", gbump::error::shown(&format!("{e:#}")));
        std::process::exit(if gbump::interrupt::interrupted() {
            gbump::interrupt::exit_status()
        } else {
            1
        });
    }
}
