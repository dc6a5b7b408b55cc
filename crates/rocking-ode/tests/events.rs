//! Event location and restarts.

use nalgebra::{SVector, Vector1, Vector2};
use rocking_ode::events::{locate, refine, Direction};
use rocking_ode::{Integrator, Method, Options, Tolerances};
use std::f64::consts::PI;

fn osc(_t: f64, y: &SVector<f64, 2>) -> SVector<f64, 2> {
    Vector2::new(y[1], -y[0])
}

/// Integrate y = (cos t, -sin t) on [t0, t1] recording events of
/// `g = y[0]` without restarting. Returns the event times.
fn oscillator_crossings(method: Method, dir: Direction, rtol: f64, t0: f64, t1: f64) -> Vec<f64> {
    let mut ode =
        Integrator::new(Options::new(method), Tolerances::uniform(rtol, 1e-2 * rtol)).unwrap();
    let mut f = osc;
    let mut g = |_t: f64, y: &SVector<f64, 2>| Vector1::new(y[0]);
    let y0 = if t0 == PI / 2.0 {
        Vector2::new(0.0, -1.0) // g exactly zero at the start
    } else {
        Vector2::new(t0.cos(), -t0.sin())
    };
    ode.reset(t0, y0, &mut f).unwrap();
    let mut g_old = g(ode.t(), ode.y());
    let mut out = Vec::new();
    loop {
        let info = ode.step(&mut f, t1).unwrap();
        let g_new = g(ode.t(), ode.y());
        if let Some(ev) = locate(&mut ode, &mut g, &[dir], &g_old, &g_new) {
            assert!(ev.t > info.t_old && ev.t <= info.t_new);
            assert!(ev.t - ev.t_before <= 4.0 * f64::EPSILON * ev.t.abs().max(1.0));
            out.push(ev.t);
        }
        g_old = g_new;
        if info.reached {
            break;
        }
    }
    assert_eq!(ode.stats().events, out.len() as u64);
    out
}

fn max_dev(times: &[f64], expected: impl Fn(usize) -> f64) -> f64 {
    times
        .iter()
        .enumerate()
        .map(|(k, t)| (t - expected(k)).abs())
        .fold(0.0, f64::max)
}

#[test]
fn oscillator_zero_crossings() {
    // The location error is dominated by the global error of the solution,
    // which is about proportional to the tolerance (~1.5e-10 at rtol 1e-10
    // over [0, 20], see the tolerance sweep); the root finder itself is
    // accurate to a few ulp (checked in `oscillator_crossings`).
    for (m, rtol, bound) in [
        (Method::Dop853, 1e-13, 1e-12),
        (Method::Dopri5, 1e-13, 1e-12),
        (Method::Dop853, 1e-10, 5e-10),
        (Method::Dopri5, 1e-10, 5e-10),
    ] {
        let ts = oscillator_crossings(m, Direction::Either, rtol, 0.0, 20.0);
        assert_eq!(ts.len(), 6, "{ts:?}");
        let dev = max_dev(&ts, |k| PI / 2.0 + k as f64 * PI);
        println!("{m:?} rtol {rtol:.0e}: zero crossings of cos t located within {dev:.2e}");
        assert!(dev <= bound, "{m:?}: {dev}");
    }
}

#[test]
fn direction_filtering() {
    for m in [Method::Dopri5, Method::Dop853] {
        let rtol = 1e-13;
        let rising = oscillator_crossings(m, Direction::Rising, rtol, 0.0, 20.0);
        assert_eq!(rising.len(), 3);
        assert!(max_dev(&rising, |k| 1.5 * PI + 2.0 * PI * k as f64) <= 1e-12);
        let falling = oscillator_crossings(m, Direction::Falling, rtol, 0.0, 20.0);
        assert_eq!(falling.len(), 3);
        assert!(max_dev(&falling, |k| 0.5 * PI + 2.0 * PI * k as f64) <= 1e-12);
    }
}

