//! The explicit Runge–Kutta integrator (Dormand–Prince 5(4) and DOP853): steps, step-size
//! control (`step.rs`), dense output (`dense.rs`) and the state a driver restarts from.

use nalgebra::SVector;

use crate::{OdeError, OdeErrorKind, Options, Stats, Tolerances};

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

mod dense;
mod step;

use step::all_finite;

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
