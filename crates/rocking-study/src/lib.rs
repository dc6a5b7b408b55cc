//! Studies of scenes: what one run reports ([`report`]: the summary, history and event
//! tables, as the command prints them and Python returns them), a scene's spectrum or record
//! batch planned once ([`plan`]), record-suite fragility studies ([`ida`]: IDA or multiple
//! stripes), and how a result converges with the number of deformation coordinates
//! ([`convergence`]).
//!
//! It owns the meaning of a scene's study settings (`[sweep]`, `[ida]`) and of the reported
//! quantities; it must not know how cells are scheduled, journaled or sharded (the generic sweep
//! engine `rocking-spectra`), nor how results are drawn or written (the command and Python).

pub mod convergence;
mod error;
pub mod ida;
pub mod plan;
pub mod report;

pub use error::{Argument, ArgumentNames, AxisRefusal, Invariant, StudyError};
