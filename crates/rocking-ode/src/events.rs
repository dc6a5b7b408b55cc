//! Event location on the dense output of the last accepted step.
//!
//! The caller supplies an event function `g(t, y) -> SVector<f64, M>` with
//! `M` components and a [`Direction`] per component. After each accepted
//! [`Integrator::step`] it evaluates `g` at the new point and calls
//! [`locate`] with the values at both ends of the step (it keeps the value at
//! the step start from the previous step or from the restart).
//!
//! # Sign convention
//!
//! A component *crosses* in a step when it leaves the open region it started
//! in: [`Direction::Rising`] triggers when `g(t_old) < 0` and `g(t_new) >= 0`,
//! [`Direction::Falling`] when `g(t_old) > 0` and `g(t_new) <= 0`,
//! [`Direction::Either`] on both. A component that is exactly zero at the
//! step start therefore never triggers in that step: after a restart on an
//! event surface (where `g = 0`), the event does not re-trigger.
//!
//! # Limitations
//!
//! Crossings are detected from the signs at the ends of a step only: a
//! component that crosses twice within one step (e.g. grazing contact) is
//! missed. If that matters, the driver must limit [`Options::h_max`]
//! (crate root) to a fraction of the shortest time scale of `g`.
//!
//! [`Options::h_max`]: crate::Options::h_max

use crate::Integrator;
use nalgebra::SVector;

/// Which sign changes of an event component are reported.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Direction {
    /// `g` goes from negative to non-negative.
    Rising,
    /// `g` goes from positive to non-positive.
    Falling,
    /// Both.
    Either,
}

impl Direction {
    /// Whether going from `g0` (step start) to `g1` is a crossing in this
    /// direction (see the module docs for the treatment of zeros).
    #[inline]
    pub fn triggers(self, g0: f64, g1: f64) -> bool {
        let rising = g0 < 0.0 && g1 >= 0.0;
        let falling = g0 > 0.0 && g1 <= 0.0;
        match self {
            Direction::Rising => rising,
            Direction::Falling => falling,
            Direction::Either => rising || falling,
        }
    }
}

/// A located event.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Event<const N: usize, const M: usize> {
    /// Index of the event component that crossed first.
    pub index: usize,
    /// Event time: the first point found on the far side of the crossing
    /// (`g[index]` has changed sign or is exactly 0 there). It is within
    /// `4 eps max(|t|, 1)` of the last point before the crossing.
    pub t: f64,
    /// State at `t` (dense output, or the step end state if `t == t_new`).
    pub y: SVector<f64, N>,
    /// Event function at `(t, y)`.
    pub g: SVector<f64, M>,
    /// Last point found before the crossing (`t_before < t`).
    pub t_before: f64,
}

/// Find the earliest crossing within `(t_old, t_new]` of the last accepted
/// step of `ode`.
///
/// `g_old` and `g_new` are the event function values at the start and end of
/// the step. Every component that crosses in its allowed direction (see the
/// module docs) is located by the Illinois (modified regula falsi) method on
/// the dense output until the bracket is at most `4 eps max(|t|, 1)` wide or
/// `g` is exactly zero; the earliest root wins and, when two roots coincide
/// to that tolerance, the lowest component index. The crossing found is
/// counted in [`Stats::events`](crate::Stats::events). Returns `None` when no
/// component crosses or when no step has been taken since the last reset.
/// Does not modify the current point: call
/// [`Integrator::truncate_at`] to move there.
pub fn locate<const N: usize, const M: usize, G>(
    ode: &mut Integrator<N>,
    g: &mut G,
    dirs: &[Direction; M],
    g_old: &SVector<f64, M>,
    g_new: &SVector<f64, M>,
) -> Option<Event<N, M>>
where
    G: FnMut(f64, &SVector<f64, N>) -> SVector<f64, M>,
{
    if !ode.has_step() {
        return None;
    }
    let t_lo = ode.t_old();
    let mut t_hi = ode.t();
    let mut g_hi = *g_new;
    let triggered = |gv: &SVector<f64, M>, i: usize| dirs[i].triggers(g_old[i], gv[i]);
    let mut best: Option<(usize, f64, SVector<f64, M>, f64)> = None;
    // Each pass locates the lowest-index component crossing before t_hi and
    // then restricts the search to crossings strictly before its bracket.
    for _ in 0..(4 * M + 4) {
        let Some(c) = (0..M).find(|&i| triggered(&g_hi, i)) else {
            break;
        };
        let (a, ga, b, gb) = bracket(ode, g, c, g_old[c] < 0.0, t_lo, *g_old, t_hi, g_hi);
        // Components crossing in (a, b] tie with c: lowest index wins.
        let idx = (0..M)
            .find(|&i| triggered(&gb, i) && !triggered(&ga, i))
            .unwrap_or(c);
        best = Some((idx, b, gb, a));
        if (0..M).any(|i| triggered(&ga, i)) {
            t_hi = a;
            g_hi = ga;
        } else {
            break;
        }
    }
    let (index, t, gv, t_before) = best?;
    let y = ode.dense(t);
    ode.count_event();
    Some(Event {
        index,
        t,
        y,
        g: gv,
        t_before,
    })
}

