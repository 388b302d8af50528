//! External programs (simulators, Yosys, nextpnr): whether one is installed, the message that
//! says how to install it, and running one with its log. Every spawn of a tool goes through
//! `run_cmd`, so Ctrl-C, a missing program and a child killed by a signal read the same
//! everywhere.

use crate::error::{Error, Result};
use crate::limits::{MAX_TOOL_TIMEOUT_SECONDS, TOOL_PROBE_SECONDS};
use std::process::Command;

/// Why `prog` cannot be used, as a table cell says it: None when it runs (and answers
/// `--version` or `-V` within [`PROBE_LIMIT`]); an optional tool's absence is reported, not
/// an error, but a hung one is not called missing.
pub fn unusable(prog: &str) -> Option<&'static str> {
    match probe(prog) {
        Probe::Runs => None,
        Probe::Missing => Some("not installed"),
        Probe::Hung => Some("hangs answering --version"),
    }
}

/// Error unless `prog` is installed and answers (and the tool time limit, which every run
/// of it will have, is valid: a bad one is refused before the command's work).
pub fn require(prog: &str) -> Result<()> {
    time_limit()?;
    match probe(prog) {
        Probe::Runs => Ok(()),
        Probe::Missing => Err(missing(prog)),
        Probe::Hung => Err(Error::Other(format!(
            "{prog} did not answer `{prog} --version` within {} s: the program of that name on PATH hangs\n  fix: reinstall it (scripts/install-tools.sh from gbump's repository), or put the right one first on PATH",
            PROBE_LIMIT.as_secs()
        ))),
    }
}

/// How long a tool may take to answer `--version`.
pub const PROBE_LIMIT: std::time::Duration = std::time::Duration::from_secs(TOOL_PROBE_SECONDS);

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Probe {
    Runs,
    Missing,
    /// Started, but did not end within [`PROBE_LIMIT`].
    Hung,
}

fn probe(prog: &str) -> Probe {
    for flag in ["--version", "-V"] {
        // Its output is not read: a process it leaves behind holding a pipe cannot hold the
        // probe open.
        let Ok(mut child) = ends_with_gbump(&mut Command::new(prog))
            .arg(flag)
            .stdin(std::process::Stdio::null())
            .stdout(std::process::Stdio::null())
            .stderr(std::process::Stdio::null())
            .spawn()
        else {
            continue;
        };
        let watchdog = Watchdog::start(child.id(), Some(PROBE_LIMIT));
        let ended = child.wait().is_ok();
        if watchdog.finish() {
            return Probe::Hung;
        }
        if ended {
            return Probe::Runs;
        }
    }
    Probe::Missing
}

/// `cmd`, set to be killed if gbump dies first. A signal gbump catches ends its tools itself
/// (`interrupt`), but SIGKILL (an OOM killer, a CI runner's hard stop) cannot be caught, and a
/// simulator left behind ran on at full speed with no one to read it. The kernel sends the
/// signal when the thread that started the tool ends; every caller waits for its tool on that
/// thread. It reaches the tool itself, not what the tool started (a compiler job of `make`
/// runs on to its end). The hook makes the start a fork rather than a posix_spawn.
pub fn ends_with_gbump(cmd: &mut Command) -> &mut Command {
    #[cfg(target_os = "linux")]
    {
        use std::os::unix::process::CommandExt;
        let parent = std::process::id() as libc::pid_t;
        // SAFETY: between fork and exec the closure calls only prctl, getppid and _exit, which
        // are async-signal-safe, and allocates nothing.
        unsafe {
            cmd.pre_exec(move || {
                if libc::prctl(libc::PR_SET_PDEATHSIG, libc::SIGKILL) != 0 {
                    return Err(std::io::Error::last_os_error());
                }
                // gbump ended between the fork and the prctl: no signal would come.
                if libc::getppid() != parent {
                    libc::_exit(1);
                }
                Ok(())
            });
        }
    }
    cmd
}

/// The error for a program that is not installed; it says how to install it.
pub fn missing(prog: &str) -> Error {
    let pkg = match prog {
        "vvp" | "iverilog" => "iverilog",
        p => p,
    };
    Error::Other(format!(
        "{prog} is not installed (or not on PATH)\n  fix: run scripts/install-tools.sh from gbump's repository, or apt-get update && apt-get install -y {pkg}"
    ))
}

