//! The step rule and the order of each step (module docs of [`super`]).

use super::dense::end_state;
use super::{err, Taylor, TaylorSystem};
use crate::{OdeError, OdeErrorKind, StepInfo};

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

impl<const D: usize, const M: usize> Taylor<D, M> {
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
}
