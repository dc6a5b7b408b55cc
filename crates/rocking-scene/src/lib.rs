//! Scene files of the rocking simulator: TOML text → overrides → the structure, excitation,
//! effects, options and units a run needs, with errors that name the file, line:column and key.
//! The `rocking` command, the tests, the benchmark study and the examples load scenes through it.
//!
//! It owns the scene format (keys, defaults, ranges, the messages that refuse a value) and the
//! [`setup::Setup`] a run needs; it must not know studies (sweeps, IDA: `rocking-study`), how a
//! run is reported, or how anything is drawn or written.

mod check;
mod effects;
mod error;
pub mod excitation;
pub mod ground;
pub mod ground_spec;
pub mod knob;
pub mod labels;
pub mod limits;
pub mod models;
pub mod scene;
pub mod setup;
mod spec;
mod structure;
pub mod units;

pub use error::{InputError, SceneError};
