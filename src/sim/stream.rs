//! `gbump regress --stream SOURCE`: stimulus and the model's expected responses made in this
//! process and piped into the Verilator C++ harness (`--vectors - --count N`), so no vector
//! file is written whatever the count. The records are byte for byte those `gbump vectors`
//! writes for the same source and seed, so a failing record replays from a file. Memory stays
//! constant: chunks are encoded in parallel a batch at a time into a bounded channel, one
//! thread writes them into the pipe, and the harness reads them into a ring.

use super::regress::{RegressOptions, RunResult};
use super::{Outcome, Sim, Verilator};
use crate::config::PipelineConfig;
use crate::error::{Error, Result};
use crate::units::MemoryContents;
use crate::vectors::sources::{chunk_rng, corners, scene_groups, RANDOM_CHUNK};
use crate::vectors::targets::TopStim;
use crate::vectors::top_records::TopRecords;
use crate::work_lock::WorkLock;
use rayon::prelude::*;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

/// A parsed `--stream`.
#[derive(Clone, Debug, PartialEq)]
pub enum StreamSource {
    Random(u64),
    Scene(String),
    /// The corner catalogue at level 2, as the default regression runs it.
    Corners,
}

impl StreamSource {
    /// `random:N` (1 <= N <= MAX_STREAM_VECTORS), `scene:NAME` or `corners`.
    pub fn parse(s: &str) -> Result<StreamSource> {
        let bad = || {
            Error::Other(format!(
                "--stream {s}: not a stream source\n  fix: use random:N, scene:NAME or corners (exhaustive sets are small: write them with `gbump vectors` and run them with --vectors)"
            ))
        };
        match s.split_once(':') {
            None if s == "corners" => Ok(StreamSource::Corners),
            Some(("random", n)) => {
                let max = crate::limits::MAX_STREAM_VECTORS;
                let v = crate::limits::parse_count(&format!("--stream {s}"), n, 1, max, "MAX_STREAM_VECTORS")?;
                Ok(StreamSource::Random(v))
            }
            Some(("scene", n)) if !n.is_empty() => {
                crate::names::check("--stream", "scene:NAME", &crate::vectors::Source::Scene(n.into()).stem())?;
                Ok(StreamSource::Scene(n.to_string()))
            }
            _ => Err(bad()),
        }
    }
}

enum Feed {
    /// `random_chunk` of this seed.
    Random(u64),
    /// Stimuli already in memory (a scene, the corners), with why each corner is there.
    Stims(Vec<TopStim>, Vec<String>),
}

/// One harness run: one power table, `count` records.
pub struct Stream {
    /// The run's name in the summary, after the set `gbump vectors` writes for it.
    pub set: String,
    pub shininess: u32,
    pub count: u64,
    feed: Feed,
    /// EMBM scene streams: the object's maps, loaded through the top's ports first.
    env: Option<crate::model::env_map::EnvMaps>,
    /// The `gbump vectors` arguments that write this stream as a file (`--source ...`).
    source_args: String,
}

/// The streams of `src` under `cfg`: one, or a scene's one per shininess. A scene is rendered
/// here, so a missing scene or a mismatched configuration is refused before anything is built.
pub fn streams(cfg: &PipelineConfig, src: &StreamSource, seed: u64, size: Option<(u32, u32)>) -> Result<Vec<Stream>> {
    Ok(match src {
        StreamSource::Random(n) => vec![Stream {
            set: format!("stream_random{n}_top"),
            shininess: cfg.shininess,
            count: *n,
            feed: Feed::Random(seed),
            env: None,
            source_args: format!("--source random:{n} --seed {seed}"),
        }],
        StreamSource::Corners => {
            let (why, stims): (Vec<String>, Vec<TopStim>) = corners(cfg, 2).into_iter().unzip();
            vec![Stream {
                set: "stream_corners_level2_top".into(),
                shininess: cfg.shininess,
                count: stims.len() as u64,
                feed: Feed::Stims(stims, why),
                env: None,
                source_args: "--source corners --level 2".into(),
            }]
        }
        StreamSource::Scene(name) => {
            crate::vectors::sources::scene_sets_made(cfg, &format!("--stream scene:{name}"))?;
            let size_arg = size.map_or(String::new(), |(w, h)| format!(" --size {w}x{h}"));
            scene_groups(cfg, name, size)?
                .into_iter()
                .map(|g| Stream {
                    set: format!("stream_{}_top", g.stem),
                    shininess: g.shininess,
                    count: g.stims.len() as u64,
                    feed: Feed::Stims(g.stims, Vec::new()),
                    env: g.env,
                    source_args: format!("--source scene:{name}{size_arg}"),
                })
                .collect()
        }
    })
}

