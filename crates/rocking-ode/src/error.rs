//! The integrators' error: what went wrong and when.

use std::fmt;

/// What went wrong, see [`OdeError`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum OdeErrorKind {
    /// The step size became too small relative to `t`.
    StepSizeUnderflow,
    /// The right-hand side or the state became NaN or infinite.
    NonFinite,
    /// More than [`Options::max_steps`](crate::Options::max_steps) attempts since the last reset.
    MaxSteps,
    /// Invalid options, tolerances or arguments.
    InvalidInput,
    /// [`Integrator::step`](crate::Integrator::step) was called before [`Integrator::reset`](crate::Integrator::reset).
    NotInitialised,
}

/// Integration error, with the time at which it happened.
#[derive(Clone, Debug, PartialEq)]
pub struct OdeError {
    /// Error category.
    pub kind: OdeErrorKind,
    /// Time of the current point when the error occurred (NaN if none).
    pub t: f64,
    /// Human-readable explanation.
    pub message: String,
}

impl OdeError {
    pub(crate) fn new(kind: OdeErrorKind, t: f64, message: String) -> Self {
        Self { kind, t, message }
    }
}

impl fmt::Display for OdeError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "ODE integration failed at t = {}: {}",
            self.t, self.message
        )
    }
}

impl std::error::Error for OdeError {}