/// Run a command, capturing stdout and stderr together; `what` names it in errors.
pub fn run_cmd(cmd: &mut Command, what: &str) -> Result<(bool, String, f64)> {
    crate::interrupt::check()?;
    let limit = time_limit()?;
    let t0 = std::time::Instant::now();
    let prog = cmd.get_program().to_string_lossy().into_owned();
    let start_err = |e: std::io::Error| {
        if e.kind() == std::io::ErrorKind::NotFound {
            missing(&prog)
        } else {
            Error::Other(format!("{what}: cannot start {prog}: {e}"))
        }
    };
    let child = ends_with_gbump(cmd)
        .stdin(std::process::Stdio::null())
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .map_err(start_err)?;
    // A signal that ends gbump ends the tool too, rather than leaving it writing on its own.
    let _child = crate::interrupt::child(child.id());
    let watchdog = Watchdog::start(child.id(), limit);
    let out = wait_capped(child).map_err(|e| Error::Other(format!("{what}: {e}")))?;
    let mut log = String::from_utf8_lossy(&out.stdout).into_owned();
    log += &String::from_utf8_lossy(&out.stderr);
    ended(what, &prog, out.status, watchdog, &mut log)?;
    crate::interrupt::check()?;
    Ok((out.status.success(), log, t0.elapsed().as_secs_f64()))
}

/// Bytes kept of the start of one output stream of a tool ([`read_capped`]).
pub const KEPT_HEAD: usize = 1 << 20;
/// Bytes kept of the end of one output stream of a tool ([`read_capped`]): its verdict is there.
pub const KEPT_TAIL: usize = 8 << 20;

/// Read `r` to its end, keeping its first [`KEPT_HEAD`] and its last [`KEPT_TAIL`] bytes (cut
/// at line ends) with a line between them saying how many were left out ([`CUT_NOTE`]): a tool
/// that floods its output (a runaway `$display`, a `yes`) costs about `KEPT_HEAD + 2 KEPT_TAIL`
/// bytes of memory, where reading it whole ran gbump out of memory and aborted it. A verdict
/// that finds the note refuses to call the run clean (`sim::verdict`): what was left out is
/// not read.
pub fn read_capped(mut r: impl std::io::Read) -> Vec<u8> {
    let mut head = Vec::new();
    let mut buf = vec![0u8; 64 << 10];
    // Trimmed once it is twice the kept length, so each byte is moved at most once and the
    // buffer never grows past its first capacity.
    let mut tail = Vec::with_capacity(2 * KEPT_TAIL + buf.len());
    let mut dropped = 0u64;
    let trim = |tail: &mut Vec<u8>, dropped: &mut u64| {
        let mut cut = tail.len() - KEPT_TAIL;
        // From the start of a line, so the kept tail holds whole lines.
        if let Some(nl) = tail[cut..].iter().position(|&b| b == b'\n') {
            cut += nl + 1;
        }
        *dropped += cut as u64;
        tail.drain(..cut);
    };
    loop {
        let n = match r.read(&mut buf) {
            Ok(0) => break,
            Ok(n) => n,
            Err(e) if e.kind() == std::io::ErrorKind::Interrupted => continue,
            Err(_) => break,
        };
        let k = KEPT_HEAD.saturating_sub(head.len()).min(n);
        head.extend_from_slice(&buf[..k]);
        if tail.len() + (n - k) > 2 * KEPT_TAIL {
            trim(&mut tail, &mut dropped);
        }
        tail.extend_from_slice(&buf[k..n]);
    }
    if tail.len() > KEPT_TAIL {
        trim(&mut tail, &mut dropped);
    }
    if dropped > 0 {
        // The head, too, ends at a line end: the rest of its last line is counted as left out.
        if let Some(nl) = head.iter().rposition(|&b| b == b'\n') {
            dropped += (head.len() - nl - 1) as u64;
            head.truncate(nl + 1);
        }
        head.extend_from_slice(format!("\n{CUT_NOTE}{dropped}{CUT_NOTE_END}\n").as_bytes());
    }
    head.extend_from_slice(&tail);
    head
}

