//! One step: the stages, the error estimate and the step-size control.

use nalgebra::SVector;

use super::{Integrator, StepInfo, STAGES};
use crate::tableau::{self, Row};
use crate::{Method, OdeError, OdeErrorKind};

/// Controller constants.
pub(super) struct Ctrl {
    /// Exponent alpha = 1/q - 0.75 beta (q = 5 or 8).
    expo1: f64,
    beta: f64,
    safe: f64,
    /// Minimal factor h_new/h.
    facmin: f64,
    /// Maximal factor h_new/h.
    facmax: f64,
}

pub(super) const DOPRI5_CTRL: Ctrl = Ctrl {
    expo1: 0.2 - 0.04 * 0.75,
    beta: 0.04,
    safe: 0.9,
    facmin: 0.2,
    facmax: 10.0,
};

pub(super) const DOP853_CTRL: Ctrl = Ctrl {
    expo1: 1.0 / 8.0,
    beta: 0.0,
    safe: 0.9,
    facmin: 0.333,
    facmax: 6.0,
};

#[inline(always)]
pub(super) fn comb<const N: usize>(k: &[SVector<f64, N>; STAGES], row: Row) -> SVector<f64, N> {
    let mut s = SVector::<f64, N>::zeros();
    for &(j, a) in row {
        s.axpy(a, &k[j], 1.0);
    }
    s
}

pub(super) fn all_finite<const N: usize>(v: &SVector<f64, N>) -> bool {
    v.iter().all(|x| x.is_finite())
}

impl<const N: usize> Integrator<N> {
    /// Perform one accepted step (rejected attempts are retried internally)
    /// without passing `t_stop`; a step that would reach or pass `t_stop`
    /// (or end within 1 % of a step before it) is set to land on `t_stop`
    /// exactly. Integration is forward only: `t_stop` must exceed `t()`.
    ///
    /// An attempt whose stages, state or error estimate are not finite (a
    /// step far beyond the method's stability region overflows) is rejected
    /// and retried at `facmin` times its size, as scipy's and Julia's
    /// integrators do.
    ///
    /// Errors: step-size underflow (`h <= 10 eps |t|`; reported as non-finite
    /// when the attempts that shrank the step were), a non-finite right-hand
    /// side at the step's start or an accepted step's end, `max_steps`
    /// attempts since the last reset, `t_stop <= t`. On error the current
    /// point is unchanged.
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
        // The last attempt's overflow, while no finite attempt has followed it.
        let mut non_finite: Option<String> = None;
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
                return Err(match non_finite {
                    Some(attempt) => OdeError::new(
                        OdeErrorKind::NonFinite,
                        self.t,
                        format!("{attempt}, and still at the step size underflow (h = {h_ctrl:e})"),
                    ),
                    None => OdeError::new(
                        OdeErrorKind::StepSizeUnderflow,
                        self.t,
                        format!("step size underflow (h = {h_ctrl:e})"),
                    ),
                });
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
                self.stats.rejected += 1;
                rejected = true;
                self.h_next = h * ctrl.facmin;
                non_finite = Some(format!(
                    "non-finite stage, state or error estimate in a step of size {h:e} \
                     (y_new = {y_new:?})"
                ));
                continue;
            }
            non_finite = None;
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
}