/// An event located on the dense output, moved to the root of its component on states that
/// the method's own steps from the last step's start give ([`Integrator::step_state`]): the
/// continuous extension is one order less accurate than the steps, and where the run restarts
/// from the event (an impact), a root of the extension carries its error into every later phase
/// (a long record with hundreds of impacts drifts by 1e-5 at a tolerance of 1e-13 without this).
///
/// Newton's iteration, the slope from the dense output across the event, at most four steps; it
/// keeps the root it converges to on either side of the crossing (the located one if it leaves
/// the step or does not converge). `t_before` stays the dense bracket's start; `g` is evaluated
/// at the returned state.
pub fn refine<const N: usize, const M: usize, F, G>(
    ode: &mut Integrator<N>,
    rhs: &mut F,
    g: &mut G,
    ev: Event<N, M>,
) -> Event<N, M>
where
    F: FnMut(f64, &SVector<f64, N>) -> SVector<f64, N>,
    G: FnMut(f64, &SVector<f64, N>) -> SVector<f64, M>,
{
    let (t_lo, t_hi) = (ode.t_old(), ode.t());
    let c = ev.index;
    let delta = 1e-3 * (t_hi - t_lo);
    let (a, b) = ((ev.t - delta).max(t_lo), (ev.t + delta).min(t_hi));
    let slope = (g(b, &ode.dense(b))[c] - g(a, &ode.dense(a))[c]) / (b - a);
    if !(slope.is_finite() && slope != 0.0 && b > a) {
        return ev;
    }
    let mut t = ev.t;
    for _ in 0..4 {
        let y = ode.step_state(rhs, t);
        let gv = g(t, &y);
        let next = t - gv[c] / slope;
        if !(next > t_lo && next <= t_hi) {
            return ev;
        }
        if (next - t).abs() <= 2.0 * f64::EPSILON * t.abs().max(1.0) {
            let y = ode.step_state(rhs, next);
            let gv = g(next, &y);
            return Event {
                t: next,
                y,
                g: gv,
                ..ev
            };
        }
        t = next;
    }
    ev
}

/// Illinois iteration for component `c` on `[a, b]`, where `g_c(a)` is on the
/// starting side (negative if `from_negative`) and `g_c(b)` has crossed.
/// Returns the final bracket with the full event vectors at both ends.
#[allow(clippy::too_many_arguments)]
fn bracket<const N: usize, const M: usize, G>(
    ode: &Integrator<N>,
    g: &mut G,
    c: usize,
    from_negative: bool,
    mut a: f64,
    mut ga: SVector<f64, M>,
    mut b: f64,
    mut gb: SVector<f64, M>,
) -> (f64, SVector<f64, M>, f64, SVector<f64, M>)
where
    G: FnMut(f64, &SVector<f64, N>) -> SVector<f64, M>,
{
    let crossed = |v: f64| if from_negative { v >= 0.0 } else { v <= 0.0 };
    let (mut fa, mut fb) = (ga[c], gb[c]);
    let mut side = 0i8;
    for iter in 0..200 {
        let tol = 4.0 * f64::EPSILON * b.abs().max(1.0);
        if gb[c] == 0.0 || b - a <= tol {
            break;
        }
        let mid = 0.5 * (a + b);
        let mut m = if iter < 40 {
            b - fb * (b - a) / (fb - fa)
        } else {
            mid
        };
        if !m.is_finite() {
            m = mid;
        }
        let margin = 0.25 * tol;
        m = m.clamp(a + margin, b - margin);
        let gm = g(m, &ode.dense(m));
        if crossed(gm[c]) {
            b = m;
            gb = gm;
            fb = gm[c];
            if side == 1 {
                fa *= 0.5;
            }
            side = 1;
        } else {
            a = m;
            ga = gm;
            fa = gm[c];
            if side == -1 {
                fb *= 0.5;
            }
            side = -1;
        }
    }
    (a, ga, b, gb)
}
