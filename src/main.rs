fn main() {
    gbump::interrupt::install();
    if let Err(e) = gbump::cli::run() {
        eprintln!("gbump: error: {e:#}");
        std::process::exit(1);
    }
}