impl Stream {
    fn chunks(&self) -> u64 {
        self.count.div_ceil(RANDOM_CHUNK)
    }

    /// The binary records of chunk `c` (records `c * RANDOM_CHUNK ..`), as `gbump vectors`
    /// writes them, by the fast model under the readable model's check
    /// (`vectors::top_records`). Random stimuli are drawn as they are encoded, a batch at a
    /// time.
    pub fn chunk_bytes(&self, maker: &TopRecords, c: u64) -> Result<Vec<u8>> {
        let len = RANDOM_CHUNK.min(self.count - c * RANDOM_CHUNK) as usize;
        let mut bin = Vec::with_capacity(len * maker.layout.bytes());
        match &self.feed {
            Feed::Random(seed) => {
                maker.random_chunk(*seed, c, self.count, Some(&mut bin), None, false)?;
            }
            Feed::Stims(v, _) => {
                let lo = (c * RANDOM_CHUNK) as usize;
                maker.encode(lo as u64, &v[lo..lo + len], Some(&mut bin), None)?;
            }
        }
        Ok(bin)
    }

    /// How to write record `k` of this stream to a file and run it alone (the whole stream
    /// when the harness named no record). A random stream's chunk `c` is chunk 0 of the stream
    /// seeded `seed ^ c * K` (`chunk_rng`), so a record replays from a file of at most
    /// `RANDOM_CHUNK` records whatever its index.
    pub fn replay(&self, pick_args: &str, k: Option<u64>) -> String {
        let cfg_args = if pick_args.is_empty() {
            "--config CONFIG.toml".to_string()
        } else {
            pick_args.to_string()
        };
        let run = format!("then `gbump regress --sim verilator {cfg_args} --vectors DIR`");
        let cfg_note = if pick_args.is_empty() {
            " (CONFIG.toml: this run's configuration, the default: `gbump config > CONFIG.toml`)"
        } else {
            ""
        };
        let Some(k) = k else {
            return format!(
                "no record named: write the stream with `gbump vectors {cfg_args} {} --target top --out DIR`; {run}{cfg_note}",
                self.source_args
            );
        };
        match &self.feed {
            Feed::Random(seed) => {
                let c = k / RANDOM_CHUNK;
                let len = RANDOM_CHUNK.min(self.count - c * RANDOM_CHUNK);
                let seed_c = chunk_rng(*seed, c).0;
                format!(
                    "seed {seed}, record {k}: it is record {k} of `gbump vectors {cfg_args} {} --target top --out DIR`, and record {} of the {len}-record replay `gbump vectors {cfg_args} --source random:{len} --seed {seed_c} --target top --out DIR`; {run}{cfg_note}",
                    self.source_args,
                    k % RANDOM_CHUNK
                )
            }
            Feed::Stims(_, why) => format!(
                "record {k}{}: it is record {k} of set {} from `gbump vectors {cfg_args} {} --target top --out DIR`; {run}{cfg_note}",
                why.get(k as usize).map_or(String::new(), |w| format!(" ({w})")),
                self.set,
                self.source_args
            ),
        }
    }
}

/// The record index of the first mismatch the harness reported (`vector K`).
pub fn first_failing_record(log: &str) -> Option<u64> {
    log.lines().filter(|l| l.starts_with("MISMATCH")).find_map(|l| {
        let rest = &l[l.find("vector ")? + 7..];
        rest.split(|c: char| !c.is_ascii_digit()).next()?.parse().ok()
    })
}

