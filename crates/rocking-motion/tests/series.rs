//! `GroundMotion::accel_series` of every excitation kind against independent references: the
//! pulses against their closed forms' derivatives (sympy, evaluated in mpmath at 50 digits:
//! fixture `tests/fixtures/series_reference.json` from `series_reference.py` beside it), every
//! kind against its own pointwise `accel` summed from the series across a step, and records
//! against the exact line of each sample interval.

use rocking_motion::{
    CosinePulse, Excitation, GroundMotion, MavroeidisPapageorgiou, Record, Ricker, SinePulse,
};
use serde_json::Value;

/// Asked of every coefficient: its error over the largest magnitude of its order among the
/// fixture's times (so a coefficient near a zero of its derivative is held to the order's
/// scale, not to itself).
const TOL: f64 = 1e-12;

fn fixture() -> Value {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/fixtures/series_reference.json");
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

fn motion(kind: &str, p: &Value) -> Excitation {
    let f = |k: &str| p[k].as_f64().unwrap_or_else(|| panic!("{kind}: {k}"));
    match kind {
        "sine" => SinePulse::new(f("amplitude"), f("omega"))
            .with_start(f("start"))
            .into(),
        "cosine" => CosinePulse::new(f("amplitude"), f("omega"))
            .with_start(f("start"))
            .into(),
        "ricker-symmetric" => Ricker::symmetric(f("amplitude"), f("omega"))
            .with_start(f("start"))
            .into(),
        "ricker-antisymmetric" => Ricker::antisymmetric(f("amplitude"), f("omega"))
            .with_start(f("start"))
            .into(),
        "mp" => MavroeidisPapageorgiou::new(f("amplitude"), f("f_p"), f("gamma"), f("nu"), f("t0"))
            .into(),
        other => panic!("unknown kind {other}"),
    }
}

fn series(m: &impl GroundMotion, t0: f64, n: usize) -> Vec<f64> {
    let mut out = vec![f64::NAN; n];
    assert!(m.accel_series(t0, &mut out), "a series at {t0}");
    out
}

/// Every pulse's coefficients, orders 0 to 24, against the closed form's derivatives / k!.
#[test]
fn pulse_coefficients_match_the_closed_forms() {
    let doc = fixture();
    let orders = doc["orders"].as_u64().unwrap() as usize;
    let mut worst: Vec<(String, f64, usize)> = Vec::new();
    for case in doc["cases"].as_array().unwrap() {
        let kind = case["kind"].as_str().unwrap();
        let m = motion(kind, &case["params"]);
        let times: Vec<f64> = case["times"]
            .as_array()
            .unwrap()
            .iter()
            .map(|t| t.as_f64().unwrap())
            .collect();
        let reference: Vec<Vec<f64>> = case["coefficients"]
            .as_array()
            .unwrap()
            .iter()
            .map(|r| {
                r.as_array()
                    .unwrap()
                    .iter()
                    .map(|c| c.as_f64().unwrap())
                    .collect()
            })
            .collect();
        let scale: Vec<f64> = (0..orders)
            .map(|k| reference.iter().fold(0f64, |s, r| s.max(r[k].abs())))
            .collect();
        assert!(scale.iter().all(|&s| s > 0.0), "{kind}: every order seen");
        let (mut e_max, mut k_max) = (0f64, 0);
        for (t0, want) in times.iter().zip(&reference) {
            let got = series(&m, *t0, orders);
            for k in 0..orders {
                let e = (got[k] - want[k]).abs() / scale[k];
                assert!(
                    e <= TOL,
                    "{kind} {}: order {k} at t0 = {t0}: {} vs {} (error {e:.1e} of the order's scale {:.1e})",
                    case["params"],
                    got[k],
                    want[k],
                    scale[k]
                );
                if e > e_max {
                    (e_max, k_max) = (e, k);
                }
            }
            // A shorter request gives the same leading coefficients (any order asked for).
            for n in [0, 1, 2, 5, 13, 21] {
                assert_eq!(series(&m, *t0, n), got[..n], "{kind}: {n} coefficients");
            }
        }
        eprintln!(
            "SERIES| {kind} {}: worst error {e_max:.1e} of the order's scale, at order {k_max}",
            case["params"]
        );
        worst.push((kind.into(), e_max, k_max));
    }
    for kind in [
        "sine",
        "cosine",
        "ricker-symmetric",
        "ricker-antisymmetric",
        "mp",
    ] {
        assert!(worst.iter().any(|w| w.0 == kind), "{kind} in the fixture");
    }
}

/// Σ a_k h^k of the series at a step's start reproduces the pointwise `accel` up to the next
/// kink, from the support's first instant on (steps never cross a kink), and the order-0
/// coefficient is `accel_right` itself; the series is zero from the end of the support.
#[test]
fn series_sum_to_the_pulse_across_a_step() {
    let pulses: Vec<Excitation> = vec![
        SinePulse::new(0.45, 2.7).with_start(0.3).into(),
        CosinePulse::new(-0.8, 5.1).into(),
        Ricker::symmetric(0.8, 3.1).with_start(0.2).into(),
        Ricker::antisymmetric(0.35, 12.5).with_start(1.0).into(),
        MavroeidisPapageorgiou::starting_at(0.8, 0.5, 2.5, 0.3, 0.0).into(),
        MavroeidisPapageorgiou::new(0.35, 1.2, 1.01, 1.5, 1.0).into(),
        Excitation::from(MavroeidisPapageorgiou::new(2.0, 0.3, 3.5, -1.0, 10.0)).scale(-2.0),
    ];
    for m in &pulses {
        let kinks: Vec<f64> = m.kinks(f64::NEG_INFINITY, f64::INFINITY).collect();
        let (start, end) = (kinks[0], *kinks.last().unwrap());
        let peak = (0..=1000)
            .map(|i| m.accel(start + (end - start) * f64::from(i) / 1000.0).abs())
            .fold(0f64, f64::max);
        // Steps of the resolution (a sixteenth of the shortest period) from the start.
        let h = m.resolution();
        let mut t0 = start;
        while t0 < end {
            let c = series(m, t0, 21);
            assert_eq!(c[0], m.accel_right(t0), "{m:?}: order 0 at {t0}");
            let stop = m.next_kink(t0).unwrap().min(t0 + h);
            for i in 1..=8 {
                let t = t0 + (stop - t0) * f64::from(i) / 8.0;
                let sum = c.iter().rev().fold(0.0, |s, a| s * (t - t0) + a);
                let want = if t < end { m.accel(t) } else { m.accel_left(t) };
                assert!(
                    (sum - want).abs() <= 1e-13 * peak,
                    "{m:?}: the series at {t0} gives {sum} at {t}, the pulse {want}"
                );
            }
            t0 = stop;
        }
        assert!(
            series(m, end, 21).iter().all(|&c| c == 0.0),
            "{m:?}: 0 from the end"
        );
        assert!(
            series(m, start - 1.0, 21).iter().all(|&c| c == 0.0),
            "{m:?}: 0 before"
        );
    }
}

/// A record's series is the line of the sample interval that starts at or before t0: the
/// interpolated value and the interval's slope, exactly, wherever in the interval t0 is
/// (an event can end a step just before a sample); zero before the record and from its end.
#[test]
fn record_series_is_the_sample_interval_line() {
    let (dt, samples) = (0.02, vec![0.0, 0.31, -0.52, -0.49, 0.2, 0.9, -0.3]);
    let r = Record::new(dt, samples.clone())
        .unwrap()
        .with_scale(9.80665);
    let scale = 9.80665;
    let slope_scale = samples
        .windows(2)
        .map(|w| (w[1] - w[0]).abs() * scale / dt)
        .fold(0f64, f64::max);
    let next_down = |x: f64| f64::from_bits(x.to_bits() - 1);
    for i in 0..samples.len() - 1 {
        let (t_i, t_j) = (r.time_of(i), r.time_of(i + 1));
        let slope = scale * (samples[i + 1] - samples[i]) / dt;
        for t0 in [
            t_i,
            t_i + 0.37 * dt,
            t_j - 1e-6 * dt,
            t_j - 1e-12 * dt,
            next_down(t_j),
        ] {
            let c = series(&r, t0, 21);
            let line = scale * samples[i] + slope * (t0 - t_i);
            assert!(
                (c[0] - line).abs() <= 1e-14 * r.peak(),
                "value at {t0}: {} vs {line}",
                c[0]
            );
            assert!(
                (c[1] - slope).abs() <= 1e-12 * slope_scale,
                "interval {i}, t0 = {t0}: slope {} vs {slope} (error {:.1e} of the largest slope)",
                c[1],
                (c[1] - slope).abs() / slope_scale
            );
            assert!(c[2..].iter().all(|&x| x == 0.0), "a line at {t0}");
        }
    }
    for t0 in [-1.0, -f64::from_bits(1), r.end(), r.end() + 1.0] {
        assert!(series(&r, t0, 21).iter().all(|&c| c == 0.0), "0 at {t0}");
    }
    // Through the wrappers: Excitation and Scaled.
    let e = Excitation::from(r.clone()).scale(-0.5);
    let (a, b) = (series(&e, 0.05, 21), series(&r, 0.05, 21));
    for (x, y) in a.iter().zip(&b) {
        assert_eq!(*x, -0.5 * y);
    }
}
