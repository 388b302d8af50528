//! Measurements: image error now; area, unit error and sweeps build on it.

pub mod area;
pub mod area_model;
pub mod bench;
pub mod configs;
pub mod embm_error;
pub mod fpga;
pub mod image_metrics;
pub mod long_run;
pub mod plot;
pub mod power_space;
pub mod report;
pub mod scene_error;
pub mod sweep;
pub mod timing_report;
pub mod unit_error;
