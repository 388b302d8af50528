//! The command-line tool's allocator: the system's, with an error in gbump's words when it
//! runs out. Rust aborts a process whose allocation fails (SIGABRT, a jumbled "memory
//! allocation of N bytes failed" from several threads at once), which skips the run's own
//! cleanup and left a dump's temporary files behind. Here the first failure releases a
//! reserve held for it, says what failed and how to fix it, removes this process's temporary
//! files, ends the tools it started and exits with status 1, as every other error does.
//!
//! Only the binary installs it (`main.rs`): the C library and the Python module reserve their
//! large buffers fallibly and return an error to their caller instead.

use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicBool, AtomicPtr, Ordering};

/// Bytes set aside at start-up and freed when an allocation fails, so that the error path
/// (its message, the list of temporary names) can still allocate.
const RESERVE_BYTES: usize = 4 << 20;

static RESERVE: AtomicPtr<u8> = AtomicPtr::new(std::ptr::null_mut());
static FAILED: AtomicBool = AtomicBool::new(false);

pub struct Allocator;

// SAFETY: every call goes to `System` unchanged; only a null result takes the error path,
// which never returns (or, on a second failure inside it, returns the null as `System` did).
unsafe impl GlobalAlloc for Allocator {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        checked(System.alloc(layout), layout.size())
    }
    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        checked(System.alloc_zeroed(layout), layout.size())
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        checked(System.realloc(ptr, layout, new_size), new_size)
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        System.dealloc(ptr, layout)
    }
}

fn reserve_layout() -> Layout {
    Layout::from_size_align(RESERVE_BYTES, 4096).expect("a valid layout")
}

#[inline]
fn checked(p: *mut u8, bytes: usize) -> *mut u8 {
    if p.is_null() {
        out_of_memory(bytes);
    }
    p
}

thread_local! {
    /// This thread is running the error path (a failure inside it is left to abort).
    static HANDLING: std::cell::Cell<bool> = const { std::cell::Cell::new(false) };
}

#[cold]
fn out_of_memory(bytes: usize) {
    if HANDLING.with(|h| h.get()) {
        return;
    }
    if FAILED.swap(true, Ordering::SeqCst) {
        // Another thread ran out first and is cleaning up: wait for its exit, which ends this
        // one too (returning the null would abort the process under it).
        loop {
            // SAFETY: pause blocks until a signal; nothing is allocated.
            unsafe {
                libc::pause();
            }
        }
    }
    HANDLING.with(|h| h.set(true));
    let reserve = RESERVE.swap(std::ptr::null_mut(), Ordering::SeqCst);
    if !reserve.is_null() {
        // SAFETY: allocated in `install` with this layout, and taken out of RESERVE once.
        unsafe { System.dealloc(reserve, reserve_layout()) };
    }
    let fix = match crate::limits::address_space_limit() {
        Some(l) => format!(
            "ulimit -v allows this process {} MiB of address space: raise it, or ask for less (fewer records, a smaller --size)",
            l >> 20
        ),
        None => "free memory, or ask for less (fewer records, a smaller --size)".to_string(),
    };
    crate::interrupt::kill_tree();
    let removed = crate::temp_files::remove_own_unless_held();
    crate::render::output::remove_made_folders_unless_held(&[crate::work_lock::LOCK_NAME]);
    let msg = format!(
        "gbump: error: out of memory: an allocation of {bytes} bytes failed{}\n  fix: {fix}\n",
        if removed > 0 {
            format!(" (its {removed} unfinished file(s) were removed; nothing partial was kept)")
        } else {
            String::new()
        }
    );
    // Past the standard error's lock, which a thread stopped above may hold.
    // SAFETY: writes the bytes of a live String to file descriptor 2.
    unsafe {
        libc::write(2, msg.as_ptr().cast(), msg.len());
        // Not `process::exit`, whose flush of standard output could wait on a lock a stopped
        // thread holds.
        libc::_exit(1);
    }
}

/// Set the reserve aside, and under an address-space limit (`ulimit -v`) keep the system
/// allocator to one arena: each thread's own arena reserves 64 MiB of address space up front
/// on 64-bit glibc, so a few worker threads exhausted a limit that the run's data fit in many
/// times over (a 20,000-record dump failed under 400 MB).
pub fn install() {
    // SAFETY: a plain allocation of a valid, non-zero layout.
    let p = unsafe { System.alloc(reserve_layout()) };
    RESERVE.store(p, Ordering::SeqCst);
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    if crate::limits::address_space_limit().is_some() {
        // SAFETY: mallopt with a documented parameter, before any other thread exists.
        unsafe {
            libc::mallopt(libc::M_ARENA_MAX, 1);
        }
    }
}
