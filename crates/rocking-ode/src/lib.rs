//! Explicit Runge–Kutta integration with dense output and event location for
//! small, fixed-size, hybrid (event-driven) systems.
//!
//! This crate is the time integrator of a rocking-structure simulator. The
//! state has a handful of components (`nalgebra::SVector<f64, N>`, `N` a
//! const generic), the integration runs until an *event* (uplift, impact,
//! overturning) is located to near machine precision, a map is applied to the
//! state, and the integration restarts at the event. The crate knows nothing
//! about the model: it only sees a right-hand side `f(t, y)` and, for events,
//! an event function `g(t, y)`.
//!
//! # Methods
//!
//! * [`Method::Dopri5`]: the Dormand–Prince 5(4) pair with the FSAL property
//!   and Hairer's 4th-order continuous extension (`dopri5.f`), see Hairer,
//!   Nørsett & Wanner, *Solving Ordinary Differential Equations I*
//!   (HNW I), Sect. II.5 and II.6. Six right-hand side evaluations per step.
//! * [`Method::Dop853`]: the 8th-order Dormand–Prince method DOP853 with the
//!   combined 5th/3rd-order error estimator and the 7th-order dense output
//!   (three extra stages), HNW I, Sect. II.10 and `dop853.f`. Twelve
//!   evaluations per step plus three for the dense output.
//! * [`taylor::Taylor`]: a Taylor-series method (Jorba–Zou step, order from a cost model) for systems
//!   that supply their Taylor coefficients; dense output is the step's polynomial and events
//!   are its roots ([`poly`]: Bernstein/Descartes isolation, so none inside a step is missed).
//!
//! Step sizes are chosen by Hairer's (PI) controller with the defaults of his
//! codes; the error norm is the RMS over the components of
//! `err_i / (atol_i + rtol * max(|y_i|, |y_new_i|))`.
//!
//! # Use in a hybrid driver
//!
//! [`Integrator::step`] performs exactly one accepted step and never passes
//! the `t_stop` it is given, landing on it exactly when the step would cross
//! it (use this for the final time and for kinks of a piecewise excitation).
//! After every step the driver evaluates its event function at the new point
//! and calls [`events::locate`] with the values at both ends of the step.
//! When an event is found, [`Integrator::truncate_at`] moves the current point
//! back to the event, the driver applies its map, and
//! [`Integrator::reset_with_step`] restarts cheaply from the mapped state,
//! reusing the last step size as the initial guess.
//!
//! Everything lives on the stack: an [`Integrator`] is plain `Copy` data and
//! no step allocates.
//!
//! ```
//! use nalgebra::{SVector, Vector1, Vector2};
//! use rocking_ode::events::{locate, Direction};
//! use rocking_ode::{Integrator, Method, Options, Tolerances};
//!
//! // Bouncing ball: y = (height, velocity), impact when the height falls to 0.
//! let mut rhs = |_t: f64, y: &SVector<f64, 2>| Vector2::new(y[1], -9.81);
//! let mut g = |_t: f64, y: &SVector<f64, 2>| Vector1::new(y[0]);
//! let dirs = [Direction::Falling];
//!
//! let tol = Tolerances::uniform(1e-10, 1e-12);
//! // h_max: a flight must not fit into one step (see `events`, limitations).
//! let opts = Options { h_max: 0.05, ..Options::new(Method::Dopri5) };
//! let mut ode = Integrator::new(opts, tol).unwrap();
//! ode.reset(0.0, Vector2::new(1.0, 0.0), &mut rhs).unwrap();
//! let mut g_old = g(ode.t(), ode.y());
//! let mut bounces = Vec::new();
//! loop {
//!     let info = ode.step(&mut rhs, 3.0).unwrap();
//!     let g_new = g(ode.t(), ode.y());
//!     if let Some(ev) = locate(&mut ode, &mut g, &dirs, &g_old, &g_new) {
//!         bounces.push(ev.t);
//!         ode.truncate_at(ev.t);
//!         let mapped = Vector2::new(0.0, -0.8 * ev.y[1]); // restitution 0.8
//!         let h = ode.last_step_size();
//!         ode.reset_with_step(ev.t, mapped, h, &mut rhs).unwrap();
//!         g_old = g(ode.t(), ode.y());
//!         continue;
//!     }
//!     g_old = g_new;
//!     if info.reached {
//!         break;
//!     }
//! }
//! let t1 = (2.0 / 9.81f64).sqrt();
//! assert!((bounces[0] - t1).abs() < 1e-12);
//! assert!((bounces[1] - (t1 + 1.6 * t1)).abs() < 1e-12);
//! assert_eq!(ode.stats().events, bounces.len() as u64);
//! ```
#![warn(missing_docs)]

