//! The explicit Runge–Kutta integrator (Dormand–Prince 5(4) and DOP853): steps, step-size
//! control, dense output and the state a driver restarts from.

use nalgebra::SVector;

use crate::tableau::{self, Row};
use crate::{Method, OdeError, OdeErrorKind, Options, Stats, Tolerances};

/// Result of one accepted step.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StepInfo {
    /// Start of the step.
    pub t_old: f64,
    /// End of the step (the new current time).
    pub t_new: f64,
    /// `true` when the step landed exactly on `t_stop`.
    pub reached: bool,
}

/// Number of stored stages (DOP853 incl. FSAL and dense-output stages).
const STAGES: usize = 16;

/// An explicit Runge–Kutta integrator with step-size control and dense output
/// for a state of fixed dimension `N`.
///
/// Plain `Copy` data: stages, dense-output coefficients and counters are held
/// inline, nothing is allocated.
#[derive(Clone, Copy, Debug)]
pub struct Integrator<const N: usize> {
    opts: Options,
    tol: Tolerances<N>,
    /// Number of error-controlled components (finite atol): the RMS error norm averages over
    /// these only, so a carried-along component (atol = +inf) does not loosen the tolerance.
    controlled: f64,
    /// Current time and state.
    t: f64,
    y: SVector<f64, N>,
    /// f(t, y) (exact unless `fsal_valid` is false, then approximated from
    /// the dense output after `truncate_at`).
    dy: SVector<f64, N>,
    fsal_valid: bool,
    initialised: bool,
    /// Step size to try next.
    h_next: f64,
    /// Last accepted step: start, nominal length, and whether one exists.
    t_old: f64,
    h_last: f64,
    has_step: bool,
    /// Hairer's `facold` for the PI controller.
    facold: f64,
    /// Attempts since the last reset (for `max_steps`).
    attempts: u64,
    k: [SVector<f64, N>; STAGES],
    /// Dense-output coefficients (5 used by Dopri5, 8 by DOP853).
    cont: [SVector<f64, N>; 8],
    stats: Stats,
}

/// Controller constants.
struct Ctrl {
    /// Exponent alpha = 1/q - 0.75 beta (q = 5 or 8).
    expo1: f64,
    beta: f64,
    safe: f64,
    /// Minimal factor h_new/h.
    facmin: f64,
    /// Maximal factor h_new/h.
    facmax: f64,
}

const DOPRI5_CTRL: Ctrl = Ctrl {
    expo1: 0.2 - 0.04 * 0.75,
    beta: 0.04,
    safe: 0.9,
    facmin: 0.2,
    facmax: 10.0,
};

const DOP853_CTRL: Ctrl = Ctrl {
    expo1: 1.0 / 8.0,
    beta: 0.0,
    safe: 0.9,
    facmin: 0.333,
    facmax: 6.0,
};

#[inline(always)]
fn comb<const N: usize>(k: &[SVector<f64, N>; STAGES], row: Row) -> SVector<f64, N> {
    let mut s = SVector::<f64, N>::zeros();
    for &(j, a) in row {
        s.axpy(a, &k[j], 1.0);
    }
    s
}

fn all_finite<const N: usize>(v: &SVector<f64, N>) -> bool {
    v.iter().all(|x| x.is_finite())
}