/// How [`read_capped`]'s note on the bytes it left out begins and ends (the count between).
pub const CUT_NOTE: &str = "[gbump: ";
const CUT_NOTE_END: &str = " bytes of this output left out here]";

/// [`read_capped`]'s note in `log`, when it cut the output.
pub fn cut_note(log: &str) -> Option<&str> {
    log.lines().find(|l| l.starts_with(CUT_NOTE) && l.ends_with(CUT_NOTE_END))
}

/// [`std::process::Child::wait_with_output`] with each stream read by [`read_capped`]. The
/// pipes are read to their end before the tool is reaped, as `wait_with_output` does: the
/// [`Watchdog`] may signal the tool's pid until then, and a reaped pid can be another
/// process's.
pub fn wait_capped(mut child: std::process::Child) -> std::io::Result<std::process::Output> {
    let (so, se) = (child.stdout.take(), child.stderr.take());
    let (stdout, stderr) = std::thread::scope(|scope| {
        let out = scope.spawn(move || so.map(read_capped).unwrap_or_default());
        let err = scope.spawn(move || se.map(read_capped).unwrap_or_default());
        (out.join().unwrap_or_default(), err.join().unwrap_or_default())
    });
    Ok(std::process::Output {
        status: child.wait()?,
        stdout,
        stderr,
    })
}

/// [`std::process::Command::output`], each stream read by [`read_capped`].
pub fn output(cmd: &mut Command) -> std::io::Result<std::process::Output> {
    let child = ends_with_gbump(cmd)
        .stdin(std::process::Stdio::null())
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()?;
    wait_capped(child)
}

/// The environment variable that limits each tool's run, in seconds (`--tool-timeout` sets
/// the limit for one command instead).
pub const TIME_LIMIT_VAR: &str = "GBUMP_TOOL_TIMEOUT";

/// `--tool-timeout`, when given (checked when the command line is read).
static FLAG_LIMIT: std::sync::OnceLock<std::time::Duration> = std::sync::OnceLock::new();

/// Set the time limit of every tool this process runs from `--tool-timeout` (`None`: the
/// environment's [`TIME_LIMIT_VAR`], else none), refusing a value that is not a positive
/// number of seconds up to `MAX_TOOL_TIMEOUT_SECONDS`.
pub fn set_time_limit(flag: Option<&str>) -> Result<()> {
    if let Some(v) = flag {
        let _ = FLAG_LIMIT.set(limit_of(v, "--tool-timeout ")?);
    }
    Ok(())
}

/// The shortest tool time limit: a limit that rounds to no time at all (`1e-300`) would stop
/// every tool as it starts, which no one means.
pub const MIN_TOOL_TIMEOUT_SECONDS: f64 = 0.001;

/// `text` (as typed, and echoed so) as a time limit.
fn limit_of(text: &str, from: &str) -> Result<std::time::Duration> {
    match text.trim().parse::<f64>() {
        Ok(v) if v.is_finite() && v >= MIN_TOOL_TIMEOUT_SECONDS && v <= MAX_TOOL_TIMEOUT_SECONDS as f64 => {
            Ok(std::time::Duration::from_secs_f64(v))
        }
        _ => Err(Error::Other(format!(
            "{from}{}: a tool time limit is a number of seconds, at least {MIN_TOOL_TIMEOUT_SECONDS} and at most {MAX_TOOL_TIMEOUT_SECONDS} (MAX_TOOL_TIMEOUT_SECONDS)\n  fix: give the longest one simulator, build or synthesis may run, in seconds (e.g. 3600), or leave it out for no limit",
            crate::shell::quoted(text)
        ))),
    }
}

/// The limit a tool about to run has: `--tool-timeout`, else [`TIME_LIMIT_VAR`] (read here,
/// so a bad value fails only a command that runs a tool), else none.
pub fn time_limit() -> Result<Option<std::time::Duration>> {
    if let Some(l) = FLAG_LIMIT.get() {
        return Ok(Some(*l));
    }
    match std::env::var(TIME_LIMIT_VAR) {
        Ok(v) if !v.trim().is_empty() => limit_of(&v, &format!("{TIME_LIMIT_VAR}=")).map(Some),
        _ => Ok(None),
    }
}

/// How long a tool stopped at its time limit has to end after SIGTERM before SIGKILL.
const KILL_GRACE: std::time::Duration = std::time::Duration::from_secs(3);

