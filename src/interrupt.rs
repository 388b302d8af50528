//! Ctrl-C, SIGTERM and SIGHUP (a CI runner's timeout, a closed terminal): the first sets a flag that long loops (vector dumps, renders, regressions)
//! check, so they stop through their normal error path and their temporary files are removed;
//! a second interrupt exits at once.

use crate::error::{Error, Result};
use std::sync::atomic::{AtomicBool, Ordering};

static INTERRUPTED: AtomicBool = AtomicBool::new(false);

/// Install the handler (once, from `main`).
pub fn install() {
    let _ = ctrlc::set_handler(|| {
        if INTERRUPTED.swap(true, Ordering::SeqCst) {
            std::process::exit(130);
        }
    });
}

/// Error if an interrupt arrived.
pub fn check() -> Result<()> {
    if INTERRUPTED.load(Ordering::Relaxed) {
        Err(Error::Other(
            "interrupted: nothing partial was kept\n  fix: run the command again".into(),
        ))
    } else {
        Ok(())
    }
}
