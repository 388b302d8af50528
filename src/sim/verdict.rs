//! A run's verdict: the testbench's own "N passed, N failed" line, and any simulator warning
//! (a memory file that did not load, among others) failing the run, whichever simulator ran it.

use crate::error::{Error, Result};
use crate::tool::tail;

/// Verdict of one simulation run.
#[derive(Clone, Debug, PartialEq)]
pub struct Outcome {
    pub passed: u64,
    pub failed: u64,
    pub seconds: f64,
    pub log: String,
}

/// Parse the testbench's summary line.
pub fn parse_summary(log: &str) -> Option<(u64, u64)> {
    log.lines().rev().find_map(summary_of)
}

/// The counts of one summary line.
fn summary_of(l: &str) -> Option<(u64, u64)> {
    let (p, rest) = l.trim().split_once(" passed, ")?;
    let f = rest.strip_suffix(" failed")?;
    Some((p.parse().ok()?, f.parse().ok()?))
}

/// Lines of a simulation log in which the simulator warned or erred: a memory file that did
/// not load (`$readmemh`), a file that did not open. Any of them fails the run, because the
/// simulation went on with contents nobody meant (X, or an old table).
pub fn simulator_warnings(log: &str) -> Vec<&str> {
    log.lines()
        .filter(|l| {
            let t = l.trim_start();
            let low = t.to_ascii_lowercase();
            t.starts_with("WARNING")
                || t.starts_with("ERROR")
                || t.starts_with("%Warning")
                || t.starts_with("%Error")
                || low.contains("$readmem")
                || low.contains("unable to open")
        })
        .collect()
}

/// Turn a finished run into an outcome, or an error when the testbench did not report, gave
/// up (a FATAL line), or the simulator warned.
pub fn outcome(ok: bool, log: String, secs: f64, what: &str) -> Result<Outcome> {
    // A failed run's testbench ends with `$fatal` (exit code 1); what failed is above it.
    let judged = match log.find(crate::rtlgen::testbench::EXIT_MARK) {
        Some(at) => &log[..log[..at].rfind('\n').map_or(0, |i| i + 1)],
        None => &log[..],
    };
    // Output cut by the cap on what gbump reads (`tool::read_capped`): what was left out may
    // hold a warning or a mismatch, so the run is not judged clean on the rest.
    if let Some(line) = crate::tool::cut_note(&log) {
        return Err(Error::Other(format!(
            "{what}: the simulator printed more than gbump reads ({line}), so the run does not count: a testbench run prints a line per mismatch and one summary\n--- last lines ---\n{}\n  fix: lower --max-errors, or find what floods the output (a $display in a loop) in the lines above",
            crate::tool::tail(&log, 10)
        )));
    }
    let warned = simulator_warnings(judged);
    if !warned.is_empty() {
        return Err(Error::Other(format!(
            "{what}: the simulator warned, so the run does not count (a warning means it went on with contents nobody meant):\n{}\n  fix: {}",
            warned.iter().take(10).copied().collect::<Vec<_>>().join("\n"),
            if warned.iter().any(|l| {
                let l = l.to_ascii_lowercase();
                l.contains("readmem") && (l.contains("not enough words") || l.contains("ended before") || l.contains("too many words"))
            }) {
                "a memory init file holds the wrong number of words (truncated, or made for another configuration): regenerate it with the command in its header (`gbump rom` or `gbump vectors`)"
            } else if warned.iter().any(|l| l.to_ascii_lowercase().contains("readmem")) {
                "a memory init file did not load: check the path given to INIT_FILE (absolute, or relative to the folder the simulator runs in)"
            } else {
                "read the lines above; rerun with --waves to see the signals"
            }
        )));
    }
    // A testbench prints one summary and a MISMATCH line for each failure it counts: a second
    // summary, or a mismatch beside "0 failed", is output mixed with another's or altered
    // (a wrapper that appends a clean line), and does not count.
    let summaries = log.lines().filter(|l| summary_of(l).is_some()).count();
    let mismatches = judged.lines().filter(|l| l.trim_start().starts_with("MISMATCH")).count();
    if summaries > 1 || (mismatches > 0 && parse_summary(&log).is_some_and(|(_, f)| f == 0)) {
        return Err(Error::Other(format!(
            "{what}: the log holds {summaries} \"N passed, N failed\" lines and {mismatches} MISMATCH line(s), which no testbench run prints (one summary, counting every mismatch), so the run does not count\n--- last lines ---\n{}\n  fix: run the simulator as installed (scripts/install-tools.sh), not through a wrapper that adds to its output",
            tail(&log, 15)
        )));
    }
    if parse_summary(&log) == Some((0, 0)) {
        return Err(Error::Other(format!(
            "{what}: the testbench checked no vectors\n{}\n  fix: {NO_VECTORS_FIX}",
            tail(&log, 10)
        )));
    }
    if let Some(fatal) = judged.lines().find(|l| l.trim_start().starts_with("FATAL")) {
        // `outcome` judges every bench (regress, cosim, a stream, render --rtl): the fix
        // names what the line says, not one command's options.
        let fix = if fatal.contains("stayed low") || fatal.contains("in flight") {
            "the RTL stopped answering the handshake the line names (or took more than it may hold): a fault of the RTL, not of the stimulus; a waveform of the same records shows where (`gbump regress --waves` on a vector set of the same source and seed)"
        } else if fatal.contains("no vectors") || fatal.contains("no fragments") {
            "nothing was checked: give records to check (a set whose manifest count is above 0, or a count of 1 or more)"
        } else {
            "the line names the input the testbench could not take; correct it (a vector file: regenerate it with the command in its manifest)"
        };
        return Err(Error::Other(format!(
            "{what}: the testbench gave up: {}\n  fix: {fix}",
            fatal.trim()
        )));
    }
    match parse_summary(&log) {
        Some((passed, failed)) => {
            // A clean summary is a pass only from a process that then exited cleanly: one
            // that crashed or was killed after printing it (its waves or coverage unwritten,
            // a later check never run) does not count.
            if !ok && failed == 0 {
                return Err(Error::Other(format!(
                    "{what}: the simulation printed \"{passed} passed, 0 failed\" and then exited with an error (a crash or a signal), so it does not count\n--- last lines ---\n{}\n  fix: rerun it; if it fails again, reinstall the simulator (scripts/install-tools.sh)",
                    tail(&log, 15)
                )));
            }
            Ok(Outcome { passed, failed, seconds: secs, log })
        }
        // Exiting 0 without the summary every testbench prints is not a crash: something
        // other than the testbench ran, or its output went elsewhere.
        None if ok => Err(Error::Other(format!(
            "{what}: the simulator exited 0 without the testbench's \"N passed, N failed\" line, so what ran was not gbump's testbench (a wrapper or another program in the simulator's place), or its output went elsewhere\n--- last lines ---\n{}\n  fix: run the simulator as installed (scripts/install-tools.sh; `which vvp verilator` shows which runs), and run again",
            tail(&log, 15)
        ))),
        None => Err(Error::Other(format!(
            "{what}: the simulation exited with an error before the testbench's \"N passed, N failed\" line: it crashed or was cut short\n--- last lines ---\n{}\n  fix: the last lines say where; rerun it, and if the simulator itself crashes again, reinstall it (scripts/install-tools.sh)",
            tail(&log, 15)
        ))),
    }
}

