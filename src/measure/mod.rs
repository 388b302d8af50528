//! Measurements: image error now; area, unit error and sweeps build on it.

pub mod image_metrics;