impl<const N: usize> Integrator<N> {
    /// Create an integrator. It must be [`reset`](Self::reset) before the
    /// first step. Fails on invalid tolerances or options.
    pub fn new(opts: Options, tol: Tolerances<N>) -> Result<Self, OdeError> {
        let bad = |m: &str| {
            Err(OdeError::new(
                OdeErrorKind::InvalidInput,
                f64::NAN,
                m.into(),
            ))
        };
        if !(tol.rtol >= 0.0 && tol.rtol.is_finite()) {
            return bad("rtol must be finite and >= 0");
        }
        if !tol.atol.iter().all(|&a| a > 0.0 && !a.is_nan()) {
            return bad("every atol component must be > 0 (+inf: not error-controlled)");
        }
        let controlled = tol.atol.iter().filter(|a| a.is_finite()).count().max(1) as f64;
        if opts.h_max.is_nan() || opts.h_max <= 0.0 {
            return bad("h_max must be > 0 (use f64::INFINITY for no limit)");
        }
        if let Some(h) = opts.h_init {
            if !(h > 0.0 && h.is_finite()) {
                return bad("h_init must be finite and > 0");
            }
        }
        let z = SVector::<f64, N>::zeros();
        Ok(Self {
            opts,
            tol,
            controlled,
            t: f64::NAN,
            y: z,
            dy: z,
            fsal_valid: false,
            initialised: false,
            h_next: f64::NAN,
            t_old: f64::NAN,
            h_last: 0.0,
            has_step: false,
            facold: 1e-4,
            attempts: 0,
            k: [z; STAGES],
            cont: [z; 8],
            stats: Stats::default(),
        })
    }

    /// Restart at `(t0, y0)`; the initial step is [`Options::h_init`] or
    /// Hairer's `hinit` estimate. Costs one RHS evaluation (two with
    /// `hinit`). Statistics are kept.
    pub fn reset<F>(&mut self, t0: f64, y0: SVector<f64, N>, rhs: &mut F) -> Result<(), OdeError>
    where
        F: FnMut(f64, &SVector<f64, N>) -> SVector<f64, N>,
    {
        self.reset_impl(t0, y0, self.opts.h_init, rhs)
    }

    /// Restart at `(t0, y0)` using `h` (e.g. [`last_step_size`](Self::last_step_size)
    /// before an event) as the initial step size; falls back to
    /// [`reset`](Self::reset)'s choice when `h` is not finite and positive.
    /// Costs one RHS evaluation.
    pub fn reset_with_step<F>(
        &mut self,
        t0: f64,
        y0: SVector<f64, N>,
        h: f64,
        rhs: &mut F,
    ) -> Result<(), OdeError>
    where
        F: FnMut(f64, &SVector<f64, N>) -> SVector<f64, N>,
    {
        let hint = if h > 0.0 && h.is_finite() {
            Some(h)
        } else {
            self.opts.h_init
        };
        self.reset_impl(t0, y0, hint, rhs)
    }

    fn reset_impl<F>(
        &mut self,
        t0: f64,
        y0: SVector<f64, N>,
        h: Option<f64>,
        rhs: &mut F,
    ) -> Result<(), OdeError>
    where
        F: FnMut(f64, &SVector<f64, N>) -> SVector<f64, N>,
    {
        self.initialised = false;
        self.has_step = false;
        if !t0.is_finite() || !all_finite(&y0) {
            return Err(OdeError::new(
                OdeErrorKind::NonFinite,
                t0,
                format!("non-finite initial time or state {y0:?}"),
            ));
        }
        let f0 = rhs(t0, &y0);
        self.stats.rhs_evals += 1;
        if !all_finite(&f0) {
            return Err(OdeError::new(
                OdeErrorKind::NonFinite,
                t0,
                format!("non-finite right-hand side {f0:?} at the initial state"),
            ));
        }
        self.t = t0;
        self.y = y0;
        self.dy = f0;
        self.fsal_valid = true;
        self.facold = 1e-4;
        self.attempts = 0;
        self.t_old = t0;
        self.h_last = 0.0;
        self.h_next = match h {
            Some(h) => h.min(self.opts.h_max),
            None => self.hinit(rhs),
        };
        self.initialised = true;
        Ok(())
    }

