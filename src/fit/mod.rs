//! `gbump fit`: the smallest hardware that renders these scenes within this error, and the
//! front around it (issue: model only what a scene requires).

pub mod budget;
pub mod evaluate;
pub mod run;
pub mod search;
pub mod table;
