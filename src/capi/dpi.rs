//! The entry points `include/gbump_dpi_pkg.sv` imports where DPI-C needs another contract
//! than C: the package binds each SystemVerilog name to its `gbump_dpi_*` symbol here (the
//! `import "DPI-C" c_name = function ...` form), so a testbench calls `gbump_config_hash` as
//! a C program does. They are not in the C header; a C program calls the functions there.
//!
//! - A string: "" where the C function gives NULL. A simulator copies a DPI `string` result
//!   without looking, so NULL crashed it; the failure is still `gbump_last_error()`'s.
//! - A record: every word of the package's `GBUMP_MAX_BITS`-bit vector is written, zero above
//!   the record, where the C function writes the record's words only; the simulator's
//!   temporary held other bits there, so a whole-vector compare differed from run to run.

use super::ffi::*;
use super::{GbumpConfig, GbumpStim};
use std::ffi::c_char;

/// The words of a `gbump_record_t`.
const RECORD_WORDS: usize = (super::MAX_RECORD_BITS / 32) as usize;

fn never_null(p: *const c_char) -> *const c_char {
    if p.is_null() {
        c"".as_ptr()
    } else {
        p
    }
}

/// Each wrapped string function, as (C function, DPI symbol).
macro_rules! strings {
    ($($dpi:ident = $f:ident($($a:ident: $t:ty),*);)*) => {
        $(
            /// # Safety
            /// As the C function of the same name without `dpi_`.
            #[no_mangle]
            pub unsafe extern "C" fn $dpi($($a: $t),*) -> *const c_char {
                never_null(unsafe { $f($($a),*) })
            }
        )*
        /// The C functions whose DPI-C import binds a `gbump_dpi_*` symbol instead.
        pub const WRAPPED: &[(&str, &str)] = &[$((stringify!($f), stringify!($dpi)),)* ("gbump_eval", "gbump_dpi_eval"), ("gbump_stim_next", "gbump_dpi_stim_next")];
    };
}

strings! {
    gbump_dpi_config_warnings = gbump_config_warnings(h: *const GbumpConfig);
    gbump_dpi_target_name = gbump_target_name(h: *const GbumpConfig, i: i32);
    gbump_dpi_config_hash = gbump_config_hash(h: *const GbumpConfig);
    gbump_dpi_config_toml = gbump_config_toml(h: *const GbumpConfig);
    gbump_dpi_module_name = gbump_module_name(h: *const GbumpConfig);
    gbump_dpi_port_name = gbump_port_name(h: *const GbumpConfig, i: i32);
    gbump_dpi_column_name = gbump_column_name(h: *const GbumpConfig, target: *const c_char, i: i32);
}

/// Zero the whole vector, then let `f` write the record.
///
/// # Safety
/// `rec_out` is NULL or `RECORD_WORDS` writable words.
unsafe fn whole_vector(rec_out: *mut u32, f: impl FnOnce() -> i32) -> i32 {
    if !rec_out.is_null() {
        unsafe { std::ptr::write_bytes(rec_out, 0, RECORD_WORDS) };
    }
    f()
}

/// # Safety
/// As `gbump_eval`, with `rec_out` a whole `gbump_record_t`.
#[no_mangle]
pub unsafe extern "C" fn gbump_dpi_eval(h: *const GbumpConfig, target: *const c_char, rec_in: *const u32, rec_out: *mut u32) -> i32 {
    // The input copied first: a caller may pass one vector as both (gbump_eval allows it), and
    // zeroing the output would have zeroed the stimulus.
    if rec_in.is_null() {
        return unsafe { whole_vector(rec_out, || gbump_eval(h, target, rec_in, rec_out)) };
    }
    let mut input = [0u32; RECORD_WORDS];
    unsafe { std::ptr::copy_nonoverlapping(rec_in, input.as_mut_ptr(), RECORD_WORDS) };
    unsafe { whole_vector(rec_out, || gbump_eval(h, target, input.as_ptr(), rec_out)) }
}

/// # Safety
/// As `gbump_stim_next`, with `rec_out` a whole `gbump_record_t`.
#[no_mangle]
pub unsafe extern "C" fn gbump_dpi_stim_next(g: *mut GbumpStim, rec_out: *mut u32) -> i32 {
    unsafe { whole_vector(rec_out, || gbump_stim_next(g, rec_out)) }
}
