//! Stepping contract, statistics and error handling.

use nalgebra::{SVector, Vector1, Vector2};
use rocking_ode::{Integrator, Method, OdeErrorKind, Options, Stats, Tolerances};

fn osc(_t: f64, y: &SVector<f64, 2>) -> SVector<f64, 2> {
    Vector2::new(y[1], -y[0])
}

fn new2(method: Method) -> Integrator<2> {
    Integrator::new(Options::new(method), Tolerances::uniform(1e-8, 1e-10)).unwrap()
}

#[test]
fn step_never_passes_t_stop_and_lands_exactly() {
    for m in [Method::Dopri5, Method::Dop853] {
        let mut ode = new2(m);
        let mut f = osc;
        ode.reset(0.0, Vector2::new(1.0, 0.0), &mut f).unwrap();
        // Kinks of a piecewise excitation, some very close together.
        let stops = [0.3, 0.3 + 1e-9, 0.7, 1.0 / 3.0 + 1.0, 2.5, 10.0];
        for &ts in &stops {
            loop {
                let info = ode.step(&mut f, ts).unwrap();
                assert!(info.t_new <= ts && info.t_new > info.t_old);
                assert_eq!(info.t_new, ode.t());
                if info.reached {
                    assert_eq!(ode.t(), ts);
                    break;
                }
            }
        }
        assert!((ode.y()[0] - 10f64.cos()).abs() < 1e-6);
        // t_stop not ahead is an error, not a panic.
        let e = ode.step(&mut f, 10.0).unwrap_err();
        assert_eq!(e.kind, OdeErrorKind::InvalidInput);
    }
}

#[test]
fn stats_count_work() {
    let mut f = osc;
    let mut a = new2(Method::Dopri5);
    a.reset(0.0, Vector2::new(1.0, 0.0), &mut f).unwrap();
    while !a.step(&mut f, 5.0).unwrap().reached {}
    let s = a.stats();
    assert!(s.steps > 5);
    // reset: f0 + hinit; then 6 per attempt (FSAL).
    assert_eq!(s.rhs_evals, 2 + 6 * (s.steps + s.rejected));
    let mut b = new2(Method::Dop853);
    b.reset(0.0, Vector2::new(1.0, 0.0), &mut f).unwrap();
    while !b.step(&mut f, 5.0).unwrap().reached {}
    let t = b.stats();
    // 11 per attempt, plus f(t+h) and 3 dense stages per accepted step.
    assert_eq!(t.rhs_evals, 2 + 11 * (t.steps + t.rejected) + 4 * t.steps);
    let sum = s + t;
    assert_eq!(sum.steps, s.steps + t.steps);
    let mut acc = Stats::default();
    acc += s;
    acc += t;
    assert_eq!(acc, sum);
    assert_eq!(b.take_stats(), t);
    assert_eq!(b.stats(), Stats::default());
}

#[test]
fn rejected_steps_are_retried() {
    // A large explicit initial step forces rejections.
    let opts = Options {
        h_init: Some(5.0),
        ..Options::new(Method::Dopri5)
    };
    let mut ode = Integrator::new(opts, Tolerances::uniform(1e-10, 1e-10)).unwrap();
    let mut f = osc;
    ode.reset(0.0, Vector2::new(1.0, 0.0), &mut f).unwrap();
    let info = ode.step(&mut f, 10.0).unwrap();
    assert!(ode.stats().rejected > 0);
    assert!((ode.y()[0] - info.t_new.cos()).abs() < 1e-10);
}

#[test]
fn nan_rhs_is_an_error() {
    for m in [Method::Dopri5, Method::Dop853] {
        let mut ode = new2(m);
        let mut f = |t: f64, y: &SVector<f64, 2>| {
            if t > 0.5 {
                Vector2::new(f64::NAN, 0.0)
            } else {
                osc(t, y)
            }
        };
        ode.reset(0.0, Vector2::new(1.0, 0.0), &mut f).unwrap();
        let err = loop {
            match ode.step(&mut f, 2.0) {
                Ok(info) => assert!(!info.reached),
                Err(e) => break e,
            }
        };
        assert_eq!(err.kind, OdeErrorKind::NonFinite);
        assert!(err.t <= 0.5 && err.t == ode.t());
        assert!(ode.y().iter().all(|v| v.is_finite()));
        assert!(!err.to_string().is_empty());
    }
    // NaN initial state.
    let mut ode = new2(Method::Dopri5);
    let e = ode
        .reset(0.0, Vector2::new(f64::NAN, 0.0), &mut osc)
        .unwrap_err();
    assert_eq!(e.kind, OdeErrorKind::NonFinite);
    assert_eq!(
        ode.step(&mut osc, 1.0).unwrap_err().kind,
        OdeErrorKind::NotInitialised
    );
}

