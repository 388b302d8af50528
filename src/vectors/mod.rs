//! The vector dumper: stimulus and expected response from the golden model, for the top and
//! for each unit, as `$readmemh`-ready text (one record per line) and fixed-size binary
//! records, each set with a JSON manifest (generator, config and hash, source, a random set's
//! seed, count, column layout, sha256 of every file). Seeded and deterministic: the same
//! command gives the same bytes.

pub mod choices;
pub mod digest;
pub mod layout;
pub mod manifest;
pub mod model_check;
pub mod rng;
pub mod sources;
pub mod staged_file;
pub mod targets;
pub mod top_records;
pub mod writer;

pub use manifest::{verify, Manifest};
pub use sources::Source;
pub use writer::{check_scene_names, dump, DumpOptions, VectorSet};
