//! Taylor-series integration with the polynomial as dense output and events as its roots.
//!
//! Independent of the model, like the Runge–Kutta methods: a [`TaylorSystem`] fills the Taylor
//! coefficients of the solution through x(t0) (the generated `rocking_kernels::taylor` kernels do
//! exactly that), a [`TaylorEvents`] the coefficients of event functions along them.
//!
//! # Order and step size
//!
//! The step is Jorba & Zou's (2005, Exp. Math. 14, 99, Section 3.2): the one at which the last
//! terms of the series reach the tolerance ε. With `‖·‖` the max norm over the controlled
//! components, `ρ_j = (A / ‖x^[j]‖)^(1/j)` estimates the radius of convergence from the
//! coefficients of orders j = p−1 and p (`A = 1` when `‖x^[0]‖ ≤ 1`, absolute error, `A = ‖x^[0]‖`
//! otherwise, relative), and `h = min(ρ_{p−1}, ρ_p) · ε^(1/p) · exp(−0.7/(p−1))` (the last factor
//! is heyoka's safety factor, Biscani & Izzo 2021, MNRAS 504, 2614). So, as with the Runge–Kutta
//! methods, ε bounds the local error of a step. No error estimate and no rejected steps: one
//! coefficient evaluation per step.
//!
//! The order p minimises the cost per unit time, `(r + (p+1)²) / ε^(1/p)`: a step costs about
//! `(p+1)²` series products plus a fixed part (the driver, the step rule, the events), `r` times
//! the cost of one unit of the first ([`FIXED_COST`], measured). Jorba and Zou minimise
//! the same cost with r = 0, which gives heyoka's order `⌈−ln ε / 2 + 1⌉` and a step of `ρ / e²`
//! at every tolerance: steps as many at 1e-5 as at 1e-12 (measured: 1119 and 789 on Fig. 3),
//! and an error far below ε at loose tolerances. With the fixed cost counted, the order is higher
//! (8 at 1e-3, 12 at 1e-6, 16 at 1e-9, 20 at 1e-12) and the steps longer.
//!
//! # The order of each step
//!
//! That order is the most a step runs. Where `t_stop` caps the step anyway (the next kink of the
//! excitation: on a record, the next sample), a lower order reaches it for less: the step takes
//! the lowest order of [`ORDERS`] whose step by the rule, predicted from the last step's radius
//! of convergence, reaches `t_stop` with a margin ([`CAP_MARGIN`]), where the system allows it
//! ([`TaylorSystem::may_lower_order`]: the state's coefficients must reflect every input the
//! events see). The rule is then applied to the step's own coefficients as always, so the
//! tolerance holds whatever the prediction; a prediction that falls short costs a shorter step,
//! not accuracy. Steps capped by [`TaylorOptions::h_max`] and a fixed order
//! ([`TaylorOptions::order`]) run the highest order.
//!
//! # Why a small set of orders
//!
//! The generated kernels are generic over the number of coefficients N and always compute all N
//! (the loop bound is the const generic), so their cost is fixed at compile time, ~N². One
//! monomorphised maximum order would pay O(N_max²) at every tolerance; one instance per order
//! would multiply the driver's compile time. The order from the tolerance is therefore chosen
//! among [`ORDERS`] (10 instances per system), and a fixed order is rounded up to the next of
//! them. The integrator stores `M` coefficients per component (`M - 1` is the highest order it accepts);
//! the instance for N = order + 1 fills a stack array that is copied into that storage.
//!
//! # Excitation
//!
//! The system owns its excitation: at `t0` it supplies the ground acceleration's series of the
//! piece that starts at `t0` (a piecewise-linear record: two nonzero coefficients; a sine pulse:
//! closed form). Steps never cross the `t_stop` given to [`Taylor::step`], so the driver passes
//! the next kink there, exactly as for the Runge–Kutta methods. The step rule sees only the
//! state's coefficients: where the state does not follow the excitation (a rigid column in
//! contact) it allows any step, so bound it with [`TaylorOptions::h_max`], as the driver bounds
//! its RK contact steps (event series are truncated Taylor series too).

use crate::poly::Root;
use crate::{OdeError, OdeErrorKind, Stats};

/// A system whose solution's Taylor coefficients can be computed.
pub trait TaylorSystem<const D: usize> {
    /// On entry `x[i][0]` is the state at `t0`; fill `x[i][k]`, `k < N`, with the Taylor
    /// coefficients of the solution (`x_i(t0 + τ) ≈ Σ x[i][k] τ^k`). Must not depend on what
    /// `x[i][1..]` held on entry.
    fn coefficients<const N: usize>(&mut self, t0: f64, x: &mut [[f64; N]; D]);

