//! gbump: a bit-accurate golden model of the Gouraud Bump Mapping hardware (Ernst,
//! Rüsseler, Schulz, Wittig; Graphics Hardware 1998), with f64 references to measure it
//! against. See ARCHITECTURE.md for the data flow and the decisions behind it.

pub mod bumpmap;
pub mod cache;
pub mod capi;
pub mod cli;
pub mod commit;
pub mod commit_journal;
pub mod config;
pub mod cosim;
pub mod engines;
pub mod error;
pub mod fit;
pub mod fixed;
pub mod interrupt;
pub mod limits;
pub mod measure;
pub mod model;
pub mod names;
pub mod out_of_memory;
pub mod progress;
pub mod raster;
pub mod reference;
pub mod renamed;
pub mod render;
pub mod rtlgen;
pub mod scene;
pub mod shell;
pub mod sim;
pub mod simd;
pub mod temp_files;
pub mod thread_pool;
pub mod toml_line;
pub mod tool;
pub mod units;
pub mod vectors;
pub mod vectors_command;
pub mod warn;
pub mod work_lock;
pub mod xml;
pub mod yosys;

pub use config::PipelineConfig;
pub use error::{Error, Result};

/// Tool name and version, as stamped into every generated file.
pub const TOOL: &str = concat!("gbump ", env!("CARGO_PKG_VERSION"));

/// A hash of the sources this build was made from (`build.rs`): `gbump --version` prints it,
/// and the Python module (`gbump.__source__`) and the C library (`gbump_source()`) carry it,
/// so one built from other sources than the gbump beside it is told apart.
pub const SOURCE_HASH: &str = env!("GBUMP_SOURCE_HASH");

/// `gbump --version`: the version and the source hash.
pub const LONG_VERSION: &str = concat!(env!("CARGO_PKG_VERSION"), " (source ", env!("GBUMP_SOURCE_HASH"), ")");
