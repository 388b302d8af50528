//! Ctrl-C, SIGTERM and SIGHUP (a CI runner's timeout, a closed terminal). Where a run holds a
//! [`Cleanup`] (writing vector files, output folders, a streamed regression), the first
//! signal sets a flag that its loops check, so they stop through their normal error path and
//! remove what they wrote; a second exits at once (unless it comes within [`SAME_STOP`] of
//! the first: the same stop, sent to the process and to its group), and so does the first
//! after [`STOP_GRACE`] when the run is blocked where no loop looks. An exit at once removes
//! whatever is still under this process's temporary names. Anywhere else the first exits at once, as
//! the signal's default would, so a long computation is not finished only to be thrown away.
//! A signal that was ignored when gbump started (`nohup`'s SIGHUP) stays ignored.

use crate::error::{Error, Result};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};

static INTERRUPTED: AtomicBool = AtomicBool::new(false);
/// Set once the handler has decided (the run stops through its error path: `INTERRUPTED`
/// is set): a tool the same signal ended may be seen ended before that, so `settle` waits
/// for the decision, not a flag still on its way.
static HANDLED: AtomicBool = AtomicBool::new(false);
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

/// End every process this one started, children and theirs (Verilator's make and compiler),
/// with SIGTERM. The tools share gbump's process group, so a terminal's Ctrl-C or a runner
/// killing the group reaches them anyway; a signal sent to gbump alone (`kill`, a runner's
/// timeout) reaches them only through this.
#[cfg(target_os = "linux")]
fn end_descendants() {
    end_tree(std::process::id(), libc::SIGTERM);
}

/// After a stop signal, as the run exits: SIGKILL whatever it started that outlived the
/// SIGTERM it got at the signal (a tool that ignores SIGTERM would go on, orphaned).
pub fn kill_remaining() {
    if interrupted() {
        kill_tree();
    }
}

/// End every process this one started (and theirs), whatever the reason for stopping.
pub fn kill_tree() {
    #[cfg(target_os = "linux")]
    end_tree(std::process::id(), libc::SIGKILL);
}

/// Send `signal` to every process under `root` (its children and theirs), and to `root`
/// itself unless it is this process; the processes signalled.
#[cfg(target_os = "linux")]
pub fn end_tree(root: u32, signal: libc::c_int) -> Vec<u32> {
    let me = std::process::id();
    // (pid, parent) of every process.
    let procs: Vec<(u32, u32)> = std::fs::read_dir("/proc")
        .into_iter()
        .flatten()
        .flatten()
        .filter_map(|e| {
            let pid: u32 = e.file_name().to_str()?.parse().ok()?;
            let ppid = stat(pid)?.get(STAT_PPID)?.parse().ok()?;
            Some((pid, ppid))
        })
        .collect();
    let mut found = vec![root];
    let mut i = 0;
    while i < found.len() {
        let parent = found[i];
        found.extend(procs.iter().filter(|p| p.1 == parent).map(|p| p.0));
        i += 1;
    }
    found.retain(|&p| p != me);
    for &pid in &found {
        // SAFETY: a plain kill(2) of a process this run started (directly or through a tool).
        unsafe {
            libc::kill(pid as libc::pid_t, signal);
        }
    }
    found
}

/// Process `pid`'s `/proc/PID/stat` fields from its state on ("pid (comm) state ppid ...";
/// comm may hold spaces and parentheses, so the fields are read after its last `)`).
#[cfg(target_os = "linux")]
fn stat(pid: u32) -> Option<Vec<String>> {
    let text = std::fs::read_to_string(format!("/proc/{pid}/stat")).ok()?;
    Some(text.rsplit_once(')')?.1.split_whitespace().map(str::to_string).collect())
}

/// Places in [`stat`]'s fields: the state (field 3 of the file), the parent (4) and the
/// start time (22).
#[cfg(target_os = "linux")]
const STAT_STATE: usize = 0;
#[cfg(target_os = "linux")]
const STAT_PPID: usize = 1;
#[cfg(target_os = "linux")]
const STAT_START: usize = 19;

/// When process `pid` started (clock ticks since boot): with the pid, it names one process,
/// where a pid alone may be reused once the process is reaped.
#[cfg(target_os = "linux")]
pub fn started(pid: u32) -> Option<u64> {
    stat(pid)?.get(STAT_START)?.parse().ok()
}

