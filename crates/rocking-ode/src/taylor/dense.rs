//! The step's polynomial: dense output, and events as its roots.

use super::{next_up, Taylor, TaylorEvent, TaylorEvents};
use crate::events::Direction;
use crate::poly::{self, Root};

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
pub(super) fn end_state<const D: usize, const M: usize>(
    coef: &[[f64; M]; D],
    p: usize,
    tau: f64,
) -> [f64; D] {
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

impl<const D: usize, const M: usize> Taylor<D, M> {
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
    /// [`Stats::events`](crate::Stats::events). Costs one event-series evaluation, no state evaluation. As with the
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
}