#[test]
fn no_retrigger_at_start_on_event_surface() {
    // Starts at t = pi/2 with g = cos t exactly 0: the first event must be
    // 3 pi / 2, whatever the direction.
    for dir in [Direction::Either, Direction::Falling, Direction::Rising] {
        let ts = oscillator_crossings(Method::Dop853, dir, 1e-13, PI / 2.0, 5.0);
        assert_eq!(ts.len(), if dir == Direction::Falling { 0 } else { 1 });
        if let Some(t) = ts.first() {
            assert!((t - 1.5 * PI).abs() < 1e-12, "{t}");
        }
    }
}

/// One big step of DOP853 from 0 to 2 on the oscillator, then locate among
/// the given event components (all functions of y[0] = cos t).
fn one_step_events(levels: [f64; 3]) -> (usize, f64, u64) {
    let opts = Options {
        h_init: Some(2.0),
        ..Options::new(Method::Dop853)
    };
    let mut ode = Integrator::new(opts, Tolerances::uniform(1e-3, 1e-3)).unwrap();
    let mut f = osc;
    ode.reset(0.0, Vector2::new(1.0, 0.0), &mut f).unwrap();
    let mut g = |_t: f64, y: &SVector<f64, 2>| {
        SVector::<f64, 3>::new(y[0] - levels[0], y[0] - levels[1], y[0] - levels[2])
    };
    let g_old = g(ode.t(), ode.y());
    let info = ode.step(&mut f, 2.0).unwrap();
    assert_eq!(info.t_new, 2.0, "expected a single step");
    let g_new = g(ode.t(), ode.y());
    let dirs = [Direction::Falling; 3];
    let ev = locate(&mut ode, &mut g, &dirs, &g_old, &g_new).unwrap();
    (ev.index, ev.t, ode.stats().events)
}

#[test]
fn earliest_of_several_events_in_one_step() {
    // cos t falls through 0.3 (t = 1.266), 0.5 (t = pi/3) and -0.2 (1.772).
    let (idx, t, n) = one_step_events([0.3, 0.5, -0.2]);
    assert_eq!(idx, 1);
    // Single loose step: the dense output is only ~1e-4 accurate, but the
    // root of the interpolant is what is located.
    assert!((t - PI / 3.0).abs() < 1e-3, "{t}");
    assert_eq!(n, 1);
    // Coinciding roots: the lowest index wins.
    let (idx, _, _) = one_step_events([0.9, 0.5, 0.5]);
    assert_eq!(idx, 0);
    let (idx, t2, _) = one_step_events([-0.5, 0.5, 0.5]);
    assert_eq!(idx, 1);
    assert_eq!(t2, t);
}

/// Bouncing ball with restitution e: drop from h0 at rest.
fn bouncing_ball(method: Method) -> Vec<f64> {
    let grav = 9.81;
    let mut f = |_t: f64, y: &SVector<f64, 2>| Vector2::new(y[1], -grav);
    let mut g = |_t: f64, y: &SVector<f64, 2>| Vector1::new(y[0]);
    let dirs = [Direction::Falling];
    // The solution is a parabola, integrated exactly: without h_max the
    // controller would take a whole flight (up and down again) in one step,
    // a double crossing that end-point signs cannot see.
    let opts = Options {
        h_max: 0.05,
        ..Options::new(method)
    };
    let mut ode = Integrator::new(opts, Tolerances::uniform(1e-10, 1e-12)).unwrap();
    ode.reset(0.0, Vector2::new(1.0, 0.0), &mut f).unwrap();
    let mut g_old = g(ode.t(), ode.y());
    let mut bounces = Vec::new();
    loop {
        let info = ode.step(&mut f, 3.0).unwrap();
        let g_new = g(ode.t(), ode.y());
        if let Some(ev) = locate(&mut ode, &mut g, &dirs, &g_old, &g_new) {
            bounces.push(ev.t);
            ode.truncate_at(ev.t);
            assert_eq!(ode.t(), ev.t);
            assert_eq!(*ode.y(), ev.y);
            let h = ode.last_step_size();
            ode.reset_with_step(ev.t, Vector2::new(0.0, -0.8 * ev.y[1]), h, &mut f)
                .unwrap();
            g_old = g(ode.t(), ode.y());
            continue;
        }
        g_old = g_new;
        if info.reached {
            break;
        }
    }
    assert_eq!(ode.stats().events, bounces.len() as u64);
    bounces
}