/// A run that checked nothing: the records it was given were none, or it never read them.
const NO_VECTORS_FIX: &str = "give it records (a set whose manifest count is above 0); if the set has records, the testbench did not read them: regenerate its vector file with the command in its manifest";

#[cfg(test)]
mod tests {
    /// A summary of no failures from a process that exited with an error is no pass; the
    /// same summary from a clean exit is, and failures from a failing exit are counted.
    #[test]
    fn a_clean_summary_from_a_failed_process_does_not_pass() {
        let log = "20 passed, 0 failed\n".to_string();
        let e = super::outcome(false, log.clone(), 1.0, "run").unwrap_err().to_string();
        assert!(e.contains("exited with an error") && e.contains("fix:"), "{e}");
        assert_eq!(super::outcome(true, log, 1.0, "run").unwrap().passed, 20);
        let failing = format!("18 passed, 2 failed\n{}\n", crate::rtlgen::testbench::EXIT_MARK);
        assert_eq!(super::outcome(false, failing.clone(), 1.0, "run").unwrap().failed, 2);
        // A clean line appended after a failing run's output (a wrapper), or a mismatch
        // beside "0 failed", does not pass.
        let appended = format!("MISMATCH vector 3\n{failing}20 passed, 0 failed\n");
        let e = super::outcome(true, appended, 1.0, "run").unwrap_err().to_string();
        assert!(e.contains("2 \"N passed, N failed\" lines") && e.contains("fix:"), "{e}");
        let hidden = "MISMATCH vector 3\n20 passed, 0 failed\n".to_string();
        assert!(super::outcome(true, hidden, 1.0, "run").is_err());
    }

    /// A run without the summary line says what it was by its exit: a clean exit is not a
    /// crash (something else ran), a failing one is; both with a fix.
    #[test]
    fn a_run_without_a_summary_is_named_by_its_exit() {
        let e = super::outcome(true, "PASS\n".into(), 1.0, "run").unwrap_err().to_string();
        assert!(e.contains("exited 0") && !e.contains("crashed") && e.contains("fix:"), "{e}");
        let e = super::outcome(false, "Segmentation fault\n".into(), 1.0, "run")
            .unwrap_err()
            .to_string();
        assert!(e.contains("crashed") && e.contains("fix:"), "{e}");
        let e = super::outcome(true, "0 passed, 0 failed\n".into(), 1.0, "run")
            .unwrap_err()
            .to_string();
        assert!(e.contains("checked no vectors") && e.contains("fix:"), "{e}");
    }

    /// A log the output cap cut (`tool::read_capped`) is not judged clean on what was kept:
    /// the part left out may hold the mismatch.
    #[test]
    fn a_cut_log_does_not_pass() {
        let flood = "MISMATCH again\n".repeat((crate::tool::KEPT_HEAD + 2 * crate::tool::KEPT_TAIL) / 15 + 1000) + "20 passed, 0 failed\n";
        let log = String::from_utf8(crate::tool::read_capped(flood.as_bytes())).unwrap();
        let e = super::outcome(true, log, 1.0, "run").unwrap_err().to_string();
        assert!(e.contains("more than gbump reads") && e.contains("fix:"), "{e}");
    }
}