    /// Hairer's initial step-size heuristic (`hinit` in dopri5.f/dop853.f).
    fn hinit<F>(&mut self, rhs: &mut F) -> f64
    where
        F: FnMut(f64, &SVector<f64, N>) -> SVector<f64, N>,
    {
        let (t, y, f0) = (self.t, self.y, self.dy);
        let sk = self.tol.atol + y.abs() * self.tol.rtol;
        let dnf = f0.component_div(&sk).norm_squared();
        let dny = y.component_div(&sk).norm_squared();
        let mut h = if dnf <= 1e-10 || dny <= 1e-10 {
            1e-6
        } else {
            (dny / dnf).sqrt() * 0.01
        };
        h = h.min(self.opts.h_max);
        let y1 = y + f0 * h;
        let f1 = rhs(t + h, &y1);
        self.stats.rhs_evals += 1;
        let der2 = (f1 - f0).component_div(&sk).norm() / h;
        let der12 = der2.abs().max(dnf.sqrt());
        let h1 = if der12 <= 1e-15 {
            (h * 1e-3).max(1e-6)
        } else {
            (0.01 / der12).powf(1.0 / self.opts.method.order() as f64)
        };
        let h = (100.0 * h).min(h1).min(self.opts.h_max);
        if h > 0.0 && h.is_finite() {
            h
        } else {
            1e-6f64.min(self.opts.h_max)
        }
    }

    /// Perform one accepted step (rejected attempts are retried internally)
    /// without passing `t_stop`; a step that would reach or pass `t_stop`
    /// (or end within 1 % of a step before it) is set to land on `t_stop`
    /// exactly. Integration is forward only: `t_stop` must exceed `t()`.
    ///
    /// Errors: step-size underflow (`h <= 10 eps |t|`), non-finite stage,
    /// state or error estimate (returned immediately, the step is not
    /// retried), `max_steps` attempts since the last reset, `t_stop <= t`.
    /// On error the current point is unchanged.
    pub fn step<F>(&mut self, rhs: &mut F, t_stop: f64) -> Result<StepInfo, OdeError>
    where
        F: FnMut(f64, &SVector<f64, N>) -> SVector<f64, N>,
    {
        if !self.initialised {
            return Err(OdeError::new(
                OdeErrorKind::NotInitialised,
                self.t,
                "step called before reset".into(),
            ));
        }
        if t_stop.is_nan() || t_stop <= self.t {
            return Err(OdeError::new(
                OdeErrorKind::InvalidInput,
                self.t,
                format!("t_stop = {t_stop} is not after the current time"),
            ));
        }
        if !self.fsal_valid {
            let f = rhs(self.t, &self.y);
            self.stats.rhs_evals += 1;
            if !all_finite(&f) {
                return Err(OdeError::new(
                    OdeErrorKind::NonFinite,
                    self.t,
                    format!("non-finite right-hand side {f:?}"),
                ));
            }
            self.dy = f;
            self.fsal_valid = true;
        }
        let ctrl = match self.opts.method {
            Method::Dopri5 => &DOPRI5_CTRL,
            Method::Dop853 => &DOP853_CTRL,
        };
        let mut rejected = false;
        loop {
            if self.attempts >= self.opts.max_steps {
                return Err(OdeError::new(
                    OdeErrorKind::MaxSteps,
                    self.t,
                    format!("more than max_steps = {} attempts", self.opts.max_steps),
                ));
            }
            let h_ctrl = self.h_next.min(self.opts.h_max);
            if h_ctrl.is_nan() || h_ctrl <= 10.0 * f64::EPSILON * self.t.abs() || h_ctrl < 1e-300 {
                return Err(OdeError::new(
                    OdeErrorKind::StepSizeUnderflow,
                    self.t,
                    format!("step size underflow (h = {h_ctrl:e})"),
                ));
            }
            let mut h = h_ctrl;
            let reaches = self.t + 1.01 * h >= t_stop;
            if reaches {
                h = t_stop - self.t;
            }
            self.attempts += 1;
            let (y_new, err) = match self.opts.method {
                Method::Dopri5 => self.attempt_dopri5(rhs, h),
                Method::Dop853 => self.attempt_dop853(rhs, h),
            };
            if !all_finite(&y_new) || !err.is_finite() {
                return Err(OdeError::new(
                    OdeErrorKind::NonFinite,
                    self.t,
                    format!(
                        "non-finite stage, state or error estimate in a step of size {h:e} \
                         (y_new = {y_new:?})"
                    ),
                ));
            }
            let fac11 = err.powf(ctrl.expo1);
            if err <= 1.0 {
                // Accepted.
                let f_new = match self.opts.method {
                    Method::Dopri5 => self.k[6],
                    Method::Dop853 => {
                        let f = rhs(self.t + h, &y_new);
                        self.stats.rhs_evals += 1;
                        f
                    }
                };
                if !all_finite(&f_new) {
                    return Err(OdeError::new(
                        OdeErrorKind::NonFinite,
                        self.t + h,
                        format!("non-finite right-hand side {f_new:?} at the end of a step"),
                    ));
                }
                // Hairer's PI controller: fac = err^alpha / errold^beta.
                let fac = (fac11 / self.facold.powf(ctrl.beta) / ctrl.safe)
                    .clamp(1.0 / ctrl.facmax, 1.0 / ctrl.facmin);
                let mut h_new = h / fac;
                self.facold = err.max(1e-4);
                if rejected {
                    h_new = h_new.min(h);
                }
                if reaches {
                    // A step shortened to hit t_stop says little about the
                    // step size the solution allows: keep the larger proposal.
                    h_new = h_new.max(h_ctrl);
                }
                match self.opts.method {
                    Method::Dopri5 => self.dense_dopri5(h, &y_new, &f_new),
                    Method::Dop853 => self.dense_dop853(rhs, h, &y_new, &f_new),
                }
                self.t_old = self.t;
                self.h_last = h;
                self.t = if reaches { t_stop } else { self.t + h };
                self.y = y_new;
                self.dy = f_new;
                self.h_next = h_new;
                self.has_step = true;
                self.stats.steps += 1;
                return Ok(StepInfo {
                    t_old: self.t_old,
                    t_new: self.t,
                    reached: reaches,
                });
            }
            // Rejected: shrink, no increase afterwards.
            self.stats.rejected += 1;
            rejected = true;
            self.h_next = h / (1.0 / ctrl.facmin).min(fac11 / ctrl.safe);
        }
    }