    /// Whether a step from `t0` that ends at the caller's `t_stop` may run below the highest
    /// order (module docs). The step rule sees the state's coefficients only: a system with an
    /// input the state does not reflect (a rigid column in contact does not move, yet its uplift
    /// functions follow the ground acceleration) must answer false unless that input is a
    /// polynomial of low degree up to `t_stop` (a record's piece), which any order keeps exact.
    fn may_lower_order(&mut self, _t0: f64) -> bool {
        true
    }
}

/// Event functions evaluated along a step's Taylor polynomial.
pub trait TaylorEvents<const D: usize, const E: usize> {
    /// The first N Taylor coefficients of each of the E event functions along the state series
    /// `x` expanded at `t0` (e.g. the generated `uplift::<N>`).
    fn event_coefficients<const N: usize>(&mut self, t0: f64, x: &[[f64; N]; D]) -> [[f64; N]; E];
}

pub use step::{order_from_tol, supported_order, CAP_MARGIN, FIXED_COST, ORDERS};

/// Options of a [`Taylor`] integrator.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TaylorOptions<const D: usize> {
    /// Tolerance ε of the step rule (absolute where the state is ≤ 1, relative above).
    pub tol: f64,
    /// Fixed order instead of [`order_from_tol`] (rounded up to [`ORDERS`] either way).
    pub order: Option<usize>,
    /// Maximal step size (`f64::INFINITY` for none).
    pub h_max: f64,
    /// Maximal number of steps between two resets.
    pub max_steps: u64,
    /// Components in the step rule's norms (`false`: carried along, e.g. work integrals).
    pub controlled: [bool; D],
}

impl<const D: usize> TaylorOptions<D> {
    /// Defaults: order from `tol`, no `h_max`, 100 000 steps, every component controlled.
    pub fn new(tol: f64) -> Self {
        Self {
            tol,
            order: None,
            h_max: f64::INFINITY,
            max_steps: 100_000,
            controlled: [true; D],
        }
    }
}

/// An event located on the last step of a [`Taylor`] integrator.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TaylorEvent<const D: usize> {
    /// Event component that fires first (lowest index on ties).
    pub index: usize,
    /// Event time `t_old + root.tau`, in `(t_old, t_new]` (`t_new` exactly for a root at the
    /// step end).
    pub t: f64,
    /// State at `t` (the step's polynomial; the step's end state when `t` is its end).
    pub y: [f64; D],
    /// The root on the step.
    pub root: Root,
}

/// A Taylor-series integrator for a state of `D` components storing `M` coefficients each
/// (orders up to `M - 1`). Plain `Copy` data, no allocation.
#[derive(Clone, Copy, Debug)]
pub struct Taylor<const D: usize, const M: usize = 21> {
    opts: TaylorOptions<D>,
    /// The highest order a step runs (from the tolerance, or the fixed order).
    max_order: usize,
    /// The order of the last step (`max_order` before the first).
    order: usize,
    /// `ln(ε^(1/p) · exp(−0.7/(p−1)))` for each of [`ORDERS`]: the step is ρ times its exp.
    ln_fac: [f64; ORDERS.len()],
    /// ln of the last step's radius of convergence `min(ρ_{p−1}, ρ_p)` (NaN when unknown).
    ln_rho: f64,
    /// The step rule's step of the last step when it ran the highest order (before `h_max` and
    /// `t_stop`; NaN otherwise): every lower order's step is shorter (module docs).
    h_rule_max: f64,
    t: f64,
    y: [f64; D],
    initialised: bool,
    t_old: f64,
    h_last: f64,
    /// Length of the last step still valid (less than `h_last` after `truncate_at`).
    h_valid: f64,
    has_step: bool,
    steps_since_reset: u64,
    /// Coefficients of the last step (expanded at `t_old`), orders `0..=order`; the rest zero.
    coef: [[f64; M]; D],
    stats: Stats,
}

/// The next f64 above a finite `x` (`f64::next_up` is newer than the MSRV).
fn next_up(x: f64) -> f64 {
    if x == 0.0 {
        f64::from_bits(1)
    } else if x > 0.0 {
        f64::from_bits(x.to_bits() + 1)
    } else {
        f64::from_bits(x.to_bits() - 1)
    }
}

fn err(kind: OdeErrorKind, t: f64, m: String) -> OdeError {
    OdeError {
        kind,
        t,
        message: m,
    }
}