/// Ends a tool, and every process it started, that runs past its time limit. [`finish`]
/// it (through [`ended`]) as soon as the tool is reaped and its pipes read.
///
/// [`finish`]: Watchdog::finish
pub struct Watchdog {
    limit: Option<std::time::Duration>,
    cancel: Option<std::sync::mpsc::Sender<()>>,
    fired: std::sync::Arc<std::sync::atomic::AtomicBool>,
    thread: Option<std::thread::JoinHandle<()>>,
}

impl Watchdog {
    /// Watch process `pid` under `limit` (nothing, without one).
    pub fn start(pid: u32, limit: Option<std::time::Duration>) -> Watchdog {
        let fired = std::sync::Arc::new(std::sync::atomic::AtomicBool::new(false));
        let Some(limit) = limit else {
            return Watchdog {
                limit,
                cancel: None,
                fired,
                thread: None,
            };
        };
        let (tx, rx) = std::sync::mpsc::channel::<()>();
        let f = fired.clone();
        let thread = std::thread::spawn(move || {
            use std::sync::mpsc::RecvTimeoutError::Timeout;
            if rx.recv_timeout(limit) != Err(Timeout) {
                return;
            }
            f.store(true, std::sync::atomic::Ordering::SeqCst);
            #[cfg(unix)]
            {
                // The processes found now are killed later even if the tool itself has gone
                // by then (a child that ignored SIGTERM, now an orphan, holding its pipes).
                let tree = crate::interrupt::end_tree(pid, libc::SIGTERM);
                // Each process with its start time, so that a pid reused by another process
                // once this one is reaped (by init, for an orphan) is never signalled.
                let tree: Vec<(u32, Option<u64>)> = tree.into_iter().map(|p| (p, crate::interrupt::started(p))).collect();
                let deadline = std::time::Instant::now() + KILL_GRACE;
                let kill = |p: u32| {
                    // SAFETY: a plain kill(2) of a process of the tool's tree: the tool itself
                    // (unreaped until this thread is told), or one that still runs as the
                    // process it was (`running` compares its start time).
                    unsafe {
                        libc::kill(p as libc::pid_t, libc::SIGKILL);
                    }
                };
                if rx.recv_timeout(KILL_GRACE) == Err(Timeout) {
                    kill(pid);
                }
                // The rest of the tree, whether or not the tool ended in its grace period:
                // the tool's end does not wait for what it started. Each gets what is left of
                // the grace period, then SIGKILL, so nothing of a stopped tool outlives the
                // run (a flaky test saw the tool's `sleep` alive after gbump had exited).
                let ends_by = |p: u32, start: Option<u64>, by: std::time::Instant| {
                    while crate::interrupt::running(p, start) && std::time::Instant::now() < by {
                        std::thread::sleep(std::time::Duration::from_millis(5));
                    }
                };
                for (p, start) in tree.into_iter().filter(|&(p, _)| p != pid) {
                    ends_by(p, start, deadline);
                    if crate::interrupt::running(p, start) {
                        kill(p);
                        ends_by(p, start, std::time::Instant::now() + KILL_GRACE);
                    }
                }
            }
        });
        Watchdog {
            limit: Some(limit),
            cancel: Some(tx),
            fired,
            thread: Some(thread),
        }
    }

    /// Stop watching (the tool has ended); whether it was stopped at the limit.
    pub fn finish(mut self) -> bool {
        self.stop();
        self.fired.load(std::sync::atomic::Ordering::SeqCst)
    }

    fn stop(&mut self) {
        drop(self.cancel.take());
        if let Some(t) = self.thread.take() {
            let _ = t.join();
        }
    }
}

impl Drop for Watchdog {
    fn drop(&mut self) {
        self.stop();
    }
}

