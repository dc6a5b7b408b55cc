//! Record-based studies of rocking structures: scaling records to an
//! intensity level, incremental dynamic analysis by hunt-and-fill, and
//! lognormal fragility curves fitted by maximum likelihood with bootstrap
//! confidence bands.
//!
//! The crate knows nothing of the simulator: an IDA takes a closure that
//! runs one analysis at an intensity level, so the CLI, a Python binding
//! and the tests (with synthetic responses) drive the same code.
//!
//! | module | what |
//! |--------|------|
//! | [`scaling`] | the factor that brings a record to a target PGA or Sa(T, ζ) |
//! | [`ida`] | hunt-and-fill (Vamvatsikos & Cornell 2002): capacity and IDA curve |
//! | [`fit`] | lognormal MLE from capacities (closed form) and stripes (Baker 2015) |
//! | [`bootstrap`] | seeded bootstrap percentile bands of a fit |
#![warn(missing_docs)]
#![forbid(unsafe_code)]

pub mod bootstrap;
pub mod fit;
pub mod ida;
mod normal;
pub mod scaling;

pub use bootstrap::{bootstrap_capacities, bootstrap_stripes, Bootstrap, BootstrapOptions};
pub use fit::{fit_capacities, fit_stripes, Lognormal, Stripe};
pub use ida::{HuntFill, Ida, IdaError, IdaPoint, Outcome};
pub use scaling::ScalingIm;

use std::fmt;

/// Why a fit, a bootstrap or a scaling could not be done.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum FragilityError {
    /// An argument is invalid; the message names it.
    InvalidParameter(String),
    /// The data have no finite maximum-likelihood estimate (no collapse,
    /// only collapses, complete separation, ...); the message says which.
    NoEstimate(String),
}

impl fmt::Display for FragilityError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            FragilityError::InvalidParameter(m) => write!(f, "invalid parameter: {m}"),
            FragilityError::NoEstimate(m) => write!(f, "no estimate: {m}"),
        }
    }
}

impl std::error::Error for FragilityError {}
