//! The bit-accurate golden model: one function per hardware unit of the paper (§4.2, §5.1),
//! each computing exactly what its Verilog twin in `rtlgen` computes, on raw integer codes
//! in the formats the [`PipelineConfig`](crate::config::PipelineConfig) resolves.
//!
//! Units, in data-flow order: [`bump_fetch`] (palette / range expansion), [`dot_clamp`]
//! (fd = max(0, B·L), also B·H), [`power_unit`] (fs = (B·H)^n from the [`power_table`]), [`blend`]
//! (`diffuse_blend`, `specular_blend`), [`texture_modulate`]; [`pipeline`] chains them in
//! the configured order. [`fast`] is the same pipeline specialised per configuration, for
//! callers that need the colour alone.

pub mod blend;
pub mod bump_fetch;
pub mod cube_normalise;
pub mod dot_clamp;
pub mod env_map;
pub mod fast;
pub mod frame_build;
pub mod frame_transform;
pub mod normalise;
pub mod pipeline;
pub mod power_table;
pub mod power_unit;
pub mod quat_frame;
pub mod texture_modulate;

pub use bump_fetch::Palette;
pub use fast::FastModel;
pub use pipeline::{shade, BumpState, BumpTexel, FragmentIn, LightSlot, Shaded, MAX_LIGHTS};
pub use power_table::PowerTable;
