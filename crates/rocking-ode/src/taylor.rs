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

use crate::events::Direction;
use crate::poly::{self, Root};
use crate::{OdeError, OdeErrorKind, Stats, StepInfo};

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

/// The orders an integrator can run (a requested order is rounded up to the next of these).
pub const ORDERS: [usize; 10] = [3, 4, 5, 6, 8, 10, 12, 14, 16, 20];

/// The fixed cost of a step in units of the kernel's cost per squared number of coefficients:
/// fitting `F + a (p+1)²` to the ns per step at orders 8, 12, 16 and 20 gives F/a ≈ 50 on the
/// point-mass and full variants; 100 reproduces their cheapest orders at 1e-6, 1e-9 and 1e-12
/// (`rocking-bench probe`), where the events' fixed costs grow with the step's length too.
pub const FIXED_COST: f64 = 100.0;

/// How far beyond a step's cap the predicted step of a lowered order must reach (module docs):
/// the radius of convergence changes from step to step, and a step that falls just short of the
/// cap costs a whole extra step.
pub const CAP_MARGIN: f64 = 1.5;

/// The order of [`ORDERS`] with the least cost per unit time at tolerance `tol` (module docs):
/// the minimum of `ln(FIXED_COST + (p+1)²) − ln(tol) / p`.
pub fn order_from_tol(tol: f64) -> usize {
    let cost = |p: usize| {
        let n = (p + 1) as f64;
        (FIXED_COST + n * n).ln() - tol.ln() / p as f64
    };
    ORDERS
        .iter()
        .copied()
        .min_by(|&a, &b| cost(a).total_cmp(&cost(b)))
        .expect("ORDERS is not empty")
}

/// The order actually run for a requested order `p`: the next of [`ORDERS`] (None above 20).
pub fn supported_order(p: usize) -> Option<usize> {
    ORDERS.iter().copied().find(|&o| o >= p)
}

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

/// Every component's polynomial of orders `0..=p` at `tau`, by Horner's rule on all components in
/// step: one chain of p multiply-adds the CPU overlaps, not D chains one after the other. The same
/// operations as [`poly::horner`] per component, so the same values.
fn horner_all<const D: usize, const M: usize>(
    coef: &[[f64; M]; D],
    p: usize,
    tau: f64,
) -> [f64; D] {
    let mut y = [0.0; D];
    for k in (0..=p).rev() {
        for (yi, ci) in y.iter_mut().zip(coef) {
            *yi = *yi * tau + ci[k];
        }
    }
    y
}