#[test]
fn bouncing_ball_restarts() {
    let grav: f64 = 9.81;
    let t1 = (2.0 / grav).sqrt();
    let v1 = grav * t1;
    let mut expected = vec![t1];
    let mut v = v1;
    // Bounces accumulate at t = 9 t1 = 4.06 (Zeno); stop well before.
    loop {
        v *= 0.8;
        let next = expected.last().unwrap() + 2.0 * v / grav;
        if next > 3.0 {
            break;
        }
        expected.push(next);
    }
    for m in [Method::Dopri5, Method::Dop853] {
        let b = bouncing_ball(m);
        assert_eq!(b.len(), expected.len(), "{m:?}: {b:?}");
        let dev = max_dev(&b, |k| expected[k]);
        println!("{m:?}: {} bounce times within {dev:.2e}", b.len());
        assert!(dev < 1e-9);
    }
}

/// `refine` moves an event from the dense output's root to the root of the method's own step
/// from the step's start (`Integrator::step_state`): for the oscillator the flow from the step's
/// start is a rotation, so that root is known exactly, and the refined event is closer to it
/// than the dense output's for DOP853 (by 1e-4 to 1e-1 here: its steps are of order 8, its extension
/// of order 7); DOPRI5's extension is of its steps' order, and the refined root is no worse.
#[test]
fn refined_events_sit_on_the_methods_own_steps() {
    for (method, rtol, gain) in [
        (Method::Dop853, 1e-5, 0.1),
        (Method::Dop853, 1e-8, 0.1),
        (Method::Dopri5, 1e-5, 2.0),
        (Method::Dopri5, 1e-8, 2.0),
    ] {
        let mut ode =
            Integrator::new(Options::new(method), Tolerances::uniform(rtol, rtol)).unwrap();
        let mut f = osc;
        let mut g = |_t: f64, y: &SVector<f64, 2>| Vector1::new(y[0]);
        ode.reset(0.0, Vector2::new(1.0, 0.0), &mut f).unwrap();
        let mut g_old = g(0.0, ode.y());
        let mut checked = 0;
        while ode.t() < 30.0 {
            ode.step(&mut f, 30.0).unwrap();
            let g_new = g(ode.t(), ode.y());
            if let Some(ev) = locate(&mut ode, &mut g, &[Direction::Either], &g_old, &g_new) {
                // The exact root of the flow from the step's start (t0, y0): y0[0] cos s +
                // y0[1] sin s = 0.
                let (t0, y0) = (ode.t_old(), ode.dense(ode.t_old()));
                let exact = t0 + (-y0[0] / y0[1]).atan().rem_euclid(PI);
                let refined = refine(&mut ode, &mut f, &mut g, ev);
                let (e_dense, e_refined) = ((ev.t - exact).abs(), (refined.t - exact).abs());
                assert!(
                    e_refined <= gain * e_dense + 1e-14,
                    "{method:?} at t = {exact}: dense root off by {e_dense:e}, refined {e_refined:e}"
                );
                // The refined state is the step's, with g zero to rounding there (|g'| = 1).
                let rounding = 4.0 * f64::EPSILON * refined.t.max(1.0);
                assert!(refined.g[0].abs() <= rounding, "{:e}", refined.g[0]);
                assert_eq!(refined.y, ode.step_state(&mut f, refined.t));
                checked += 1;
            }
            g_old = g_new;
        }
        assert!(checked >= 9, "{method:?}: {checked} crossings");
    }
}