/// How tool `prog` (run for `what`), reaped with `status` and its output read whole into
/// `log`, ended, with its `watchdog` finished here (the tool is gone, and every pipe it held
/// closed): past the time limit, an error; by a signal, a line on `log`, or the user's stop
/// when the same signal reached gbump (`interrupt::settle`).
pub fn ended(what: &str, prog: &str, status: std::process::ExitStatus, watchdog: Watchdog, log: &mut String) -> Result<()> {
    let limit = watchdog.limit;
    if watchdog.finish() {
        let secs = limit.map_or(0.0, |l| l.as_secs_f64());
        return Err(Error::Other(format!(
            "{what}: {prog} ran for more than the tool time limit ({secs} s, --tool-timeout or {TIME_LIMIT_VAR}) and was stopped; the end of its output:\n{}\n  fix: if the run is only long (many vectors, a large design), raise the limit; a tool that does not end on a small run is hung: run it again, and report it with the command if it hangs again",
            tail(log, 10)
        )));
    }
    // A child killed by a signal (a crash, or Ctrl-C reaching the whole process group).
    #[cfg(unix)]
    {
        use std::os::unix::process::ExitStatusExt;
        if let Some(sig) = status.signal() {
            crate::interrupt::settle(sig)?;
            *log += &format!("\n{what}: killed by signal {sig}");
        }
    }
    #[cfg(not(unix))]
    let _ = status;
    Ok(())
}

/// The last `n` lines of a log, for error messages.
pub fn tail(log: &str, n: usize) -> String {
    let lines: Vec<&str> = log.lines().collect();
    lines[lines.len().saturating_sub(n)..].join("\n")
}

/// Where `tool` is on PATH (the first executable match, the one a search of PATH runs),
/// for messages about which one ran.
pub fn on_path(tool: &str) -> Option<std::path::PathBuf> {
    first_executable(tool, &std::env::var_os("PATH")?)
}

/// [`on_path`] in the folders of `path`.
fn first_executable(tool: &str, path: &std::ffi::OsStr) -> Option<std::path::PathBuf> {
    use std::os::unix::fs::PermissionsExt;
    std::env::split_paths(path)
        .map(|d| d.join(tool))
        .find(|p| p.metadata().is_ok_and(|m| m.is_file() && m.permissions().mode() & 0o111 != 0))
}

/// The last `n` lines of a failed tool's `log`, or a line saying it printed nothing (a
/// message with an empty gap where the reason goes reads as a gbump bug).
pub fn log_tail(tool: &str, log: &str, n: usize) -> String {
    if log.trim().is_empty() {
        format!("({tool} printed nothing)")
    } else {
        tail(log, n)
    }
}

/// Where `tool` runs from, for a message: its path on PATH, or that it is not there.
pub fn located(tool: &str) -> String {
    on_path(tool).map_or("not found on PATH".to_string(), |p| p.display().to_string())
}

/// A tool that exited 0 without the output that proves it did its work (`evidence` says
/// which): a lint or check that looked at nothing is not clean.
pub fn did_not_run(tool: &str, evidence: &str, log: &str) -> String {
    let at = located(tool);
    format!(
        "{tool} ({at}) exited 0 but did not do its work ({evidence}, and it did not){}\n  fix: it is not a working {tool}: reinstall it (scripts/install-tools.sh) or put a working one first on PATH",
        if log.trim().is_empty() { String::new() } else { format!(":\n{}", tail(log, 10)) }
    )
}

/// The fix line of a failed run of `tool` that printed nothing: it is not the tool gbump
/// knows, or it is broken.
pub fn silent_fix(tool: &str) -> String {
    let at = located(tool);
    format!("  fix: {tool} ({at}) failed without a word and made none of its outputs: it is not a working {tool}; reinstall it (scripts/install-tools.sh) or put a working one first on PATH")
}

/// The fix line of a tool that failed because of the machine, not the sources: a full disk,
/// a file-size limit, an unusable TMPDIR, a folder it may not write. None when `log` shows
/// none of these.
pub fn environment_fix(tool: &str, log: &str) -> Option<String> {
    let has = |keys: &[&str]| keys.iter().any(|k| log.contains(k));
    Some(if has(&["No space left on device", "Disk quota exceeded"]) {
        format!("  fix: {tool} ran out of disk space (the lines above): free space on the work folder's disk and on TMPDIR's (`df -h`), or give --work on a larger disk, and run again")
    } else if has(&["File size limit exceeded", "File too large"]) {
        format!("  fix: a file-size limit (`ulimit -f`) stopped {tool} (the lines above): raise it and run again")
    } else if has(&["TMPDIR", "temporary file", "mkstemp"]) {
        let at = std::env::var("TMPDIR").map_or("unset: /tmp".to_string(), |t| format!("`{t}`"));
        format!("  fix: {tool} could not write its temporary files (TMPDIR is {at}): point TMPDIR at a writable folder with room, and run again")
    } else if has(&["Permission denied", "Read-only file system"]) {
        format!("  fix: {tool} may not write a file it needs (the lines above): check the work folder's permissions, and run again")
    } else {
        return None;
    })
}

