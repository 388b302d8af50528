// Running out says so and cleans up, rather than aborting with the run's temporary files left.
#[global_allocator]
static ALLOCATOR: gbump::out_of_memory::Allocator = gbump::out_of_memory::Allocator;

fn main() {
    gbump::out_of_memory::install();
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
            let shown = gbump::error::shown(&format!("{e:#}"));
            if !gbump::interrupt::interrupted() {
                eprintln!("gbump: error: {shown}");
                std::process::exit(1);
            }
            // One prefix for every way a signal ends a run (this error path, a forced stop,
            // a signal after the last check), so a script greps `gbump: interrupted:` alone.
            eprintln!("gbump: interrupted: {}", shown.strip_prefix("interrupted: ").unwrap_or(&shown));
            std::process::exit(gbump::interrupt::exit_status());
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