/// Whether process `pid`, started at `start` ([`started`]), still runs: a zombie, waiting to
/// be reaped, has ended, and a process that took its pid since is another one. No start time
/// means the process had ended when it was read: whatever has the pid now is another.
#[cfg(target_os = "linux")]
pub fn running(pid: u32, start: Option<u64>) -> bool {
    stat(pid).is_some_and(|f| {
        let state = f.get(STAT_STATE).map_or("", |s| s.as_str());
        let same = start.is_some() && f.get(STAT_START).and_then(|s| s.parse().ok()) == start;
        same && !(state.starts_with('Z') || state.starts_with('X'))
    })
}

/// Where the process table cannot be read, a start time is not known.
#[cfg(all(unix, not(target_os = "linux")))]
pub fn started(_pid: u32) -> Option<u64> {
    None
}

/// Whether process `pid` still exists.
#[cfg(all(unix, not(target_os = "linux")))]
pub fn running(pid: u32, _start: Option<u64>) -> bool {
    // SAFETY: signal 0 only checks that the process exists.
    unsafe { libc::kill(pid as libc::pid_t, 0) == 0 }
}

/// `root` alone where the process tree cannot be read.
#[cfg(all(unix, not(target_os = "linux")))]
pub fn end_tree(root: u32, signal: libc::c_int) -> Vec<u32> {
    // SAFETY: a plain kill(2) of a tool this run started and still waits for.
    unsafe {
        libc::kill(root as libc::pid_t, signal);
    }
    vec![root]
}

#[cfg(not(target_os = "linux"))]
fn end_descendants() {
    #[cfg(unix)]
    for pid in CHILDREN.lock().map(|c| c.clone()).unwrap_or_default() {
        // SAFETY: a plain kill(2) of a tool this run started and still waits for.
        unsafe {
            libc::kill(pid as libc::pid_t, libc::SIGTERM);
        }
    }
}

impl Drop for Child {
    fn drop(&mut self) {
        if let Ok(mut c) = CHILDREN.lock() {
            c.retain(|&p| p != self.0);
        }
    }
}

/// How long a run stopping through its error path may take before the signal ends it.
pub const STOP_GRACE: std::time::Duration = std::time::Duration::from_secs(10);

/// Exit as a signal's default would, removing what is still under a temporary name (the
/// run's own cleanup does not get to run) and saying what is left behind.
fn stop_now() -> ! {
    kill_tree();
    crate::temp_files::remove_own();
    eprintln!("gbump: interrupted: stopped (outputs written so far are complete files; temporary files were removed)");
    std::process::exit(exit_status());
}

/// The first stop signal's number (0: none yet), so the exit status is the shell's 128 + n
/// (130 for SIGINT, 143 for SIGTERM, 129 for SIGHUP), as a process the signal ended would give.
static SIGNAL: std::sync::atomic::AtomicI32 = std::sync::atomic::AtomicI32::new(0);

/// The exit status of a run a signal stopped: 128 + the signal's number (130 when not known).
pub fn exit_status() -> i32 {
    match SIGNAL.load(Ordering::SeqCst) {
        0 => 130,
        n => 128 + n,
    }
}

/// The handler `ctrlc` installed for each of SIGHUP, SIGINT and SIGTERM (its address and
/// flags), called after the number is recorded.
#[cfg(unix)]
static CHAINED_AT: [std::sync::atomic::AtomicUsize; 3] = [const { std::sync::atomic::AtomicUsize::new(0) }; 3];
#[cfg(unix)]
static CHAINED_FLAGS: [std::sync::atomic::AtomicI32; 3] = [const { std::sync::atomic::AtomicI32::new(0) }; 3];

#[cfg(unix)]
fn slot(sig: libc::c_int) -> Option<usize> {
    [libc::SIGHUP, libc::SIGINT, libc::SIGTERM].iter().position(|&s| s == sig)
}