    /// One Dopri5 attempt of size `h`; stages in `self.k[0..7]`, `k[6]` is
    /// f(t+h, y_new). Returns `(y_new, err)`.
    fn attempt_dopri5<F>(&mut self, rhs: &mut F, h: f64) -> (SVector<f64, N>, f64)
    where
        F: FnMut(f64, &SVector<f64, N>) -> SVector<f64, N>,
    {
        use tableau::{DP5_A, DP5_C, DP5_E};
        self.k[0] = self.dy;
        for i in 1..6 {
            let ys = self.y + comb(&self.k, DP5_A[i]) * h;
            self.k[i] = rhs(self.t + DP5_C[i] * h, &ys);
        }
        // Row 6 of A is b: the last stage is evaluated at y_new (FSAL).
        let y_new = self.y + comb(&self.k, DP5_A[6]) * h;
        self.k[6] = rhs(self.t + h, &y_new);
        self.stats.rhs_evals += 6;
        let e = comb(&self.k, DP5_E) * h;
        (y_new, self.err_norm(&e, &y_new))
    }

    /// One DOP853 attempt of size `h`; stages in `self.k[0..12]`.
    fn attempt_dop853<F>(&mut self, rhs: &mut F, h: f64) -> (SVector<f64, N>, f64)
    where
        F: FnMut(f64, &SVector<f64, N>) -> SVector<f64, N>,
    {
        use tableau::{DOP853_A, DOP853_BHH, DOP853_C, DOP853_E5};
        self.k[0] = self.dy;
        for i in 1..12 {
            let ys = self.y + comb(&self.k, DOP853_A[i]) * h;
            self.k[i] = rhs(self.t + DOP853_C[i] * h, &ys);
        }
        self.stats.rhs_evals += 11;
        let bk = comb(&self.k, DOP853_A[12]);
        let y_new = self.y + bk * h;
        let e5 = comb(&self.k, DOP853_E5);
        let e3 = bk - comb(&self.k, DOP853_BHH);
        let sk = self.scale(&y_new);
        let err5 = e5.component_div(&sk).norm_squared();
        let err3 = e3.component_div(&sk).norm_squared();
        let mut deno = err5 + 0.01 * err3;
        if deno <= 0.0 {
            deno = 1.0;
        }
        let err = h.abs() * err5 * (1.0 / (self.controlled * deno)).sqrt();
        (y_new, err)
    }