/// `$f::<types.., N>(args)` with N = order + 1, for an order of [`ORDERS`].
macro_rules! by_order {
    ($order:expr, $($f:ident)::+ ; $($g:ty),* ; $($arg:expr),*) => {
        match $order {
            3 => $($f)::+::<$($g,)* 4>($($arg),*),
            4 => $($f)::+::<$($g,)* 5>($($arg),*),
            5 => $($f)::+::<$($g,)* 6>($($arg),*),
            6 => $($f)::+::<$($g,)* 7>($($arg),*),
            8 => $($f)::+::<$($g,)* 9>($($arg),*),
            10 => $($f)::+::<$($g,)* 11>($($arg),*),
            12 => $($f)::+::<$($g,)* 13>($($arg),*),
            14 => $($f)::+::<$($g,)* 15>($($arg),*),
            16 => $($f)::+::<$($g,)* 17>($($arg),*),
            20 => $($f)::+::<$($g,)* 21>($($arg),*),
            o => unreachable!("order {o} is not in ORDERS"),
        }
    };
}

mod dense;
mod step;

impl<const D: usize, const M: usize> Taylor<D, M> {
    /// Create an integrator; fails on a tolerance outside (0, 1), `h_max <= 0`, or an order
    /// above `M - 1` or 20.
    pub fn new(opts: TaylorOptions<D>) -> Result<Self, OdeError> {
        let bad = |m: String| Err(err(OdeErrorKind::InvalidInput, f64::NAN, m));
        if !(opts.tol > 0.0 && opts.tol < 1.0) {
            return bad(format!("tol = {} must be in (0, 1)", opts.tol));
        }
        if opts.h_max.is_nan() || opts.h_max <= 0.0 {
            return bad("h_max must be > 0 (f64::INFINITY for no limit)".into());
        }
        let want = opts.order.unwrap_or_else(|| order_from_tol(opts.tol));
        let Some(order) = supported_order(want) else {
            return bad(format!("order {want} above the highest supported, 20"));
        };
        if order + 1 > M {
            return bad(format!("order {order} needs M >= {}, M = {M}", order + 1));
        }
        let ln_fac = ORDERS.map(|p| {
            let p = p as f64;
            opts.tol.ln() / p - 0.7 / (p - 1.0)
        });
        Ok(Self {
            opts,
            max_order: order,
            order,
            ln_fac,
            ln_rho: f64::NAN,
            h_rule_max: f64::NAN,
            t: f64::NAN,
            y: [0.0; D],
            initialised: false,
            t_old: f64::NAN,
            h_last: 0.0,
            h_valid: 0.0,
            has_step: false,
            steps_since_reset: 0,
            coef: [[0.0; M]; D],
            stats: Stats::default(),
        })
    }

    /// Restart at `(t0, y0)` (no evaluation: the coefficients are computed by the next step; the
    /// first step runs the highest order, as on a new integrator).
    pub fn reset(&mut self, t0: f64, y0: [f64; D]) -> Result<(), OdeError> {
        self.initialised = false;
        self.has_step = false;
        if !t0.is_finite() || !y0.iter().all(|v| v.is_finite()) {
            return Err(err(
                OdeErrorKind::NonFinite,
                t0,
                format!("non-finite initial time or state {y0:?}"),
            ));
        }
        self.t = t0;
        self.y = y0;
        self.t_old = t0;
        self.h_last = 0.0;
        self.ln_rho = f64::NAN;
        self.h_rule_max = f64::NAN;
        self.steps_since_reset = 0;
        self.initialised = true;
        Ok(())
    }

    /// The coefficients of the last step (expanded at [`t_old`](Self::t_old)), orders
    /// `0..=`[`order`](Self::order); e.g. θ's row is an event polynomial for [`poly::first_root`](crate::poly::first_root).
    pub fn coefficients(&self) -> &[[f64; M]; D] {
        &self.coef
    }

    /// The order of the last step (before the first: the highest a step runs).
    pub fn order(&self) -> usize {
        self.order
    }

    /// The highest order a step runs: from the tolerance, or the fixed order (module docs).
    pub fn max_order(&self) -> usize {
        self.max_order
    }

    /// Current time.
    pub fn t(&self) -> f64 {
        self.t
    }

    /// Current state.
    pub fn y(&self) -> &[f64; D] {
        &self.y
    }

    /// Start of the last step.
    pub fn t_old(&self) -> f64 {
        self.t_old
    }

    /// Length of the last step (0 before the first).
    pub fn last_step_size(&self) -> f64 {
        self.h_last
    }

    /// Whether a step has been taken since the last reset.
    pub fn has_step(&self) -> bool {
        self.has_step
    }

    /// Work counters (`rhs_evals` counts coefficient evaluations, one per step).
    pub fn stats(&self) -> Stats {
        self.stats
    }

    /// Reset the work counters to zero, returning the old ones.
    pub fn take_stats(&mut self) -> Stats {
        std::mem::take(&mut self.stats)
    }

    /// The options.
    pub fn options(&self) -> &TaylorOptions<D> {
        &self.opts
    }
}