/// The fix line of a synthesis by Yosys that failed with `log`.
pub fn synthesis_fix(log: &str) -> String {
    if log.trim().is_empty() {
        silent_fix("yosys")
    } else if let Some(fix) = environment_fix("yosys", log) {
        fix
    } else if ["killed by signal", "out of memory", "Killed"].iter().any(|k| log.contains(k)) {
        "  fix: yosys was killed (a crash, or memory ran out): check free memory, reinstall it if it happens again (scripts/install-tools.sh), and run again".into()
    } else {
        "  fix: yosys refused the design for the reasons above; gbump's RTL synthesises on the version scripts/install-tools.sh installs, so an error in it is a gbump bug: report it with the configuration".into()
    }
}

/// The fix line of a build by `tool` that failed with `log`: a tool that crashed is reinstalled;
/// one that refused the sources names what it refused in the log above the line.
pub fn build_fix(tool: &str, log: &str) -> String {
    if log.trim().is_empty() {
        return silent_fix(tool);
    }
    if let Some(fix) = environment_fix(tool, log) {
        return fix;
    }
    // make found nothing to build: the tool before it wrote no makefile and said why nowhere.
    if log.contains("No targets") && !log.contains("%Error") {
        let at = located(tool);
        return format!("  fix: make found no makefile: {tool} ({at}) wrote none of its outputs without an error of its own; check the work folder's free disk space (`df -h`) and that `{tool} --version` answers, reinstall it if need be (scripts/install-tools.sh), and run again");
    }
    // Killed itself, or a compiler it ran (gcc's "Killed signal terminated program cc1plus"
    // when memory ran out).
    if ["killed by signal", "Killed signal", "fatal error: Killed", "out of memory"]
        .iter()
        .any(|k| log.contains(k))
    {
        format!("  fix: {tool} or a compiler it ran was killed (a crash, or memory ran out): check free memory, reinstall it if it happens again (scripts/install-tools.sh), and run again")
    } else if !log.contains("%Error")
        && !log.lines().any(|l| l.contains("error") && l.contains("harness.cpp"))
        && log.contains("make")
        && log.contains("Error")
    {
        // Verilator took the sources (its own errors start with %Error) and gbump's own C++
        // (the harness) is not what the compiler refused: the C++ build of the model failed
        // on the machine's compiler or make, not on the RTL.
        format!("  fix: {tool} accepted the sources, but the C++ compiler or make it ran failed (the lines above): check that `${{CXX:-g++}} --version` answers and compiles a file, that CXX names a working compiler, and that the work folder's disk has room; scripts/install-tools.sh installs a known-good g++")
    } else {
        format!("  fix: {tool} refused the sources for the reasons above; gbump's own RTL and testbenches compile on the versions scripts/install-tools.sh installs, so an error in them is a gbump bug: report it with the configuration")
    }
}

#[cfg(test)]
mod tests {
    /// A failed build's fix names what failed: Verilator's own error (gbump's sources), the
    /// compiler or make it ran (the machine), or a kill (memory).
    #[test]
    fn a_build_fix_names_what_failed() {
        // The machine, not the sources: never called a gbump bug.
        for (log, says) in [
            ("ld: final link failed: No space left on device\nmake: *** Error 1", "disk space"),
            ("OSError: [Errno 28] No space left on device", "disk space"),
            ("iverilog: Please check TMP or TMPDIR", "TMPDIR"),
            ("sh: line 1: 123 File size limit exceeded", "ulimit -f"),
            ("make: *** No targets.  Stop.", "make found no makefile"),
        ] {
            let fix = super::build_fix("verilator", log);
            assert!(fix.contains(says) && !fix.contains("bug: report"), "{log}: {fix}");
        }
        assert!(super::synthesis_fix("ERROR: No space left on device").contains("disk space"));
        let ours = super::build_fix("verilator", "%Error: top.v:3: syntax error\n%Error: Exiting due to 1 error(s)");
        assert!(ours.contains("bug: report it"), "{ours}");
        let cxx = super::build_fix(
            "verilator",
            "g++: error: unrecognized command-line option\nmake: *** [Vtop__ALL.o] Error 1\nmake: *** Waiting for unfinished jobs",
        );
        assert!(cxx.contains("C++ compiler") && !cxx.contains("bug: report it"), "{cxx}");
        // gbump's own C++ refused by the compiler is gbump's to fix.
        let harness = super::build_fix(
            "verilator",
            "../harness.cpp:12:5: error: 'foo' was not declared in this scope\nmake: *** [harness.o] Error 1",
        );
        assert!(harness.contains("bug: report it"), "{harness}");
        let killed = super::build_fix("verilator", "g++: fatal error: Killed signal terminated program cc1plus");
        assert!(killed.contains("memory"), "{killed}");
    }

