fn main() {
    gbump::interrupt::install();
    match gbump::cli::run() {
        // The reader of standard output closed it early (`gbump config | head -1`): quiet, with
        // the status a tool killed by SIGPIPE has, as `head`'s other writers end.
        Err(e) if gbump::error::is_closed_stdout(&e) => {
            gbump::render::output::remove_made_folders(&[gbump::work_lock::LOCK_NAME]);
            std::process::exit(128 + 13);
        }
        Err(e) => {
            gbump::interrupt::kill_remaining();
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
            gbump::interrupt::kill_remaining();
            eprintln!("gbump: interrupted: the signal came as the run finished; its outputs are complete");
            std::process::exit(gbump::interrupt::exit_status());
        }
        Ok(()) => {}
    }
}
