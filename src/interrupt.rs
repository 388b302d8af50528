//! Ctrl-C, SIGTERM and SIGHUP (a CI runner's timeout, a closed terminal). Where a run holds a
//! [`Cleanup`] (writing vector files, output folders, a streamed regression), the first
//! signal sets a flag that its loops check, so they stop through their normal error path and
//! remove what they wrote; a second exits at once. Anywhere else the first exits at once, as
//! the signal's default would, so a long computation is not finished only to be thrown away.
//! A signal that was ignored when gbump started (`nohup`'s SIGHUP) stays ignored.

use crate::error::{Error, Result};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};

static INTERRUPTED: AtomicBool = AtomicBool::new(false);
static CLEANUPS: AtomicUsize = AtomicUsize::new(0);
/// Tools running now (`tool::run_cmd`): a signal that ends gbump ends them too.
static CHILDREN: std::sync::Mutex<Vec<u32>> = std::sync::Mutex::new(Vec::new());

/// While held, `pid` is signalled when a signal ends gbump.
pub struct Child(u32);

/// Register a started tool for as long as the result is held.
pub fn child(pid: u32) -> Child {
    if let Ok(mut c) = CHILDREN.lock() {
        c.push(pid);
    }
    Child(pid)
}

impl Drop for Child {
    fn drop(&mut self) {
        if let Ok(mut c) = CHILDREN.lock() {
            c.retain(|&p| p != self.0);
        }
    }
}

/// Install the handler (once, from `main`).
pub fn install() {
    #[cfg(unix)]
    let ignored: Vec<libc::c_int> = [libc::SIGHUP, libc::SIGINT, libc::SIGTERM]
        .into_iter()
        .filter(|&s| {
            // SAFETY: reads the current action into a zeroed struct; changes nothing.
            unsafe {
                let mut old: libc::sigaction = std::mem::zeroed();
                libc::sigaction(s, std::ptr::null(), &mut old) == 0 && old.sa_sigaction == libc::SIG_IGN
            }
        })
        .collect();
    let _ = ctrlc::set_handler(|| {
        // The handler runs on a thread of its own, not in signal context: it may print and
        // signal the tools gbump started. Each runs in its own process group (`tool::run_cmd`),
        // out of reach of a terminal's Ctrl-C, so it is ended here on the first signal too: a
        // run stopping through its error path must not wait for a half-hour build.
        #[cfg(unix)]
        for pid in CHILDREN.lock().map(|c| c.clone()).unwrap_or_default() {
            // SAFETY: a plain kill(2) of the process group of a tool this run started and
            // still waits for.
            unsafe {
                libc::kill(-(pid as libc::pid_t), libc::SIGTERM);
            }
        }
        if CLEANUPS.load(Ordering::SeqCst) == 0 || INTERRUPTED.swap(true, Ordering::SeqCst) {
            eprintln!("gbump: interrupted: stopped (outputs written so far are complete files; temporary files go at the next run in that folder)");
            std::process::exit(130);
        }
    });
    #[cfg(unix)]
    for s in ignored {
        // SAFETY: restores the ignore disposition the process was started with.
        unsafe {
            libc::signal(s, libc::SIG_IGN);
        }
    }
}

/// While held, a signal asks the run to stop through its error path instead of exiting, so
/// the holder can remove what it wrote.
pub struct Cleanup(());

/// Hold a [`Cleanup`] for as long as a run writes something it must remove when stopped.
pub fn cleanup() -> Cleanup {
    CLEANUPS.fetch_add(1, Ordering::SeqCst);
    Cleanup(())
}

impl Drop for Cleanup {
    fn drop(&mut self) {
        CLEANUPS.fetch_sub(1, Ordering::SeqCst);
    }
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
