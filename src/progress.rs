//! Progress of the commands that run for minutes (lint, area, power-space, fuzz, sweep,
//! report): a bar on a terminal, and one line per finished step on stderr otherwise, so a
//! log or CI run shows where the time goes instead of minutes of silence. Stdout keeps only
//! the results, so piping a report stays clean.

use indicatif::{ProgressBar, ProgressStyle};
use std::io::IsTerminal;
use std::sync::Mutex;
use std::time::Instant;

/// Steps of one long job; shareable across rayon workers.
pub struct Progress {
    what: String,
    len: u64,
    /// Steps done; held while a line is printed so lines from workers come out in order.
    done: Mutex<u64>,
    bar: Option<ProgressBar>,
    t0: Instant,
}

impl Progress {
    /// `len` steps of job `what`.
    pub fn new(what: &str, len: u64) -> Progress {
        let bar = std::io::stderr().is_terminal().then(|| {
            let bar = ProgressBar::new(len);
            let style = ProgressStyle::with_template("{prefix} [{bar:40}] {pos}/{len}, {elapsed} {msg}").expect("template");
            bar.set_style(style.progress_chars("=> "));
            bar.set_prefix(what.to_string());
            bar
        });
        Progress {
            what: what.to_string(),
            len,
            done: Mutex::new(0),
            bar,
            t0: Instant::now(),
        }
    }

    /// Say what is running now (a bar's message; nothing in plain mode, where `done` speaks).
    pub fn start(&self, msg: &str) {
        if let Some(b) = &self.bar {
            b.set_message(msg.to_string());
        }
    }

    /// One step finished: `msg` says which.
    pub fn done(&self, msg: &str) {
        let mut done = self.done.lock().unwrap_or_else(|e| e.into_inner());
        *done += 1;
        let n = *done;
        match &self.bar {
            Some(b) => {
                b.inc(1);
                b.set_message(msg.to_string());
            }
            None => {
                eprintln!("{}: [{n}/{}] {msg} ({:.1} s)", self.what, self.len, self.t0.elapsed().as_secs_f64());
            }
        }
    }
}

impl Drop for Progress {
    fn drop(&mut self) {
        if let Some(b) = &self.bar {
            b.finish_and_clear();
        }
    }
}
