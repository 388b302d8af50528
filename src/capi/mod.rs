//! The golden model as a C library (`libgbump.so`, header `include/gbump.h`, SystemVerilog
//! DPI-C package `include/gbump_dpi_pkg.sv`): configuration handles, widths, ports and
//! latency, per-unit and whole-pipeline evaluation of packed records (single and batches),
//! power-table contents and the seeded random stimulus stream of `gbump vectors random:N`.
//!
//! Every argument type is one SystemVerilog DPI-C maps directly (`chandle`, `string`, `int`,
//! `longint`, packed `bit` vectors as 32-bit words), so a testbench imports these functions
//! with no C shim. Records are the vector files' records (`vectors::layout`) as 32-bit words,
//! LSB first. No panic crosses the boundary: each function catches it and reports it through
//! [`ffi::gbump_last_error`].

pub mod dpi;
pub mod dpi_pkg;
pub mod ffi;
mod guard;
mod handle;

pub use handle::{plan_memory, GbumpConfig, GbumpStim, Target};

/// The calling conventions, stated once: the header opens with them and `ffi`'s functions
/// follow them.
pub const CONVENTIONS: &str = "\
Conventions of every function below:
- Handles: gbump_config_* and gbump_stim_new create one, the matching _free releases it.
  NULL means failure. A NULL handle passed in is refused like any bad argument (it is never
  dereferenced); a freed handle, or one of the other type, is undefined behaviour, as in C.
- Status: functions returning int32_t give 0 on success and -1 on failure (gbump_eval,
  gbump_eval_batch, gbump_set_shininess, gbump_set_env_map, gbump_set_env_texel,
  gbump_stim_next); counts, widths, offsets and
  words (gbump_record_words, gbump_column, gbump_power_word, ...) are -1 on failure;
  functions returning a string give NULL on failure (an index out of range, a bad handle).
- Errors: gbump_last_error() says why the last failing call on this thread failed, with
  the fix; it keeps that message until the next failure on the thread (a success does not
  clear it); empty before any failure.
- Strings returned are owned by the library, never freed by the caller: gbump_version and
  gbump_source are static; gbump_config_hash, gbump_config_toml, gbump_port_name and
  gbump_column_name, gbump_target_name, gbump_module_name and gbump_config_warnings live
  as long as their handle; gbump_last_error's until the next failure on the thread, which
  frees it. Copy an error before the next call: in an argument list that both fails a call
  and reads gbump_last_error() (printf(\"%d %s\", gbump_latency(NULL), gbump_last_error()),
  say) the pointer read may be freed by the failure before it is used.
- Output: the library never writes to stdout or stderr. A configuration read under an old
  field name is accepted with a warning that gbump_config_warnings returns.
- Records: gbump_record_words(h, target) 32-bit words, LSB first, holding the bits of one
  record of the vector files (gbump_column gives each column's offset); a binary vector
  file packs its records back to back in gbump_record_bits / 8 bytes each (rounded up), so
  copy each into a zeroed buffer of whole words. Targets are \"top\" and the units the
  configuration has, which gbump_target_count and gbump_target_name list. Bits above a
  record's last bit are ignored. A unit input the pipeline never gives above a bound its
  unit relies on is refused above it, with the port and the bound: power_unit's x above 1.0
  (a clamped dot product; the table has no word past it), env_fetch's texel block past the
  map's last two columns or rows (x0, y0), colour_round's c_in above full scale (a stage
  colour saturates there); so is a record whose result overflows its output. Every other
  input is taken over its whole format, as the unit's RTL takes it (a blend factor or k
  above 1.0 included), though the pipeline feeds at most 1.0 there, and light_accumulate's
  running sum wraps at the accumulator's width as its adder does. In a stream of one record
  per edge, a column enters gbump_column_enters edges after the rest.
- Palette configurations (palette = true) are refused by gbump_config_* for now.
- Batches: gbump_eval_batch takes 0..=GBUMP_MAX_BATCH_RECORDS records per call (the
  limit the Python module's arrays have too); one whose copy of its input would not fit
  in memory (MAX_MEMORY_BYTES, MemAvailable, or what ulimit -v leaves) is refused before
  anything is allocated, rather than abort the process.
- Threads: a handle may be read from several threads at once, but not while
  gbump_set_shininess, gbump_set_env_map, gbump_set_env_texel or _free runs on it; a stimulus stream belongs to one thread. A batch
  of 1024 records or more runs on the library's own thread pool, one thread per core, or
  RAYON_NUM_THREADS threads when that is set before the first such batch; its threads stay
  for the process's life. A child of fork() gets a pool of its own at its first batch (it
  has none of its parent's threads).
- DPI-C: include/gbump_dpi_pkg.sv imports these functions, but binds the string functions
  that may give NULL, gbump_eval and gbump_stim_next to gbump_dpi_* symbols the library
  also exports (\"\" for NULL, and the whole GBUMP_MAX_BITS vector written, zero above the
  record); a C program calls the functions here.";

/// Bumped whenever a function's signature or a record's meaning changes.
pub const ABI_VERSION: i32 = 1;

/// The checked-in header and DPI-C package (regenerated by `cargo run --release --example
/// capi_header`; `tests/capi.rs` fails when they are stale).
pub const HEADER: &str = include_str!("../../include/gbump.h");
pub const DPI_PACKAGE: &str = include_str!("../../include/gbump_dpi_pkg.sv");

/// The widest record any valid configuration has, rounded up to a power of two: the width of
/// the DPI package's record vectors (`GBUMP_MAX_BITS`).
pub const MAX_RECORD_BITS: u32 = 2048;

/// Records of one call from which it runs on the library's thread pool (fewer run on the
/// caller's thread: handing them to the pool costs more than they do).
pub const PARALLEL_RECORDS: usize = 1024;
