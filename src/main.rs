fn main() {
    gbump::interrupt::install();
    match gbump::cli::run() {
        Err(e) => {
            gbump::render::output::remove_made_folders(&[gbump::work_lock::LOCK_NAME]);
            eprintln!("gbump: error: {}", gbump::error::shown(&format!("{e:#}")));
            std::process::exit(if gbump::interrupt::interrupted() {
                gbump::interrupt::exit_status()
            } else {
                1
            });
        }
        // A signal that came after the run's last check: it finished, but a script that sent
        // the signal must not read a plain success.
        Ok(()) if gbump::interrupt::interrupted() => {
            eprintln!("gbump: interrupted: the signal came as the run finished; its outputs are complete");
            std::process::exit(gbump::interrupt::exit_status());
        }
        Ok(()) => {}
    }
}