use nalgebra::SVector;
use std::ops::{Add, AddAssign};

mod error;
pub mod events;
pub mod poly;
pub mod roots;
mod runge_kutta;
mod tableau;
pub mod taylor;

pub use error::{OdeError, OdeErrorKind};
pub use runge_kutta::{Integrator, StepInfo};

/// The Runge–Kutta method used by an [`Integrator`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Method {
    /// Dormand–Prince 5(4), FSAL, 4th-order dense output (HNW I, II.5/II.6).
    Dopri5,
    /// DOP853: 8th order, 5th/3rd-order combined error estimate, 7th-order
    /// dense output (HNW I, II.10).
    Dop853,
}

impl Method {
    /// Classical order of the propagated solution (5 or 8).
    pub fn order(self) -> u32 {
        match self {
            Method::Dopri5 => 5,
            Method::Dop853 => 8,
        }
    }
}

/// Error tolerances: scalar relative tolerance, per-component absolute one.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Tolerances<const N: usize> {
    /// Relative tolerance (`>= 0`).
    pub rtol: f64,
    /// Absolute tolerance of each component (each `> 0`; `f64::INFINITY` leaves a component out
    /// of the error control, e.g. an integral that is only carried along).
    pub atol: SVector<f64, N>,
}

impl<const N: usize> Tolerances<N> {
    /// Same absolute tolerance for every component.
    pub fn uniform(rtol: f64, atol: f64) -> Self {
        Self {
            rtol,
            atol: SVector::from_element(atol),
        }
    }
}

/// Integrator options.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Options {
    /// Integration method.
    pub method: Method,
    /// Maximal step size (`f64::INFINITY` for none). A step may exceed it by
    /// at most 1 % when it is stretched to land on `t_stop`.
    pub h_max: f64,
    /// Initial step size used by [`Integrator::reset`]; `None` selects
    /// Hairer's `hinit` heuristic.
    pub h_init: Option<f64>,
    /// Maximal number of step attempts (accepted + rejected) between two
    /// resets.
    pub max_steps: u64,
}

impl Options {
    /// Defaults for `method`: no `h_max`, automatic initial step,
    /// `max_steps = 100_000`.
    pub fn new(method: Method) -> Self {
        Self {
            method,
            h_max: f64::INFINITY,
            h_init: None,
            max_steps: 100_000,
        }
    }
}

impl Default for Options {
    fn default() -> Self {
        Self::new(Method::Dopri5)
    }
}

/// Work counters. They accumulate over resets; add them up across runs with
/// `+` / `+=`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Stats {
    /// Accepted steps.
    pub steps: u64,
    /// Rejected step attempts.
    pub rejected: u64,
    /// Right-hand side evaluations.
    pub rhs_evals: u64,
    /// Events located by [`events::locate`].
    pub events: u64,
}

impl Add for Stats {
    type Output = Stats;
    fn add(self, o: Stats) -> Stats {
        Stats {
            steps: self.steps + o.steps,
            rejected: self.rejected + o.rejected,
            rhs_evals: self.rhs_evals + o.rhs_evals,
            events: self.events + o.events,
        }
    }
}

impl AddAssign for Stats {
    fn add_assign(&mut self, o: Stats) {
        *self = *self + o;
    }
}
