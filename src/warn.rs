//! Warnings (a renamed field read under its old name, an ignored environment setting): the
//! command line prints them on stderr; the C library and the Python module, which must not
//! write into their host's streams, collect them for the caller to read.

use std::cell::RefCell;

thread_local! {
    static CAPTURED: RefCell<Option<Vec<String>>> = const { RefCell::new(None) };
}

/// Say `msg`: on stderr, or into the collection of the [`capture`] running on this thread.
/// Each message is said once: a command reads its scene or configuration several times (to
/// check it, size the pipeline, render it), and a warning repeated per read is noise.
pub fn warn(msg: String) {
    CAPTURED.with(|c| match &mut *c.borrow_mut() {
        Some(list) => {
            if !list.contains(&msg) {
                list.push(msg)
            }
        }
        None => {
            static SAID: std::sync::Mutex<Vec<String>> = std::sync::Mutex::new(Vec::new());
            let mut said = SAID.lock().unwrap_or_else(|e| e.into_inner());
            if !said.contains(&msg) {
                eprintln!("{msg}");
                said.push(msg);
            }
        }
    })
}

/// Run `f`, collecting the warnings it gives instead of printing them.
pub fn capture<R>(f: impl FnOnce() -> R) -> (R, Vec<String>) {
    let outer = CAPTURED.with(|c| c.borrow_mut().replace(Vec::new()));
    // Restored however `f` ends (a panic caught at the FFI boundary included).
    struct Restore(Option<Option<Vec<String>>>);
    impl Drop for Restore {
        fn drop(&mut self) {
            let outer = self.0.take().flatten();
            CAPTURED.with(|c| *c.borrow_mut() = outer);
        }
    }
    let restore = Restore(Some(outer));
    let r = f();
    let got = CAPTURED.with(|c| c.borrow_mut().take()).unwrap_or_default();
    drop(restore);
    (r, got)
}

#[cfg(test)]
mod tests {
    #[test]
    fn captured_warnings_are_not_printed_and_nesting_keeps_each_its_own() {
        let (((), inner), outer) = super::capture(|| {
            super::warn("a".into());
            let r = super::capture(|| super::warn("b".into()));
            super::warn("c".into());
            r
        });
        assert_eq!(inner, vec!["b".to_string()]);
        assert_eq!(outer, vec!["a".to_string(), "c".to_string()]);
    }

    #[test]
    fn a_warning_given_twice_is_collected_once() {
        let ((), got) = super::capture(|| {
            for m in ["a", "b", "a", "b", "c"] {
                super::warn(m.into());
            }
        });
        assert_eq!(got, ["a", "b", "c"]);
    }
}
