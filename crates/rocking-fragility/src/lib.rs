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
//! | [`bootstrap`] | seeded bootstrap confidence bands of a fit |
//!
//! # Example
//!
//! Capacities of a few records in Sa(T1 = 4.5 s, 5 %), each found by
//! hunt-and-fill, then the fitted curve. Here a stand-in replaces the
//! simulator: a record "overturns" when its scaled PGA exceeds 3 m/s².
//!
//! ```
//! use rocking_fragility::{fit_capacities, HuntFill, Outcome, ScalingIm};
//! use rocking_motion::Record;
//!
//! let sa = ScalingIm::Sa { period: 4.5, damping: 0.05 };
//! let hunt = HuntFill {
//!     first: 0.05, step: 0.1, step_increment: 0.05, // m/s², the paper's pattern
//!     tolerance: 0.01, max_gap: 0.05, max_runs: 60,
//! };
//! let mut capacities = Vec::new();
//! for (k, w) in [3.0, 5.0, 8.0, 13.0].into_iter().enumerate() {
//!     let dt = 0.01;
//!     let a = (0..3000).map(|i| (w * i as f64 * dt).sin() * (-(i as f64) * dt / (k + 2) as f64).exp());
//!     let record = Record::new(dt, a.collect())?;
//!     let ida = hunt.run(|im| {
//!         let scaled = record.clone().with_scale(sa.scale_factor(&record, im)?);
//!         let response = scaled.peak() / 3.0; // stand-in for max θ/α
//!         Ok::<_, rocking_fragility::FragilityError>(Outcome { collapsed: response >= 1.0, response })
//!     })?;
//!     capacities.push(ida.capacity);
//! }
//! let curve = fit_capacities(&capacities)?;
//! assert!(curve.theta > 0.0 && curve.beta > 0.0);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
#![warn(missing_docs)]
#![forbid(unsafe_code)]

pub mod bootstrap;
mod error;
pub mod fit;
pub mod ida;
mod normal;
pub mod scaling;

pub use bootstrap::{bootstrap_capacities, bootstrap_stripes, Bootstrap, BootstrapOptions};
pub use error::{ArgumentError, FragilityError, NoFit};
pub use fit::{fit_capacities, fit_stripes, Lognormal, Stripe};
pub use ida::{HuntFill, HuntFillError, Ida, IdaError, IdaPoint, Outcome};
pub use scaling::ScalingIm;
