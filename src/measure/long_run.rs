//! The long regression of `gbump report`: `random:N` records of one configuration run through
//! the Verilator harness twice, streamed from the model (`gbump regress --stream`) and from a
//! vector file of the same records (`gbump vectors`, then the harness on the file), with the
//! regressions' bubble and stall patterns, so the two times stand side by side. The file is removed after
//! its run: at 10^8 records it is several gigabytes.

use crate::config::PipelineConfig;
use crate::error::{Error, Result};
use crate::sim::stream::{power_table, regress_harness, run_stream, streams, StreamRun, StreamSource};
use crate::sim::{Outcome, Simulator, Verilator};
use std::path::Path;
use std::time::Instant;

/// Records of the report's long regression.
pub const LONG_RUN_RECORDS: u64 = 100_000_000;
/// Seed of its records.
pub const LONG_RUN_SEED: u64 = 1;
/// `gbump regress`'s stall and bubble patterns (`--stall`, `--bubbles`), which the long run keeps.
pub const LONG_RUN_STALL: u32 = 13;
pub const LONG_RUN_BUBBLES: u32 = 29;

/// One run's line.
pub struct Run {
    pub what: &'static str,
    pub outcome: Outcome,
    /// Seconds spent before the harness started (writing the vector file), 0 when streamed.
    pub prepare: f64,
}

/// Both runs of `count` records of `cfg` (selected by `pick_args`, as `gbump regress` is
/// given it) in `work`, with the harness `gbump regress --stream` builds there; an error when
/// either run fails.
pub fn long_run(cfg: &PipelineConfig, pick_args: &str, work: &Path, count: u64) -> Result<Vec<Run>> {
    // Absolute, as `gbump regress` makes its --work: the harness build runs in its own folder.
    let work = std::path::absolute(work).map_err(|e| Error::io(work, e))?;
    let exe = regress_harness(cfg, pick_args, &work)?;
    let table = power_table(cfg, &work.join("long_run_table"), cfg.shininess, "gbump report")?;
    let s = &streams(cfg, &StreamSource::Random(count), LONG_RUN_SEED, None)?[0];
    let run = StreamRun {
        exe: &exe,
        table: &table,
        cwd: &work,
        max_errors: crate::sim::regress::MAX_ERRORS,
        bubbles: LONG_RUN_BUBBLES,
        stall: LONG_RUN_STALL,
        progress: true,
    };
    let streamed = run_stream(cfg, s, &run)?;
    let vdir = work.join("long_run_vectors");
    let _ = std::fs::remove_dir_all(&vdir);
    let o = crate::vectors::DumpOptions {
        seed: LONG_RUN_SEED,
        ..crate::vectors::DumpOptions::formats("gbump report", false, true)
    };
    let t = Instant::now();
    let sets = crate::vectors::dump(cfg, &crate::vectors::Source::Random(count), &["top".to_string()], &vdir, &o)?;
    let prepare = t.elapsed().as_secs_f64();
    let (m, dir) = crate::vectors::verify(&sets[0].manifest)?;
    let args = [
        "--vectors".to_string(),
        dir.join(&m.bin.as_ref().expect("a binary file").name).display().to_string(),
        "--table".into(),
        table.display().to_string(),
        "--stall".into(),
        LONG_RUN_STALL.to_string(),
        "--bubbles".into(),
        LONG_RUN_BUBBLES.to_string(),
    ];
    let file = Verilator.run(&exe, &args, None, &work, "long file run");
    let _ = std::fs::remove_dir_all(&vdir);
    let file = file?;
    let runs = vec![
        Run {
            what: "streamed (`gbump regress --stream`)",
            outcome: streamed,
            prepare: 0.0,
        },
        Run {
            what: "from a file (`gbump vectors`, then the harness)",
            outcome: file,
            prepare,
        },
    ];
    if let Some(r) = runs.iter().find(|r| r.outcome.passed != count || r.outcome.failed > 0) {
        return Err(Error::Other(format!(
            "long regression, {}: {} passed, {} failed of {count}:\n{}",
            r.what,
            r.outcome.passed,
            r.outcome.failed,
            crate::tool::tail(&r.outcome.log, 20)
        )));
    }
    Ok(runs)
}

/// The runs as the report's Markdown table.
pub fn markdown(cfg: &PipelineConfig, count: u64, runs: &[Run]) -> String {
    let mut s = format!(
        "`gbump regress --stream random:{count} --seed {LONG_RUN_SEED}` on config `{}` ({:?} x{}), beside the harness on a file of the same records; both idle `in_valid` and hold `out_ready` low as regressions do (`--bubbles {LONG_RUN_BUBBLES} --stall {LONG_RUN_STALL}`).\n\n| run | vectors passed | failed | harness wall time | vectors/s | writing the file first |\n|---|---:|---:|---:|---:|---:|\n",
        &cfg.hash()[..8],
        cfg.light_mode,
        cfg.lights
    );
    for r in runs {
        s += &format!(
            "| {} | {} | {} | {:.1} s | {:.2} M | {} |\n",
            r.what,
            r.outcome.passed,
            r.outcome.failed,
            r.outcome.seconds,
            r.outcome.passed as f64 / r.outcome.seconds / 1e6,
            if r.prepare > 0.0 {
                format!("{:.1} s", r.prepare)
            } else {
                "none".into()
            }
        );
    }
    s
}