    fn scale(&self, y_new: &SVector<f64, N>) -> SVector<f64, N> {
        self.tol.atol + self.y.abs().sup(&y_new.abs()) * self.tol.rtol
    }

    fn err_norm(&self, e: &SVector<f64, N>, y_new: &SVector<f64, N>) -> f64 {
        (e.component_div(&self.scale(y_new)).norm_squared() / self.controlled).sqrt()
    }

    fn dense_dopri5(&mut self, h: f64, y_new: &SVector<f64, N>, f_new: &SVector<f64, N>) {
        let ydiff = y_new - self.y;
        let bspl = self.dy * h - ydiff;
        self.cont[0] = self.y;
        self.cont[1] = ydiff;
        self.cont[2] = bspl;
        self.cont[3] = ydiff - f_new * h - bspl;
        self.cont[4] = comb(&self.k, tableau::DP5_D) * h;
    }

    fn dense_dop853<F>(
        &mut self,
        rhs: &mut F,
        h: f64,
        y_new: &SVector<f64, N>,
        f_new: &SVector<f64, N>,
    ) where
        F: FnMut(f64, &SVector<f64, N>) -> SVector<f64, N>,
    {
        use tableau::{DOP853_A, DOP853_C, DOP853_D};
        self.k[12] = *f_new;
        for i in 13..16 {
            let ys = self.y + comb(&self.k, DOP853_A[i]) * h;
            self.k[i] = rhs(self.t + DOP853_C[i] * h, &ys);
        }
        self.stats.rhs_evals += 3;
        let ydiff = y_new - self.y;
        let bspl = self.dy * h - ydiff;
        self.cont[0] = self.y;
        self.cont[1] = ydiff;
        self.cont[2] = bspl;
        self.cont[3] = ydiff - f_new * h - bspl;
        for (r, row) in DOP853_D.iter().enumerate() {
            self.cont[4 + r] = comb(&self.k, row) * h;
        }
    }

    /// Value of the continuous extension of the last accepted step at
    /// `t in [t_old, t_new]` (4th order for Dopri5, 7th for DOP853).
    /// Returns `y()` exactly at the current time. Outside the step the
    /// polynomial is extrapolated (inaccurate). Before any step it returns
    /// the current state.
    pub fn dense(&self, t: f64) -> SVector<f64, N> {
        if !self.has_step || t == self.t {
            return self.y;
        }
        let s = (t - self.t_old) / self.h_last;
        let s1 = 1.0 - s;
        let c = &self.cont;
        match self.opts.method {
            Method::Dopri5 => c[0] + (c[1] + (c[2] + (c[3] + c[4] * s1) * s) * s1) * s,
            Method::Dop853 => {
                let conpar = c[4] + (c[5] + (c[6] + c[7] * s) * s1) * s;
                c[0] + (c[1] + (c[2] + (c[3] + conpar * s1) * s) * s1) * s
            }
        }
    }

    /// The state at `t` inside the last accepted step, by a step of the method itself from that
    /// step's start: of the method's order (the continuous extension is one order lower) and, as
    /// the step is no longer than the accepted one, within its error estimate. For a state that a
    /// discontinuity (an impact) starts from, where the extension's error would be carried on.
    /// Returns `y()` at the current time and the step's start state at its start.
    pub fn step_state<F>(&mut self, rhs: &mut F, t: f64) -> SVector<f64, N>
    where
        F: FnMut(f64, &SVector<f64, N>) -> SVector<f64, N>,
    {
        let (t0, y0) = (self.t_old, self.cont[0]);
        if !self.has_step || t == self.t {
            return self.y;
        }
        if t == t0 {
            return y0;
        }
        let h = t - t0;
        // The stages of the accepted step are kept (its dense output needs them): a scratch set.
        let mut k = [SVector::<f64, N>::zeros(); STAGES];
        // k[0] is f at the step's start for both methods.
        k[0] = self.k[0];
        let (a, c, last) = match self.opts.method {
            Method::Dopri5 => (&tableau::DP5_A[..], &tableau::DP5_C[..], 6),
            Method::Dop853 => (&tableau::DOP853_A[..], &tableau::DOP853_C[..], 12),
        };
        for i in 1..last {
            let ys = y0 + comb(&k, a[i]) * h;
            k[i] = rhs(t0 + c[i] * h, &ys);
        }
        self.stats.rhs_evals += last as u64 - 1;
        y0 + comb(&k, a[last]) * h
    }