/// Options of one streamed run.
pub struct StreamRun<'a> {
    pub exe: &'a Path,
    /// The power table loaded through the load port before the first record.
    pub table: &'a Path,
    pub cwd: &'a Path,
    pub max_errors: u32,
    pub bubbles: u32,
    /// Tops with out_ready: hold it low for 1-3 edges every Nth edge (0: never).
    pub stall: u32,
    /// Show a progress bar (or progress lines).
    pub progress: bool,
}

/// Stream `s` through the harness: its verdict, as a file-based run's.
pub fn run_stream(cfg: &PipelineConfig, s: &Stream, r: &StreamRun) -> Result<Outcome> {
    crate::interrupt::check()?;
    let what = format!("verilator {}", s.set);
    let contents = MemoryContents::new(cfg, s.shininess).with_env(s.env.as_ref());
    // Beside the power table, the maps the harness loads (as a file-based set's).
    let dir = r.table.parent().unwrap_or(r.cwd);
    let files = match &s.env {
        Some(env) => Some(crate::vectors::writer::write_env_maps(
            dir,
            &s.set,
            cfg,
            env,
            "gbump regress --stream",
        )?),
        None => None,
    };
    let env_args = super::regress::harness_memory_args(files.as_ref(), dir);
    let maker = TopRecords::new(cfg, contents.view());
    let t0 = std::time::Instant::now();
    let mut cmd = Command::new(r.exe);
    cmd.args([
        "--vectors",
        "-",
        "--count",
        &s.count.to_string(),
        "--max-errors",
        &r.max_errors.to_string(),
    ])
    .arg("--table")
    .arg(r.table)
    .args(&env_args);
    if r.bubbles > 0 {
        cmd.args(["--bubbles", &r.bubbles.to_string()]);
    }
    if r.stall > 0 {
        cmd.args(["--stall", &r.stall.to_string()]);
    }
    let mut child = crate::tool::ends_with_gbump(&mut cmd)
        .current_dir(r.cwd)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .map_err(|e| Error::Other(format!("{what}: cannot start {}: {e}", r.exe.display())))?;
    let _registered = crate::interrupt::child(child.id());
    let watchdog = crate::tool::Watchdog::start(child.id(), crate::tool::time_limit()?);
    let mut stdin = child.stdin.take().expect("piped");
    let stdout = child.stdout.take().expect("piped");
    let stderr = child.stderr.take().expect("piped");
    let chunks = s.chunks();
    let steps = chunks.min(100);
    let progress = r
        .progress
        .then(|| crate::progress::Progress::new(&format!("stream {}", s.set), steps));
    // Chunks in flight: a batch being encoded and two waiting for the pipe.
    let batch = 2 * rayon::current_num_threads() as u64;
    let (tx, rx) = std::sync::mpsc::sync_channel::<(u64, Vec<u8>)>(2 * batch as usize);
    let (ok, log, digest) = std::thread::scope(|scope| -> Result<(bool, String, crate::vectors::digest::Digest)> {
        let out = scope.spawn(move || crate::tool::read_capped(stdout));
        let err = scope.spawn(move || crate::tool::read_capped(stderr));
        let progress = &progress;
        let record_bytes = maker.layout.bytes();
        let writer = scope.spawn(move || {
            let (mut sent, mut shown) = (0u64, 0u64);
            // What the harness's digest of the records it checks must be.
            let mut digest = crate::vectors::digest::Digest::default();
            for (records, bytes) in rx {
                digest.records(&bytes, record_bytes);
                // A harness that stopped reading (after --max-errors mismatches) ends the stream.
                if stdin.write_all(&bytes).is_err() {
                    return digest;
                }
                sent += records;
                while let Some(p) = progress.as_ref().filter(|_| (shown + 1) * s.count <= sent * steps) {
                    shown += 1;
                    p.done(&format!("{sent} of {} records", s.count));
                }
            }
            digest
        });
        let mut c0 = 0;
        let mut result = Ok(());
        'feed: while c0 < chunks {
            if let Err(e) = crate::interrupt::check() {
                result = Err(e);
                break;
            }
            let c1 = (c0 + batch).min(chunks);
            let done: Result<Vec<(u64, Vec<u8>)>> = (c0..c1)
                .into_par_iter()
                .map(|c| {
                    let b = s.chunk_bytes(&maker, c)?;
                    Ok(((b.len() / maker.layout.bytes()) as u64, b))
                })
                .collect();
            let done = match done {
                Ok(d) => d,
                Err(e) => {
                    result = Err(e);
                    break;
                }
            };
            for d in done {
                if tx.send(d).is_err() {
                    break 'feed;
                }
            }
            c0 = c1;
        }
        drop(tx);
        let digest = writer.join().unwrap_or_default();
        if result.is_err() {
            let _ = child.kill();
        }
        let status = child.wait().map_err(|e| Error::Other(format!("{what}: {e}")))?;
        let mut log = String::from_utf8_lossy(&out.join().unwrap_or_default()).into_owned();
        log += &String::from_utf8_lossy(&err.join().unwrap_or_default());
        crate::tool::ended(&what, &r.exe.display().to_string(), status, watchdog, &mut log)?;
        result?;
        Ok((status.success(), log, digest))
    })?;
    let out = super::outcome(ok, log, t0.elapsed().as_secs_f64(), &what)?;
    super::regress::every_record(out, s.count, digest, &what)
}