/// Every component's polynomial of orders `0..=p` at the step's end `tau`, in two halves, as the
/// first level of Estrin's scheme: `lo(τ) + τ^m hi(τ)`, each half by Horner's rule and `τ^m`
/// beside them. The end state is the one result the next step waits for (its kernel starts from
/// it), and Horner's 16 dependent multiply-adds at order 16 were the longest wait of a step:
/// the halves take 8 or 9 each, the CPU runs them side by side (`rocking-bench probe`: 2-4 % per
/// simulation on Fig. 3 and the full-mass case). Within a few ulp of [`horner_all`]; the step's
/// other points (dense output, events) are Horner's.
fn end_state<const D: usize, const M: usize>(coef: &[[f64; M]; D], p: usize, tau: f64) -> [f64; D] {
    let m = p.div_ceil(2);
    // hi holds orders m..=p: p − m + 1 = m + 1 of them for an even p, whose highest starts it.
    let mut hi: [f64; D] = std::array::from_fn(|i| if 2 * m <= p { coef[i][p] } else { 0.0 });
    let mut lo = [0.0; D];
    for k in (0..m).rev() {
        for ((l, h), ci) in lo.iter_mut().zip(hi.iter_mut()).zip(coef) {
            *l = *l * tau + ci[k];
            *h = *h * tau + ci[k + m];
        }
    }
    let mut tau_m = tau;
    for _ in 1..m {
        tau_m *= tau;
    }
    std::array::from_fn(|i| lo[i] + tau_m * hi[i])
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

    /// One step by the step rule (module docs), never past `t_stop` (landing on it exactly when the step would
    /// reach it or end within 1 % of a step before it). Forward only.
    pub fn step<S: TaylorSystem<D>>(
        &mut self,
        sys: &mut S,
        t_stop: f64,
    ) -> Result<StepInfo, OdeError> {
        self.step_impl(sys, t_stop, None)
    }

    /// One step of length `h` (or to `t_stop`), without the step rule: for order studies and for
    /// callers with their own control.
    pub fn step_fixed<S: TaylorSystem<D>>(
        &mut self,
        sys: &mut S,
        h: f64,
        t_stop: f64,
    ) -> Result<StepInfo, OdeError> {
        if !(h > 0.0 && h.is_finite()) {
            return Err(err(
                OdeErrorKind::InvalidInput,
                self.t,
                format!("h = {h} must be > 0"),
            ));
        }
        self.step_impl(sys, t_stop, Some(h))
    }

    fn step_impl<S: TaylorSystem<D>>(
        &mut self,
        sys: &mut S,
        t_stop: f64,
        fixed: Option<f64>,
    ) -> Result<StepInfo, OdeError> {
        if !self.initialised {
            return Err(err(
                OdeErrorKind::NotInitialised,
                self.t,
                "step called before reset".into(),
            ));
        }
        if t_stop.is_nan() || t_stop <= self.t {
            return Err(err(
                OdeErrorKind::InvalidInput,
                self.t,
                format!("t_stop = {t_stop} is not after the current time"),
            ));
        }
        if self.steps_since_reset >= self.opts.max_steps {
            return Err(err(
                OdeErrorKind::MaxSteps,
                self.t,
                format!("more than max_steps = {} steps", self.opts.max_steps),
            ));
        }
        let order = self.order_for(sys, t_stop);
        by_order!(order, Self::step_n; S; self, sys, t_stop, fixed)
    }

    /// The order of the next step (module docs): the lowest of [`ORDERS`] whose predicted step
    /// reaches `t_stop` with [`CAP_MARGIN`], where `t_stop` caps the step (not `h_max`: it
    /// stands for an input's resolution, which a lower order would truncate) and the system
    /// allows it; else the highest.
    fn order_for<S: TaylorSystem<D>>(&self, sys: &mut S, t_stop: f64) -> usize {
        let cap = t_stop - self.t;
        if self.opts.order.is_some() || self.ln_rho.is_nan() || cap > self.opts.h_max {
            return self.max_order;
        }
        // A cap beyond the highest order's step (with a margin far above the rounding of its
        // exp and of the ln below) is beyond every lower order's: `ln_fac` grows with the order,
        // by at least 0.7 (1/15 − 1/19) ≈ 0.01 from one of ORDERS to the next. Most steps; no
        // logarithm for them.
        if cap * CAP_MARGIN > self.h_rule_max * (1.0 + 1e-9) {
            return self.max_order;
        }
        let ln_cap = (cap * CAP_MARGIN).ln();
        let lower = ORDERS
            .iter()
            .zip(&self.ln_fac)
            .take_while(|(&p, _)| p < self.max_order)
            .find(|(_, &f)| self.ln_rho + f >= ln_cap)
            .map(|(&p, _)| p);
        match lower {
            Some(p) if sys.may_lower_order(self.t) => p,
            _ => self.max_order,
        }
    }

    /// One step at order `N − 1`: the coefficients in a stack array of N, stored on success.
    fn step_n<S: TaylorSystem<D>, const N: usize>(
        &mut self,
        sys: &mut S,
        t_stop: f64,
        fixed: Option<f64>,
    ) -> Result<StepInfo, OdeError> {
        let mut x = [[0.0; N]; D];
        for (c, &y) in x.iter_mut().zip(&self.y) {
            c[0] = y;
        }
        sys.coefficients::<N>(self.t, &mut x);
        self.stats.rhs_evals += 1;
        let p = N - 1;
        // A non-finite coefficient is reported as such, before any error it causes below. It is
        // looked for only on the way to an error: every coefficient enters the end state through
        // one of [`end_state`]'s Horner chains with a finite τ > 0, and a non-finite value stays
        // non-finite along a chain and in `lo + τ^m hi`, so a finite end state proves them all
        // finite (and the scan, reading as vectors what the system had just stored, stalled
        // every step).
        let fail = |e: OdeError| -> Result<StepInfo, OdeError> {
            let non_finite = x.iter().flatten().any(|v| !v.is_finite());
            Err(if non_finite {
                err(
                    OdeErrorKind::NonFinite,
                    self.t,
                    "non-finite Taylor coefficient".into(),
                )
            } else {
                e
            })
        };
        let ln_rho = self.ln_rho(&x);
        let h_rule = match fixed {
            Some(_) => f64::NAN,
            None => {
                let k = ORDERS.iter().position(|&o| o == p).expect("p is in ORDERS");
                (ln_rho + self.ln_fac[k]).exp()
            }
        };
        let h_ctrl = fixed.unwrap_or(h_rule).min(self.opts.h_max);
        if h_ctrl.is_nan() || h_ctrl <= 10.0 * f64::EPSILON * self.t.abs() || h_ctrl < 1e-300 {
            return fail(err(
                OdeErrorKind::StepSizeUnderflow,
                self.t,
                format!("step size underflow (h = {h_ctrl:e})"),
            ));
        }
        let reaches = self.t + 1.01 * h_ctrl >= t_stop;
        let h = if reaches { t_stop - self.t } else { h_ctrl };
        if !h.is_finite() {
            return fail(err(
                OdeErrorKind::InvalidInput,
                self.t,
                "infinite step (polynomial solution, no h_max and no finite t_stop)".into(),
            ));
        }
        let y_new = end_state(&x, p, h);
        if !y_new.iter().all(|v| v.is_finite()) {
            return fail(err(
                OdeErrorKind::NonFinite,
                self.t,
                format!("non-finite state {y_new:?} at the end of a step of {h:e}"),
            ));
        }
        // The orders above p stay zero (`coefficients`), so only a lower order than the last
        // step's clears any.
        for (c, xi) in self.coef.iter_mut().zip(&x) {
            c[..N].copy_from_slice(xi);
            if self.order > p {
                c[N..=self.order].fill(0.0);
            }
        }
        self.order = p;
        self.ln_rho = ln_rho;
        self.h_rule_max = if p == self.max_order {
            h_rule
        } else {
            f64::NAN
        };
        self.t_old = self.t;
        self.h_last = h;
        self.h_valid = h;
        self.t = if reaches { t_stop } else { self.t + h };
        self.y = y_new;
        self.has_step = true;
        self.steps_since_reset += 1;
        self.stats.steps += 1;
        Ok(StepInfo {
            t_old: self.t_old,
            t_new: self.t,
            reached: reaches,
        })
    }

    /// `ln min(ρ_{p−1}, ρ_p)` of a step's coefficients of orders `0..=p` (module docs); the
    /// step is this radius times `ε^(1/p) · exp(−0.7/(p−1))`.
    fn ln_rho<const N: usize>(&self, x: &[[f64; N]; D]) -> f64 {
        let p = N - 1;
        let (mut n0, mut n1, mut n2) = (0.0f64, 0.0f64, 0.0f64);
        for i in (0..D).filter(|&i| self.opts.controlled[i]) {
            n0 = n0.max(x[i][0].abs());
            n1 = n1.max(x[i][p - 1].abs());
            n2 = n2.max(x[i][p].abs());
        }
        let a = if n0 <= 1.0 { 1.0 } else { n0 };
        // Through the logarithms: two `ln`, not two `powf`.
        let ln_rho1 = (a / n1).ln() / (p - 1) as f64;
        let ln_rho2 = (a / n2).ln() / p as f64;
        ln_rho1.min(ln_rho2)
    }

    /// The step's polynomial at `t` in `[t_old, t_new]` (Horner); exactly the step's end (start)
    /// state at its end (start). Before any step: the current state.
    pub fn dense(&self, t: f64) -> [f64; D] {
        if !self.has_step || t == self.t {
            return self.y;
        }
        if t == self.t_old {
            return std::array::from_fn(|i| self.coef[i][0]);
        }
        horner_all(&self.coef, self.order, t - self.t_old)
    }

    /// Component `i` of [`dense`](Self::dense) alone (one Horner sum instead of D).
    pub fn dense_component(&self, i: usize, t: f64) -> f64 {
        if !self.has_step || t == self.t {
            return self.y[i];
        }
        if t == self.t_old {
            return self.coef[i][0];
        }
        poly::horner(&self.coef[i][..=self.order], t - self.t_old)
    }

    /// Time derivative of the step's polynomial at `t`.
    pub fn dense_derivative(&self, t: f64) -> [f64; D] {
        let tau = t - self.t_old;
        self.coef.map(|c| {
            (1..=self.order)
                .rev()
                .fold(0.0, |acc, k| acc * tau + k as f64 * c[k])
        })
    }

    /// Move the current point back to `t_event` in the last step (clamped to it); the polynomial
    /// stays available on `[t_old, t_event]`. The next step expands afresh at `t_event`.
    pub fn truncate_at(&mut self, t_event: f64) {
        if !self.has_step || t_event == self.t || t_event.is_nan() {
            return;
        }
        let te = t_event.clamp(self.t_old, self.t);
        self.y = self.dense(te);
        self.t = te;
        self.h_valid = te - self.t_old;
    }

    /// The earliest root in `(t_old, t]` of the event functions' polynomials on the last
    /// step (up to the current point, which [`truncate_at`](Self::truncate_at) may have moved), per component in its direction (see [`poly::first_root`]); counted in
    /// [`Stats::events`]. Costs one event-series evaluation, no state evaluation. As with the
    /// RK events, a component exactly 0 at the step start does not trigger there: the driver's
    /// map should put the state on the surface exactly (a restart a few ulp off it sees a real
    /// crossing of the polynomial at once).
    pub fn locate<V: TaylorEvents<D, E>, const E: usize>(
        &mut self,
        ev: &mut V,
        dirs: &[Direction; E],
    ) -> Option<TaylorEvent<D>> {
        if !self.has_step {
            return None;
        }
        if self.h_valid <= 0.0 {
            return None;
        }
        let (index, root) = by_order!(self.order, Self::first_event_n; V, E; self, ev, dirs)?;
        self.stats.events += 1;
        // At the step end exactly t_new; otherwise after t_old even when τ is below its ulp.
        let t = if root.tau == self.h_valid {
            self.t
        } else {
            (self.t_old + root.tau).max(next_up(self.t_old)).min(self.t)
        };
        Some(TaylorEvent {
            index,
            t,
            y: self.dense(t),
            root,
        })
    }

    /// The earliest root of the event functions on the last step (for [`locate`](Self::locate)),
    /// their series of N = order + 1 coefficients in stack arrays.
    fn first_event_n<V: TaylorEvents<D, E>, const E: usize, const N: usize>(
        &self,
        ev: &mut V,
        dirs: &[Direction; E],
    ) -> Option<(usize, Root)> {
        let x: [[f64; N]; D] = std::array::from_fn(|i| std::array::from_fn(|k| self.coef[i][k]));
        let g = ev.event_coefficients::<N>(self.t_old, &x);
        let mut best: Option<(usize, Root)> = None;
        for (j, gj) in g.iter().enumerate() {
            if let Some(r) = poly::first_root(gj, self.h_valid, dirs[j]) {
                if best.is_none_or(|(_, b)| r.tau < b.tau) {
                    best = Some((j, r));
                }
            }
        }
        best
    }

    /// The coefficients of the last step (expanded at [`t_old`](Self::t_old)), orders
    /// `0..=`[`order`](Self::order); e.g. θ's row is an event polynomial for [`poly::first_root`].
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
