//! The FFI boundary: the thread's last error, and a guard that turns both an `Err` and a
//! panic into a status the caller can test, since unwinding into C is undefined behaviour.

use crate::error::{Error, Result};
use std::cell::RefCell;
use std::ffi::{c_char, CStr, CString};
use std::panic::{catch_unwind, AssertUnwindSafe};

thread_local! {
    static LAST_ERROR: RefCell<CString> = RefCell::new(CString::default());
}

/// Record `msg` as this thread's last error.
pub fn set_error(msg: &str) {
    // Control characters a caller passed in (a name, a path) shown escaped, as the CLI shows them.
    let c = CString::new(crate::error::shown(&msg.replace('\0', " "))).expect("no NUL left");
    LAST_ERROR.with(|e| *e.borrow_mut() = c);
}

/// This thread's last error; valid until the next failing call on this thread.
pub fn last_error() -> *const c_char {
    LAST_ERROR.with(|e| e.borrow().as_ptr())
}

/// Guarded calls running now, on any thread.
static GUARDED: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);

thread_local! {
    /// Whether this thread is inside a guarded call.
    static IN_GUARD: std::cell::Cell<bool> = const { std::cell::Cell::new(false) };
}

/// The panic hook, chained once in front of the one before it (in the C library, this
/// library's own): silent for a panic on a thread inside a guarded call, or on the library's
/// thread pool while one runs (its batches), since that panic comes back as the call's error
/// message and a library writes nothing into its host's stderr; the previous hook's
/// behaviour for every other panic.
fn quiet_panics() {
    static ONCE: std::sync::Once = std::sync::Once::new();
    ONCE.call_once(|| {
        let previous = std::panic::take_hook();
        std::panic::set_hook(Box::new(move |info| {
            let pool = rayon::current_thread_index().is_some() && GUARDED.load(std::sync::atomic::Ordering::SeqCst) > 0;
            if !(IN_GUARD.with(|g| g.get()) || pool) {
                previous(info);
            }
        }));
    });
}

/// Run `f`; on an error or a panic record the message and return `fail`.
pub fn guard<T>(what: &str, fail: T, f: impl FnOnce() -> Result<T>) -> T {
    use std::sync::atomic::Ordering::SeqCst;
    quiet_panics();
    struct Active(bool);
    impl Drop for Active {
        fn drop(&mut self) {
            GUARDED.fetch_sub(1, SeqCst);
            IN_GUARD.with(|g| g.set(self.0));
        }
    }
    GUARDED.fetch_add(1, SeqCst);
    let active = Active(IN_GUARD.with(|g| g.replace(true)));
    let result = catch_unwind(AssertUnwindSafe(f));
    drop(active);
    match result {
        Ok(Ok(v)) => v,
        Ok(Err(e)) => {
            set_error(&format!("{what}: {e}"));
            fail
        }
        Err(p) => {
            let msg = p
                .downcast_ref::<String>()
                .map(String::as_str)
                .or_else(|| p.downcast_ref::<&str>().copied())
                .unwrap_or("unknown panic");
            set_error(&format!(
                "{what}: internal error (panic: {msg})\n  fix: report it with the inputs of this call"
            ));
            fail
        }
    }
}

/// A C string argument as UTF-8; `arg` names it in errors.
///
/// # Safety
/// `p` is null or points to a NUL-terminated string that outlives the call.
pub unsafe fn str_arg<'a>(p: *const c_char, arg: &str) -> Result<&'a str> {
    if p.is_null() {
        return Err(Error::Other(format!("{arg} is NULL\n  fix: pass a NUL-terminated string")));
    }
    CStr::from_ptr(p)
        .to_str()
        .map_err(|_| Error::Other(format!("{arg} is not UTF-8\n  fix: pass UTF-8 text")))
}

/// A name argument (a target, a column, a unit): [`str_arg`], refused when it holds a control
/// character (see [`one_line_arg`]).
///
/// # Safety
/// As [`str_arg`].
pub unsafe fn name_arg<'a>(p: *const c_char, arg: &str) -> Result<&'a str> {
    one_line_arg(
        str_arg(p, arg)?,
        arg,
        "pass the name alone, as gbump_target_name and gbump_column_name give it",
    )
}

/// `s` (argument `arg`), refused when it holds a control character: a message quotes it, and a
/// line break in it would start a line of its own (a forged `fix:` line in the caller's log).
pub fn one_line_arg<'a>(s: &'a str, arg: &str, fix: &str) -> Result<&'a str> {
    match s.chars().any(char::is_control) {
        true => Err(Error::Other(format!(
            "{arg} {s:?} holds a control character (a line break, a tab, an escape)\n  fix: {fix}"
        ))),
        false => Ok(s),
    }
}

/// A handle argument; `arg` names it in errors.
///
/// # Safety
/// `p` is null or a live handle of type `T` from this library.
pub unsafe fn handle<'a, T>(p: *const T, arg: &str) -> Result<&'a T> {
    p.as_ref().ok_or_else(|| {
        Error::Other(format!(
            "{arg} is NULL\n  fix: check the result of the call that created it (gbump_last_error says why it failed)"
        ))
    })
}

/// A mutable handle argument.
///
/// # Safety
/// As [`handle`], and no other reference to it is live.
pub unsafe fn handle_mut<'a, T>(p: *mut T, arg: &str) -> Result<&'a mut T> {
    p.as_mut().ok_or_else(|| {
        Error::Other(format!(
            "{arg} is NULL\n  fix: check the result of the call that created it (gbump_last_error says why it failed)"
        ))
    })
}

/// A buffer argument of `n` words: a record's 32-bit ones, a map's 64-bit ones.
///
/// # Safety
/// `p` is null or points to at least `n` readable words.
pub unsafe fn words<'a, T>(p: *const T, n: usize, arg: &str) -> Result<&'a [T]> {
    if p.is_null() {
        let bits = 8 * std::mem::size_of::<T>();
        return Err(Error::Other(format!("{arg} is NULL\n  fix: pass a buffer of {n} {bits}-bit words")));
    }
    Ok(std::slice::from_raw_parts(p, n))
}

/// A writable record buffer argument of `n` 32-bit words.
///
/// # Safety
/// `p` is null or points to at least `n` writable words not otherwise borrowed.
pub unsafe fn words_mut<'a>(p: *mut u32, n: usize, arg: &str) -> Result<&'a mut [u32]> {
    if p.is_null() {
        return Err(Error::Other(format!("{arg} is NULL\n  fix: pass a buffer of {n} 32-bit words")));
    }
    Ok(std::slice::from_raw_parts_mut(p, n))
}

#[cfg(test)]
mod tests {
    /// A panic inside a guarded call comes back as the call's error, and the count of
    /// guarded calls (which keeps the panic hook silent) is restored however the call ends.
    #[test]
    fn a_panic_is_an_error_and_the_hook_is_restored() {
        let r = super::guard("f", -1, || -> crate::error::Result<i32> { panic!("boom") });
        assert_eq!(r, -1);
        let e = unsafe { std::ffi::CStr::from_ptr(super::last_error()) }
            .to_string_lossy()
            .into_owned();
        assert!(e.starts_with("f: internal error (panic: boom)"), "{e}");
        assert_eq!(super::guard("g", -1, || Ok(3)), 3);
        assert_eq!(super::GUARDED.load(std::sync::atomic::Ordering::SeqCst), 0);
    }
}
