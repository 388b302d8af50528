//! Measurements: image error now; area, unit error and sweeps build on it.

pub mod area;
pub mod image_metrics;
pub mod unit_error;
