//! Where a phase starts after an event: past the event's surface, not on it.

use nalgebra::SVector;
use rocking_ode::events::{Direction, Event};
use rocking_ode::Integrator;

/// The event moved past its surface by more than the `noise` of its component (64 ulps of its
/// scale: α for θ, B + |v| for a depth). `refine` keeps the root on the side it converges to, and a
/// phase that started on the old side or within rounding of 0 (a depth of +1e-18 or exactly 0
/// on the dense output one ulp later, after a lift-off) found the same surface again at once,
/// the root search's first point after t0 being still there: a long first step (a flight) ended
/// in a landing one ulp after its lift-off, that landing in a lift-off one ulp later, and so on,
/// more than 20 000 events at one instant (issue 44, docs/ground.md, "Chattering"). Moves by 1,
/// 2, 4, … ulps of t (the step's own states, as `refine`) until the component is past the noise;
/// at most 2^24 ulps (4e-9 of t), lest the move pass another component's crossing: beyond, the
/// event stays where `refine` put it.
pub(super) fn past<const N: usize, F, G>(
    ode: &mut Integrator<N>,
    rhs: &mut F,
    g: &mut G,
    dir: Direction,
    noise: f64,
    ev: Event<N, 4>,
) -> Event<N, 4>
where
    F: FnMut(f64, &SVector<f64, N>) -> SVector<f64, N>,
    G: FnMut(f64, &SVector<f64, N>) -> SVector<f64, 4>,
{
    let crossed = |gv: f64| crossed(dir, noise, gv);
    if crossed(ev.g[ev.index]) {
        return ev;
    }
    // The search on the line y + Δ f(t, y) (its error Δ² ÿ / 2 is below rounding for the
    // shifts it takes), checked on the step's own state there.
    let slope = rhs(ev.t, &ev.y);
    let ulp = f64::EPSILON * ev.t.abs().max(1.0);
    for k in 0..=24 {
        let shift = ulp * f64::from(1u32 << k);
        let t = ev.t + shift;
        if t > ode.t() {
            break;
        }
        if crossed(g(t, &(ev.y + slope * shift))[ev.index]) {
            let y = ode.step_state(rhs, t);
            let moved = Event {
                t,
                g: g(t, &y),
                y,
                ..ev
            };
            if crossed(moved.g[ev.index]) {
                return moved;
            }
        }
    }
    ev
}

/// Whether an event function's value `gv` lies past its surface in the event's direction by
/// more than `noise`.
pub(super) fn crossed(dir: Direction, noise: f64, gv: f64) -> bool {
    match dir {
        Direction::Rising => gv > noise,
        Direction::Falling => gv < -noise,
        Direction::Either => gv.abs() > noise,
    }
}

/// [`past`] on a Taylor step, whose polynomial is the state at every t of the step: the time
/// from the root `t` on, up to the step's end `t_end`, at which the event function `g` lies
/// past its surface by more than `noise` (`t` itself when it does there or no move gets there).
pub(super) fn past_on_polynomial(
    g: impl Fn(f64) -> f64,
    t: f64,
    t_end: f64,
    dir: Direction,
    noise: f64,
) -> f64 {
    if crossed(dir, noise, g(t)) {
        return t;
    }
    let ulp = f64::EPSILON * t.abs().max(1.0);
    (0..=24)
        .map(|k| t + ulp * f64::from(1u32 << k))
        .take_while(|&tk| tk <= t_end)
        .find(|&tk| crossed(dir, noise, g(tk)))
        .unwrap_or(t)
}