/// Run `o`'s Verilator regression on `src`, streamed: the table and totals to `say` as
/// `gbump regress` prints them, the XML to `junit`, and for a failing run the seed and record
/// to replay. `lock` takes the work folder once the source is checked.
pub fn regress_stream(
    cfg: &PipelineConfig,
    pick_args: &str,
    src: &StreamSource,
    o: &RegressOptions,
    junit: Option<&Path>,
    lock: impl FnOnce() -> Result<WorkLock>,
    say: &mut dyn FnMut(&str) -> Result<()>,
) -> Result<()> {
    // A stream that fails or is stopped before its table leaves no earlier report behind.
    super::regress_cmd::reporting(cfg, junit, |reported| {
        super::require(Sim::Verilator)?;
        // A signal ends the stream through its error path: the harness stops, the seed is said.
        let _cleanup = crate::interrupt::cleanup();
        let streams = streams(cfg, src, o.seed, o.scene_size)?;
        if let Some(j) = junit {
            crate::render::output::check_writable(j)?;
        }
        let _lock = lock()?;
        let h = &cfg.hash()[..8];
        let exe = regress_harness(cfg, pick_args, &o.work)?;
        let mut results = Vec::new();
        let mut replays = Vec::new();
        for s in &streams {
            let table = power_table(cfg, &o.work.join(format!("stream_{h}")), s.shininess, &o.command)?;
            let run = StreamRun {
                exe: &exe,
                table: &table,
                cwd: &o.work,
                max_errors: o.max_errors,
                bubbles: o.bubbles,
                stall: o.stall,
                progress: true,
            };
            let mut outcome = run_stream(cfg, s, &run).map_err(|e| e.to_string());
            // A signal that stopped the harness too is the user's stop, not a failing RTL run.
            crate::interrupt::check()?;
            let failing = match &mut outcome {
                Ok(out) if out.failed > 0 => Some(first_failing_record(&out.log)),
                Ok(_) => None,
                Err(e) if e.starts_with("interrupted") => return Err(Error::Other(e.clone())),
                Err(e) => Some(first_failing_record(e)),
            };
            if let Some(k) = failing {
                let line = format!("replay {}: {}", s.set, s.replay(pick_args, k));
                if let Ok(out) = &mut outcome {
                    out.log += &format!("\n{line}\n");
                }
                replays.push(line);
            }
            results.push(RunResult {
                sim: Sim::Verilator,
                set: s.set.clone(),
                target: "top".into(),
                outcome,
            });
        }
        let t = super::summary::table(&results, say)?;
        if let Some(j) = junit {
            crate::render::output::write_atomic(j, super::summary::junit(cfg, &results).as_bytes())?;
            *reported = true;
        }
        for r in &replays {
            say(r)?;
        }
        super::summary::verdict(cfg, " (streamed)", &t, say)
    })
}

