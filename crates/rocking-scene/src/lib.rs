//! Scene files of the rocking simulator: TOML text → overrides → the structure, excitation,
//! effects, options and units a run needs, with errors that name the file, line:column and key.
//! The `rocking` command, the tests, the benchmark study and the examples load scenes through it.

pub mod knob;
pub mod labels;
pub mod limits;
pub mod model;
pub mod models;
pub mod report;
pub mod scene;
