//! From scene to fragments: per-object assets (stored bump map, texture), per-triangle bump
//! state (L_i and H_i in bump space, paper §4.1; in eye space with a frame per fragment under
//! `frame_transform`), a z-buffered rasteriser, and the fragment
//! records that feed the golden model, the vectors and the f64 renderers; under EMBM each
//! object's environment maps, the triangle's 2×2 matrix and the fragment's map coordinates.

pub mod assets;
pub mod env_setup;
pub mod fragment;
pub mod rasterise;
pub mod tri_state;

pub use assets::{ObjectAssets, Prepared};
pub use fragment::{FragmentRecord, PixelGeom};
pub use rasterise::{GBuffer, Hit};