/// The harness a streamed regression of `cfg` (selected by `pick_args`) builds in `work`:
/// its RTL in `work/rtl_HASH`, the build cached under `work/build`.
pub fn regress_harness(cfg: &PipelineConfig, pick_args: &str, work: &Path) -> Result<PathBuf> {
    build(cfg, work, &super::rtl_files::regression_rtl(cfg, pick_args, work)?)
}

/// The harness of `cfg`'s top, cached under `work/build`.
pub fn build(cfg: &PipelineConfig, work: &Path, rtl: &super::rtl_files::Rtl) -> Result<PathBuf> {
    let top = crate::rtlgen::units_v::module_name(cfg, "gbump_pipeline");
    Verilator.build_harness(&work.join("build"), &top, &crate::sim::testbench::harness_top(cfg), rtl)
}

/// The power table for shininess `n` in `dir` (a ROM file, not vectors: the harness loads it
/// through the load port as a file-based run does).
pub fn power_table(cfg: &PipelineConfig, dir: &Path, n: u32, command: &str) -> Result<PathBuf> {
    use crate::rtlgen::rom;
    crate::render::output::make_folder(dir)?;
    let p = dir.join(format!("power_table_n{n}.hex"));
    let r = rom::power_rom(cfg, n);
    let text = rom::write(
        &r,
        rom::RomFormat::Hex,
        &rom::rom_header(&r, Some(cfg), command, "power table of a streamed run"),
    );
    crate::render::output::write_atomic(&p, text.as_bytes())?;
    Ok(p)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::vectors::sources::random_chunk;

    /// Chunk c of a random stream is chunk 0 of the stream its replay names, so the short
    /// replay file holds the failing record.
    #[test]
    fn a_chunk_replays_as_the_first_chunk_of_its_own_seed() {
        let cfg = PipelineConfig::default();
        let (seed, c) = (0xDEAD_BEEF_u64, 5u64);
        let n = c * RANDOM_CHUNK + 1000;
        let s = &streams(&cfg, &StreamSource::Random(n), seed, None).unwrap()[0];
        let k = c * RANDOM_CHUNK + 777;
        let hint = s.replay("--config x.toml", Some(k));
        let seed_c = chunk_rng(seed, c).0;
        assert!(
            hint.contains(&format!("--source random:1000 --seed {seed_c}")) && hint.contains("record 777 of"),
            "{hint}"
        );
        assert!(hint.contains(&format!("seed {seed}, record {k}")), "{hint}");
        assert_eq!(random_chunk(&cfg, seed, c, n), random_chunk(&cfg, seed_c, 0, 1000));
    }

    #[test]
    fn sources_are_checked() {
        assert_eq!(StreamSource::parse("random:1_000").unwrap(), StreamSource::Random(1000));
        assert_eq!(StreamSource::parse("corners").unwrap(), StreamSource::Corners);
        let max = crate::limits::MAX_STREAM_VECTORS;
        assert!(StreamSource::parse(&format!("random:{max}")).is_ok());
        for bad in [
            "random:0",
            &format!("random:{}", max + 1),
            "random:x",
            "exhaustive:dot_clamp",
            "nope",
            "scene:",
        ] {
            let e = StreamSource::parse(bad).unwrap_err().to_string();
            assert!(e.contains("fix:"), "{bad}: {e}");
        }
    }

    #[test]
    fn the_first_failing_record_is_read_from_the_log() {
        let log = "x\nMISMATCH unit gbump_pipeline vector 1234:\n  in_c 3\nMISMATCH unit gbump_pipeline vector 99:\n";
        assert_eq!(first_failing_record(log), Some(1234));
        let t = "MISMATCH unit gbump_pipeline timing: latency: 3 rising edges, the interface states 9 (vector 17, edge 40)";
        assert_eq!(first_failing_record(t), Some(17));
    }
}
