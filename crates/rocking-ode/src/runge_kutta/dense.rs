//! Dense output of the last step: the interpolants of Dormand–Prince 5(4) and DOP853, and the
//! truncation at an event.

use nalgebra::SVector;

use super::step::comb;
use super::{Integrator, STAGES};
use crate::{tableau, Method};

impl<const N: usize> Integrator<N> {
    pub(super) fn dense_dopri5(
        &mut self,
        h: f64,
        y_new: &SVector<f64, N>,
        f_new: &SVector<f64, N>,
    ) {
        let ydiff = y_new - self.y;
        let bspl = self.dy * h - ydiff;
        self.cont[0] = self.y;
        self.cont[1] = ydiff;
        self.cont[2] = bspl;
        self.cont[3] = ydiff - f_new * h - bspl;
        self.cont[4] = comb(&self.k, tableau::DP5_D) * h;
    }

    pub(super) fn dense_dop853<F>(
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
}
