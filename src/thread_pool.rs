//! The thread pool of the library's entry points (the C ABI's batches, the Python module's
//! arrays): rayon's, but made again in a process that `fork()` started. A forked child has
//! none of its parent's threads, so the pool the parent made would take the child's work and
//! never do it (a batch called in a child of a process that had run one hung for ever).
//! Its size is rayon's: `RAYON_NUM_THREADS`, else one thread per core.

use std::sync::atomic::{AtomicPtr, Ordering};

struct Pool {
    pid: u32,
    pool: rayon::ThreadPool,
}

static POOL: AtomicPtr<Pool> = AtomicPtr::new(std::ptr::null_mut());

/// Run `f` on this process's pool: every rayon call inside it runs on that pool's threads.
pub fn install<R: Send>(f: impl FnOnce() -> R + Send) -> R {
    pool().install(f)
}

fn pool() -> &'static rayon::ThreadPool {
    let pid = std::process::id();
    let p = POOL.load(Ordering::Acquire);
    // SAFETY: a pointer stored here comes from `Box::leak` and is never freed (only a pool
    // that lost the race to be stored is).
    if let Some(p) = unsafe { p.as_ref() }.filter(|p| p.pid == pid) {
        return &p.pool;
    }
    // No lock: a child may be forked while another thread of its parent holds one.
    let built = Box::leak(Box::new(Pool {
        pid,
        pool: rayon::ThreadPoolBuilder::new()
            .thread_name(|i| format!("gbump-{i}"))
            .build()
            .expect("the system starts threads"),
    }));
    match POOL.compare_exchange(p, built, Ordering::AcqRel, Ordering::Acquire) {
        Ok(_) => &built.pool,
        // Another thread of this process made one first: use it, and end this one's threads.
        Err(won) => {
            // SAFETY: `built` came from `Box::leak` above and was never shared.
            drop(unsafe { Box::from_raw(built as *mut Pool) });
            &unsafe { &*won }.pool
        }
    }
}