/// Put a handler before `ctrlc`'s for `sig` that records the signal's number (`ctrlc` calls
/// its closure without it) and then runs `ctrlc`'s, which only wakes its thread.
#[cfg(unix)]
fn record_signal_number(sig: libc::c_int) {
    extern "C" fn first(sig: libc::c_int, info: *mut libc::siginfo_t, ctx: *mut libc::c_void) {
        // Async-signal-safe: atomics and a call through a plain function pointer.
        let _ = SIGNAL.compare_exchange(0, sig, Ordering::SeqCst, Ordering::SeqCst);
        let Some(k) = slot(sig) else { return };
        let at = CHAINED_AT[k].load(Ordering::SeqCst);
        if at == libc::SIG_IGN {
            return;
        }
        if at == libc::SIG_DFL {
            // What the signal would have done: end the process (signal and raise are
            // async-signal-safe).
            // SAFETY: restores the default disposition and sends the signal again.
            unsafe {
                libc::signal(sig, libc::SIG_DFL);
                libc::raise(sig);
            }
            return;
        }
        if CHAINED_FLAGS[k].load(Ordering::SeqCst) & libc::SA_SIGINFO != 0 {
            // SAFETY: `at` is the handler the kernel would have called with these arguments.
            let f: extern "C" fn(libc::c_int, *mut libc::siginfo_t, *mut libc::c_void) = unsafe { std::mem::transmute(at) };
            f(sig, info, ctx);
        } else {
            // SAFETY: as above, a handler of one argument (no SA_SIGINFO).
            let f: extern "C" fn(libc::c_int) = unsafe { std::mem::transmute(at) };
            f(sig);
        }
    }
    let Some(k) = slot(sig) else { return };
    // SAFETY: reads the installed action, then installs one that calls it; the old one's
    // address and flags are stored before the new handler can run.
    unsafe {
        let mut old: libc::sigaction = std::mem::zeroed();
        if libc::sigaction(sig, std::ptr::null(), &mut old) != 0 {
            return;
        }
        CHAINED_AT[k].store(old.sa_sigaction, Ordering::SeqCst);
        CHAINED_FLAGS[k].store(old.sa_flags, Ordering::SeqCst);
        let mut new: libc::sigaction = std::mem::zeroed();
        new.sa_sigaction = first as extern "C" fn(libc::c_int, *mut libc::siginfo_t, *mut libc::c_void) as usize;
        new.sa_flags = libc::SA_SIGINFO | (old.sa_flags & libc::SA_RESTART);
        new.sa_mask = old.sa_mask;
        libc::sigaction(sig, &new, std::ptr::null_mut());
    }
}

/// A second signal this soon after the first is the same stop, not a second request: GNU
/// `timeout` and process managers signal the process and then its group, milliseconds
/// apart, and that pair must not cut the run's own cleanup short.
pub const SAME_STOP: std::time::Duration = std::time::Duration::from_secs(1);
static FIRST_SIGNAL: std::sync::OnceLock<std::time::Instant> = std::sync::OnceLock::new();

/// The other signals whose default ends the process (Ctrl-\\'s SIGQUIT, a soft CPU-time limit's
/// SIGXCPU (`ulimit -St`; at the hard limit the kernel sends SIGKILL),
/// an alarm or profiling timer, a user signal): each stops the run as SIGTERM does, through
/// its cleanup, and the exit status is still 128 + its own number. By default they ended the
/// process at once, with a dump's temporary files left behind.
#[cfg(unix)]
const OTHER_STOPS: [libc::c_int; 7] = [
    libc::SIGQUIT,
    libc::SIGUSR1,
    libc::SIGUSR2,
    libc::SIGALRM,
    libc::SIGVTALRM,
    libc::SIGPROF,
    libc::SIGXCPU,
];

/// Route each of [`OTHER_STOPS`] the process was not started ignoring to the SIGTERM handler.
#[cfg(unix)]
fn forward_other_stops() {
    extern "C" fn forward(sig: libc::c_int) {
        // Async-signal-safe: an atomic, getpid and kill. The first signal's number is kept,
        // so the status says which one stopped the run.
        let first = SIGNAL.compare_exchange(0, sig, Ordering::SeqCst, Ordering::SeqCst).is_ok();
        // A CPU-time limit's SIGXCPU comes again every CPU second: past the first it is the
        // same stop, not a second one that would cut the cleanup short.
        if !first && sig == libc::SIGXCPU && SIGNAL.load(Ordering::SeqCst) == libc::SIGXCPU {
            return;
        }
        // SAFETY: sends SIGTERM to this process, whose handler is installed.
        unsafe {
            libc::kill(libc::getpid(), libc::SIGTERM);
        }
    }
    for s in OTHER_STOPS {
        // SAFETY: reads the current action, and replaces a default one with `forward`.
        unsafe {
            let mut old: libc::sigaction = std::mem::zeroed();
            if libc::sigaction(s, std::ptr::null(), &mut old) != 0 || old.sa_sigaction != libc::SIG_DFL {
                continue;
            }
            let mut new: libc::sigaction = std::mem::zeroed();
            new.sa_sigaction = forward as extern "C" fn(libc::c_int) as usize;
            new.sa_flags = libc::SA_RESTART;
            libc::sigaction(s, &new, std::ptr::null_mut());
        }
    }
}

