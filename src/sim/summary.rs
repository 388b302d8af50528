//! What a regression reports: the table of runs (the user's), its totals, and JUnit XML
//! (a CI's).

use super::regress::RunResult;
use crate::config::PipelineConfig;
use crate::error::Result;
use crate::tool::tail;

/// Runs, vectors whose result matched, failed checks and failing runs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Totals {
    pub runs: usize,
    /// Vectors whose result matched.
    pub passed: u64,
    /// Failed checks: a vector's result, and each timing, handshake or X report (a vector
    /// can fail more than one), so not a count of vectors.
    pub failed: u64,
    pub failing: usize,
}

/// One line per run to `say` (a failing run's log tail before its line), under a header.
pub fn table(results: &[RunResult], say: &mut dyn FnMut(&str) -> Result<()>) -> Result<Totals> {
    let mut t = Totals {
        runs: results.len(),
        passed: 0,
        failed: 0,
        failing: 0,
    };
    say(&format!(
        "{:10} {:44} {:>10} {:>8} {:>9}",
        "sim", "set", "passed", "failed", "seconds"
    ))?;
    for r in results {
        match &r.outcome {
            Ok(out) => {
                t.passed += out.passed;
                t.failed += out.failed;
                if out.failed > 0 {
                    t.failing += 1;
                    say(&tail(&out.log, 40))?;
                }
                say(&format!(
                    "{:10} {:44} {:>10} {:>8} {:>9.2}",
                    r.sim.name(),
                    r.set,
                    out.passed,
                    out.failed,
                    out.seconds
                ))?;
            }
            Err(e) => {
                t.failing += 1;
                say(&format!("{:10} {:44} ERROR: {e}", r.sim.name(), r.set))?;
            }
        }
    }
    Ok(t)
}

/// JUnit XML of a regression.
/// The closing line of a regression (`kind`: "" or " (streamed)"), and its verdict: an error
/// when any run failed.
pub fn verdict(cfg: &PipelineConfig, kind: &str, t: &Totals, say: &mut dyn FnMut(&str) -> Result<()>) -> Result<()> {
    say(&format!(
        "regress config {}{kind}: {} runs, {} vectors passed, {} failed checks, {} failing run(s)",
        cfg.hash(),
        t.runs,
        t.passed,
        t.failed,
        t.failing
    ))?;
    if t.failing > 0 {
        return Err(crate::error::Error::Other(format!("{} regression run(s) failed", t.failing)));
    }
    Ok(())
}

pub fn junit(cfg: &PipelineConfig, results: &[RunResult]) -> String {
    let failures = results.iter().filter(|r| !matches!(&r.outcome, Ok(o) if o.failed == 0)).count();
    let mut s = format!(
        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n{SUITE}{}\" tests=\"{}\" failures=\"{failures}\">\n",
        cfg.hash(),
        results.len()
    );
    for r in results {
        let name = format!("{}.{}", r.sim.name(), r.set);
        match &r.outcome {
            Ok(o) if o.failed == 0 => s += &format!("  <testcase classname=\"{}\" name=\"{}\" time=\"{:.3}\"/>\n", r.target, crate::xml::escape(&name), o.seconds),
            Ok(o) => s += &format!("  <testcase classname=\"{}\" name=\"{}\" time=\"{:.3}\"><failure message=\"{} passed, {} failed\">{}</failure></testcase>\n", r.target, crate::xml::escape(&name), o.seconds, o.passed, o.failed, crate::xml::escape(&tail(&o.log, 60))),
            Err(e) => s += &format!("  <testcase classname=\"{}\" name=\"{}\"><error message=\"simulation error\">{}</error></testcase>\n", r.target, crate::xml::escape(&name), crate::xml::escape(e)),
        }
    }
    s + "</testsuite>\n"
}

/// How every regression report opens its suite, the configuration's hash next.
const SUITE: &str = "<testsuite name=\"gbump regress ";

/// Whether `head`, the start of a file, is a regression report gbump wrote.
pub fn is_report(head: &[u8]) -> bool {
    head.starts_with(b"<?xml") && head.windows(SUITE.len()).any(|w| w == SUITE.as_bytes())
}

/// The report of a regression that failed before it had runs to report (a set refused, a
/// build that failed, a simulator missing): one test case in error, with the message.
pub fn junit_error(cfg: &PipelineConfig, message: &str) -> String {
    let first = message.lines().next().unwrap_or_default();
    format!(
        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n{SUITE}{}\" tests=\"1\" failures=\"0\" errors=\"1\">\n  <testcase classname=\"regress\" name=\"gbump regress\"><error message=\"{}\">{}</error></testcase>\n</testsuite>\n",
        cfg.hash(),
        crate::xml::escape(first),
        crate::xml::escape(message)
    )
}