    /// Time derivative of the continuous extension of the last accepted step
    /// (one order lower accuracy than [`dense`](Self::dense)).
    pub fn dense_derivative(&self, t: f64) -> SVector<f64, N> {
        if !self.has_step {
            return self.dy;
        }
        let s = (t - self.t_old) / self.h_last;
        let s1 = 1.0 - s;
        let c = &self.cont;
        // Differentiate the nested Horner forms with respect to s.
        let d = match self.opts.method {
            Method::Dopri5 => {
                let p = c[3] + c[4] * s1;
                let dp = -c[4];
                let q = c[2] + p * s;
                let dq = p + dp * s;
                let r = c[1] + q * s1;
                let dr = dq * s1 - q;
                r + dr * s
            }
            Method::Dop853 => {
                let a = c[6] + c[7] * s;
                let da = c[7];
                let b = c[5] + a * s1;
                let db = da * s1 - a;
                let cp = c[4] + b * s;
                let dcp = b + db * s;
                let p = c[3] + cp * s1;
                let dp = dcp * s1 - cp;
                let q = c[2] + p * s;
                let dq = p + dp * s;
                let r = c[1] + q * s1;
                let dr = dq * s1 - q;
                r + dr * s
            }
        };
        d / self.h_last
    }

    /// Move the current point back to `t_event` inside the last step:
    /// the state becomes [`dense`](Self::dense)`(t_event)`, the derivative
    /// the dense-output derivative (the exact `f` is re-evaluated lazily if
    /// stepping continues without a reset). The dense output of the last step
    /// stays available on `[t_old, t_event]`. `t_event` is clamped to the
    /// last step.
    pub fn truncate_at(&mut self, t_event: f64) {
        if !self.has_step || t_event == self.t || t_event.is_nan() {
            return;
        }
        let te = t_event.clamp(self.t_old, self.t);
        self.y = self.dense(te);
        self.dy = self.dense_derivative(te);
        self.t = te;
        self.fsal_valid = false;
    }

    /// Current time.
    pub fn t(&self) -> f64 {
        self.t
    }

    /// Current state.
    pub fn y(&self) -> &SVector<f64, N> {
        &self.y
    }

    /// Derivative f(t, y) at the current point (after
    /// [`truncate_at`](Self::truncate_at): the dense-output approximation).
    pub fn dy(&self) -> &SVector<f64, N> {
        &self.dy
    }

    /// Start time of the last accepted step.
    pub fn t_old(&self) -> f64 {
        self.t_old
    }

    /// Length of the last accepted step (0 before the first step).
    pub fn last_step_size(&self) -> f64 {
        self.h_last
    }

    /// Step size the controller will try next (before `h_max`/`t_stop`
    /// clipping).
    pub fn next_step_size(&self) -> f64 {
        self.h_next
    }

    /// Whether a step has been taken since the last reset (i.e. whether the
    /// dense output is meaningful).
    pub fn has_step(&self) -> bool {
        self.has_step
    }

    /// Work counters accumulated since creation.
    pub fn stats(&self) -> Stats {
        self.stats
    }

    /// Reset the work counters to zero, returning the old ones.
    pub fn take_stats(&mut self) -> Stats {
        std::mem::take(&mut self.stats)
    }

    /// The options.
    pub fn options(&self) -> &Options {
        &self.opts
    }

    /// The tolerances.
    pub fn tolerances(&self) -> &Tolerances<N> {
        &self.tol
    }

    pub(crate) fn count_event(&mut self) {
        self.stats.events += 1;
    }
}