/// Install the handler (once, from `main`).
pub fn install() {
    // Past a file-size limit (`ulimit -f`) a write fails with EFBIG, which names the file and
    // goes through the run's cleanup, instead of SIGXFSZ ending the process without a word
    // and with its temporary files left.
    #[cfg(unix)]
    // SAFETY: sets a disposition; no handler runs.
    unsafe {
        libc::signal(libc::SIGXFSZ, libc::SIG_IGN);
    }
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
    let installed = ctrlc::set_handler(|| {
        // The handler runs on a thread of its own, not in signal context: it may read /proc,
        // print and signal. The tools end on the first signal too: a run stopping through its
        // error path must not wait for a whole build first.
        end_descendants();
        // The second of a pair is passed over before anything else is decided: the run may
        // have dropped its Cleanup on its way out, and an exit now would cut that short.
        if FIRST_SIGNAL.get().is_some_and(|t| t.elapsed() < SAME_STOP) {
            return;
        }
        FIRST_SIGNAL.get_or_init(std::time::Instant::now);
        if CLEANUPS.load(Ordering::SeqCst) == 0 || INTERRUPTED.swap(true, Ordering::SeqCst) {
            stop_now();
        }
        HANDLED.store(true, Ordering::SeqCst);
        // A run blocked where no loop checks the flag (opening a FIFO nobody reads, a full
        // pipe) would wait for a second signal, which a CI timeout or `docker stop` never
        // sends: after a grace period the first one ends it too.
        std::thread::spawn(|| {
            std::thread::sleep(STOP_GRACE);
            eprintln!(
                "gbump: interrupted: the run did not stop within {} s of the signal (blocked outside its loops)",
                STOP_GRACE.as_secs()
            );
            stop_now();
        });
    });
    // Chained only ahead of a handler ctrlc installed: without one the signals keep their
    // default, which ends the process with the right status by itself. A signal in the
    // moment between the two installs reaches ctrlc's alone and exits 130.
    #[cfg(unix)]
    for s in [libc::SIGHUP, libc::SIGINT, libc::SIGTERM] {
        if installed.is_ok() && !ignored.contains(&s) {
            record_signal_number(s);
        }
    }
    #[cfg(unix)]
    if installed.is_ok() && !ignored.contains(&libc::SIGTERM) {
        forward_other_stops();
    }
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

/// Whether a signal asked this run to stop (its error path then exits with
/// [`exit_status`], 128 + the signal's number as the shell's convention is, whichever step
/// noticed it).
pub fn interrupted() -> bool {
    INTERRUPTED.load(Ordering::Relaxed)
}

/// How long a tool ended by a stop signal (SIGINT, SIGTERM, SIGHUP, [`OTHER_STOPS`]) waits
/// for gbump's own handler.
const SETTLE: std::time::Duration = std::time::Duration::from_secs(1);

/// A tool ended by signal `sig`: when that is a stop signal that may have reached gbump too
/// (a terminal's Ctrl-C, a runner's SIGTERM to the group), the handler is given [`SETTLE`]
/// to run, so the run stops as interrupted rather than reporting a crashed tool, whichever
/// process the kernel signalled first.
#[cfg(unix)]
pub fn settle(sig: i32) -> Result<()> {
    if [libc::SIGINT, libc::SIGTERM, libc::SIGHUP].contains(&sig) || OTHER_STOPS.contains(&sig) {
        // A signal that reached gbump too ends in the handler's decision: it exits the
        // process (no cleanup to wait for), or sets INTERRUPTED and then HANDLED.
        let t = std::time::Instant::now();
        while !HANDLED.load(Ordering::SeqCst) && t.elapsed() < SETTLE {
            std::thread::sleep(std::time::Duration::from_millis(10));
        }
    }
    check()
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

#[cfg(all(test, target_os = "linux"))]
mod tests {
    /// A process is running as the one started at its start time: not under another start
    /// time (a reused pid), and not once it has ended.
    #[test]
    fn a_process_is_known_by_its_pid_and_start_time() {
        let mut child = std::process::Command::new("sleep").arg("30").spawn().expect("sleep runs");
        let pid = child.id();
        let start = super::started(pid);
        assert!(start.is_some(), "no start time for a running process");
        assert!(super::running(pid, start));
        assert!(!super::running(pid, start.map(|s| s + 1)), "another start time is another process");
        assert!(!super::running(pid, None), "a process whose start was not read may be another");
        child.kill().unwrap();
        child.wait().unwrap();
        assert!(!super::running(pid, start), "a reaped process still runs");
        assert_eq!(super::started(pid), None);
    }
}