    /// A file of the tool's name without an execute bit is passed over, as a search of PATH
    /// passes it over, so a message names the one that ran.
    #[test]
    fn the_tool_on_path_is_the_first_executable() {
        use std::os::unix::fs::PermissionsExt;
        let dir = tempfile::tempdir().unwrap();
        let (a, b) = (dir.path().join("a"), dir.path().join("b"));
        for (d, mode) in [(&a, 0o644), (&b, 0o755)] {
            std::fs::create_dir(d).unwrap();
            std::fs::write(d.join("tooly"), "#!/bin/sh\n").unwrap();
            std::fs::set_permissions(d.join("tooly"), std::fs::Permissions::from_mode(mode)).unwrap();
        }
        let path = std::env::join_paths([&a, &b]).unwrap();
        assert_eq!(super::first_executable("tooly", &path), Some(b.join("tooly")));
        assert_eq!(super::first_executable("absent", &path), None);
    }

    /// An optional tool is named missing only when it is: one that hangs on `--version` says
    /// so (after the probe's limit), one that answers is usable.
    #[test]
    fn an_unusable_tool_says_why() {
        let dir = tempfile::tempdir().unwrap();
        let script = |name: &str, body: &str| {
            use std::os::unix::fs::PermissionsExt;
            let p = dir.path().join(name);
            std::fs::write(&p, format!("#!/bin/sh\n{body}\n")).unwrap();
            std::fs::set_permissions(&p, std::fs::Permissions::from_mode(0o755)).unwrap();
            p.to_str().unwrap().to_string()
        };
        assert_eq!(super::unusable(&dir.path().join("absent").to_string_lossy()), Some("not installed"));
        assert_eq!(super::unusable(&script("answers", "echo 1.0")), None);
        assert_eq!(
            super::unusable(&script("hangs", "exec sleep 60")),
            Some("hangs answering --version")
        );
    }

    /// A flood keeps its first and last bytes and says how many went between them; a short
    /// output is kept whole.
    #[test]
    fn output_is_kept_head_and_tail() {
        let short = b"3 passed, 0 failed\n".to_vec();
        assert_eq!(super::read_capped(&short[..]), short);
        let mut flood = Vec::new();
        let mut i = 0;
        while flood.len() < super::KEPT_HEAD + 3 * super::KEPT_TAIL {
            flood.extend_from_slice(format!("MISMATCH line {i}\n").as_bytes());
            i += 1;
        }
        let kept = super::read_capped(&flood[..]);
        let text = String::from_utf8(kept.clone()).unwrap();
        let (head, rest) = text.split_once(&format!("\n{}", super::CUT_NOTE)).expect("the note");
        let (count, tail) = rest.split_once(" bytes of this output left out here]\n").expect("the note's end");
        // Whole lines on both sides, the head the flood's start and the tail its end.
        assert!(flood.starts_with(head.as_bytes()) && head.ends_with('\n'));
        assert!(flood.ends_with(tail.as_bytes()) && tail.starts_with("MISMATCH line "));
        assert!(head.len() <= super::KEPT_HEAD && tail.len() <= super::KEPT_TAIL && tail.len() > super::KEPT_TAIL - 100);
        assert_eq!(head.len() + count.parse::<usize>().unwrap() + tail.len(), flood.len());
    }
}
