//! Which vector extensions the bulk loops (the fast model, random records) run with. They are
//! written as plain loops over fixed-size blocks and compiled three times: for AVX-512, for
//! AVX2 and for the baseline CPU; the best the machine has is chosen once, at run time, so
//! one binary is fast everywhere and correct everywhere. Every level gives the same bits:
//! the tests run each level the test machine has.

/// A set of vector extensions, best last.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Level {
    Baseline,
    Avx2,
    Avx512,
}

impl Level {
    /// Every level up to `self`.
    pub fn and_below(self) -> Vec<Level> {
        [Level::Baseline, Level::Avx2, Level::Avx512]
            .into_iter()
            .filter(|l| *l <= self)
            .collect()
    }
}

/// The best level this CPU runs (detected once; later calls are a load). `GBUMP_SIMD=
/// baseline|avx2|avx512` caps it, to measure or check a lower level on a machine with a
/// higher one.
pub fn level() -> Level {
    static LEVEL: std::sync::OnceLock<Level> = std::sync::OnceLock::new();
    *LEVEL.get_or_init(|| {
        let cap = match std::env::var("GBUMP_SIMD").as_deref() {
            Ok("baseline") => Level::Baseline,
            Ok("avx2") => Level::Avx2,
            Ok("avx512") | Err(_) => Level::Avx512,
            Ok(other) => {
                // Deep in a loop there is no error path; say so once and run uncapped.
                crate::warn::warn(format!(
                    "gbump: warning: GBUMP_SIMD={other:?} is not baseline, avx2 or avx512; ignored"
                ));
                Level::Avx512
            }
        };
        detected().min(cap)
    })
}

/// Whether this CPU runs code compiled for `level`.
pub fn supported(level: Level) -> bool {
    static DETECTED: std::sync::OnceLock<Level> = std::sync::OnceLock::new();
    level <= *DETECTED.get_or_init(detected)
}

#[cfg(target_arch = "x86_64")]
fn detected() -> Level {
    use std::arch::is_x86_feature_detected as has;
    if has!("avx512f") && has!("avx512dq") && has!("avx512vl") && has!("avx512bw") && has!("avx2") && has!("bmi2") {
        Level::Avx512
    } else if has!("avx2") && has!("bmi2") {
        Level::Avx2
    } else {
        Level::Baseline
    }
}

#[cfg(not(target_arch = "x86_64"))]
fn detected() -> Level {
    Level::Baseline
}

/// `body` compiled for the vector extensions of `level` (which the CPU must have: [`level`]
/// or a [`supported`] one) and run: the macro writes the body into one function per level,
/// each compiled with its level's `target_feature`, and calls the one `level` names. The body
/// is a call of an `#[inline(always)]` function, which each copy then holds whole.
///
/// `[generic parameters] [their names]` are the enclosing function's, repeated because a
/// nested function cannot see them; the parameters are variables of the caller, passed by
/// name (a method passes `self` as a named variable).
macro_rules! at_level {
    ($level:expr, [$($gen:tt)*] [$($garg:tt)*] fn($($arg:ident: $ty:ty),* $(,)?) $(-> $ret:ty)? $body:block) => {{
        #[cfg(target_arch = "x86_64")]
        #[target_feature(enable = "avx512f,avx512dq,avx512vl,avx512bw,avx2,bmi2")]
        unsafe fn avx512<$($gen)*>($($arg: $ty),*) $(-> $ret)? $body
        #[cfg(target_arch = "x86_64")]
        #[target_feature(enable = "avx2,bmi2")]
        unsafe fn avx2<$($gen)*>($($arg: $ty),*) $(-> $ret)? $body
        // A call of its own on every level, so the body is compiled the same way in each.
        #[inline(never)]
        fn baseline<$($gen)*>($($arg: $ty),*) $(-> $ret)? $body
        match $level {
            #[cfg(target_arch = "x86_64")]
            // SAFETY: the CPU has every extension `avx512` is compiled for (the caller's
            // contract on `level`).
            $crate::simd::Level::Avx512 => unsafe { avx512::<$($garg)*>($($arg),*) },
            #[cfg(target_arch = "x86_64")]
            // SAFETY: as above.
            $crate::simd::Level::Avx2 => unsafe { avx2::<$($garg)*>($($arg),*) },
            _ => baseline::<$($garg)*>($($arg),*),
        }
    }};
}
pub(crate) use at_level;