#[test]
fn max_steps_is_an_error() {
    let opts = Options {
        max_steps: 5,
        ..Options::new(Method::Dopri5)
    };
    let mut ode = Integrator::new(opts, Tolerances::uniform(1e-10, 1e-10)).unwrap();
    let mut f = osc;
    ode.reset(0.0, Vector2::new(1.0, 0.0), &mut f).unwrap();
    let e = loop {
        if let Err(e) = ode.step(&mut f, 100.0) {
            break e;
        }
    };
    assert_eq!(e.kind, OdeErrorKind::MaxSteps);
    assert!(e.t > 0.0);
    // A reset starts a fresh budget.
    ode.reset(e.t, *ode.y(), &mut f).unwrap();
    assert!(ode.step(&mut f, 100.0).is_ok());
}

#[test]
fn blow_up_terminates_with_an_error() {
    // y' = y^2, y(0) = 1 blows up at t = 1.
    for m in [Method::Dopri5, Method::Dop853] {
        let opts = Options {
            max_steps: 1_000_000,
            ..Options::new(m)
        };
        let mut ode = Integrator::new(opts, Tolerances::uniform(1e-8, 1e-8)).unwrap();
        let mut f = |_t: f64, y: &SVector<f64, 1>| Vector1::new(y[0] * y[0]);
        ode.reset(0.0, Vector1::new(1.0), &mut f).unwrap();
        let e = loop {
            if let Err(e) = ode.step(&mut f, 2.0) {
                break e;
            }
        };
        assert!(matches!(
            e.kind,
            OdeErrorKind::StepSizeUnderflow | OdeErrorKind::NonFinite
        ));
        assert!((e.t - 1.0).abs() < 1e-3, "{e}");
    }
}

#[test]
fn reset_with_step_uses_hint_and_dense_matches_ends() {
    let mut f = osc;
    let mut ode = new2(Method::Dop853);
    ode.reset_with_step(1.0, Vector2::new(1.0f64.cos(), -1.0f64.sin()), 0.05, &mut f)
        .unwrap();
    assert_eq!(ode.next_step_size(), 0.05);
    assert_eq!(ode.stats().rhs_evals, 1);
    let info = ode.step(&mut f, 3.0).unwrap();
    assert!((info.t_new - info.t_old - 0.05).abs() < 1e-15);
    assert_eq!(ode.dense(info.t_new), *ode.y());
    assert!((ode.dense(info.t_old) - Vector2::new(1.0f64.cos(), -1.0f64.sin())).amax() < 1e-15);
    let tm = 0.5 * (info.t_old + info.t_new);
    assert!((ode.dense_derivative(tm) - osc(tm, &ode.dense(tm))).amax() < 1e-10);
    // truncate_at moves back inside the step.
    ode.truncate_at(tm);
    assert_eq!(ode.t(), tm);
    assert!((ode.y()[0] - tm.cos()).abs() < 1e-12);
    assert!((ode.dy()[0] + tm.sin()).abs() < 1e-10);
    // Stepping on after a truncation works (f re-evaluated).
    while !ode.step(&mut f, 3.0).unwrap().reached {}
    assert!((ode.y()[0] - 3f64.cos()).abs() < 1e-7);
}

#[test]
fn invalid_tolerances_are_rejected() {
    let bad = Tolerances::<2> {
        rtol: 1e-6,
        atol: Vector2::new(1e-6, 0.0),
    };
    assert!(Integrator::new(Options::default(), bad).is_err());
    assert!(Integrator::new(Options::default(), Tolerances::<2>::uniform(-1.0, 1e-6)).is_err());
    let o = Options {
        h_max: 0.0,
        ..Options::default()
    };
    assert!(Integrator::new(o, Tolerances::<2>::uniform(1e-6, 1e-6)).is_err());
}

#[test]
fn integrator_is_plain_data() {
    fn is_copy<T: Copy + Send + Sync + 'static>() {}
    is_copy::<Integrator<4>>();
    let size = std::mem::size_of::<Integrator<4>>();
    // 16 stages + 8 dense coefficients + a few vectors of 4 f64.
    assert!(size < 1200, "{size}");
}

/// A first step far beyond the stability region overflows (here y' = -1e60 y from h = 1: the
/// stages grow as (λh)^k to inf): that attempt is rejected and retried smaller, not an error.
/// The step taken is then stable and accurate.
#[test]
fn an_overflowing_attempt_is_rejected_and_retried_smaller() {
    let lambda = 1e60;
    for m in [Method::Dopri5, Method::Dop853] {
        let opts = Options {
            h_init: Some(1.0),
            ..Options::new(m)
        };
        let mut ode = Integrator::new(opts, Tolerances::uniform(1e-10, 1e-10)).unwrap();
        let mut f = |_t: f64, y: &SVector<f64, 1>| Vector1::new(-lambda * y[0]);
        ode.reset(0.0, Vector1::new(1.0), &mut f).unwrap();
        let info = ode.step(&mut f, 1.0).unwrap();
        let h = info.t_new - info.t_old;
        assert!(h > 0.0 && h * lambda < 10.0, "{m:?}: h = {h:e}");
        assert!(ode.stats().rejected > 0, "{m:?}");
        let exact = (-lambda * ode.t()).exp();
        assert!(
            (ode.y()[0] - exact).abs() < 1e-8,
            "{m:?}: {} against {exact}",
            ode.y()[0]
        );
    }
}
