//! The ground's kernels (issue 44, `derive/rocking_derive/ground.py`): their golden samples, the
//! statics against closed forms, and the identities that make the energy balance close.
//!
//! Closed forms (B the half-width, k the bed's stiffness per unit length or each corner spring's,
//! W the load on the base centre):
//! - settlement v0 = W / K_v, K_v = 2 k B (bed), 2 k (two springs);
//! - rotational stiffness before lift-off (2/3) k B^3 (bed), 2 k B^2 (two springs);
//! - first edge lift-off at sin(theta) = v0 / B with M = W B cos(theta) / 3 (bed), W B cos(theta)
//!   (two springs);
//! - after lift-off (bed): the contact length L = sqrt(2 W / (k sin theta)) and M = W cos(theta)
//!   (B - L / 3), which approaches W B as L shrinks; two springs: M = W B cos(theta).

use std::path::Path;

use rocking_kernels::ground::{self, Params};
use serde_json::Value;

const Q_THETA: usize = ground::winkler_full::Q_THETA;
const Q_V: usize = ground::winkler_full::Q_V;
const STRAIN: usize = ground::winkler_full::STRAIN;
const DISSIPATION: usize = ground::winkler_full::DISSIPATION;

type Kernel = fn(&[f64; 4], f64, &Params) -> [f64; 9];

fn flight(y: &[f64; 4], _s: f64, p: &Params) -> [f64; 9] {
    ground::flight(y, p)
}

/// (name, kernel) of every kind and state.
const KERNELS: [(&str, Kernel); 5] = [
    ("winkler_full", ground::winkler_full),
    ("winkler_edge", ground::winkler_edge),
    ("two_spring_full", ground::two_spring_full),
    ("two_spring_edge", ground::two_spring_edge),
    ("flight", flight),
];

fn number(v: &Value) -> f64 {
    match v {
        Value::Number(n) => n.as_f64().unwrap(),
        other => panic!("not a finite number: {other}"),
    }
}

#[test]
fn ground_kernels_reproduce_casadi_golden_samples() {
    let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("ir/ground/ground.json");
    let ir: Value = serde_json::from_str(&std::fs::read_to_string(file).unwrap()).unwrap();
    let mut checked = 0;
    for function in ir["functions"].as_array().unwrap() {
        let name = function["name"].as_str().unwrap();
        for sample in function["golden"].as_array().unwrap() {
            let inputs: Vec<Vec<f64>> = sample["inputs"]
                .as_array()
                .unwrap()
                .iter()
                .map(|i| i.as_array().unwrap().iter().map(number).collect())
                .collect();
            let refs: Vec<&[f64]> = inputs.iter().map(Vec::as_slice).collect();
            let got = ground::call(name, &refs).unwrap();
            let want: Vec<f64> = sample["output"]
                .as_array()
                .unwrap()
                .iter()
                .map(number)
                .collect();
            assert_eq!(got.len(), want.len());
            for (k, (g, w)) in got.iter().zip(&want).enumerate() {
                assert!(
                    (g - w).abs() <= 1e-12 * w.abs().max(1e-300),
                    "{name}[{k}]: {g} vs {w}"
                );
            }
            checked += 1;
        }
    }
    assert_eq!(checked, 7 * 3, "three samples of each of the seven kernels");
}

/// The settlement v under the load W at the rotation theta, from Q_v(theta, v) = -W (the kernel
/// of the given state; monotonic in v), by bisection on [lo, hi].
fn settle(kernel: Kernel, theta: f64, w: f64, p: &Params, lo: f64, hi: f64) -> f64 {
    let s = theta.signum();
    let residual = |v: f64| kernel(&[theta, v, 0.0, 0.0], s, p)[Q_V] + w;
    let (mut a, mut b) = (lo, hi);
    assert!(
        residual(a) > 0.0 && residual(b) < 0.0,
        "no root in [{lo}, {hi}]"
    );
    for _ in 0..200 {
        let m = 0.5 * (a + b);
        if residual(m) > 0.0 {
            a = m;
        } else {
            b = m;
        }
    }
    0.5 * (a + b)
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

#[test]
fn statics_match_the_closed_forms() {
    let (bw, k, w): (f64, f64, f64) = (1.5, 2.0e4, 300.0);
    let p = [bw, k, 0.0];
    for (kind, full, statics, k_v, k_rot, ratio) in [
        (
            "winkler",
            ground::winkler_full as Kernel,
            ground::winkler_statics as fn(f64, &Params) -> [f64; 5],
            2.0 * k * bw,
            2.0 / 3.0 * k * bw.powi(3),
            1.0 / 3.0,
        ),
        (
            "two_spring",
            ground::two_spring_full,
            ground::two_spring_statics,
            2.0 * k,
            2.0 * k * bw * bw,
            1.0,
        ),
    ] {
        let st = statics(w, &p);
        use ground::winkler_statics as i;
        // The settlement solved from the full-contact kernel against W / K_v.
        let v0 = settle(full, 1e-300, w, &p, -1.0, 1.0);
        assert!(rel(v0, w / k_v) < 1e-14, "{kind}: settlement {v0}");
        assert!(rel(st[i::SETTLEMENT], w / k_v) < 1e-15, "{kind}");
        assert!(rel(st[i::K_V], k_v) < 1e-15, "{kind}");
        // Rotational stiffness: the kernel's statics and a central difference of the moment.
        assert!(rel(st[i::K_ROT], k_rot) < 1e-14, "{kind}: {}", st[i::K_ROT]);
        let h = 1e-6;
        let m = |t: f64| -full(&[t, v0, 0.0, 0.0], 1.0, &p)[Q_THETA];
        let fd = (m(h) - m(-h)) / (2.0 * h);
        assert!(rel(fd, k_rot) < 1e-9, "{kind}: dM/dtheta {fd} vs {k_rot}");
        // First edge lift-off: the left corner's depth is 0 at sin(theta) = v0 / B.
        let theta_lift = (v0 / bw).asin();
        assert!(rel(st[i::THETA_LIFT_OFF], theta_lift) < 1e-14, "{kind}");
        let y = [theta_lift, v0, 0.0, 0.0];
        assert!(full(&y, 1.0, &p)[ground::winkler_full::DEPTH_LEFT].abs() < 1e-18);
        let m_lift = ratio * w * bw * theta_lift.cos();
        assert!(rel(st[i::MOMENT_LIFT_OFF], m_lift) < 1e-14, "{kind}");
        assert!(rel(m(theta_lift), m_lift) < 1e-13, "{kind}");
    }
}

#[test]
fn bed_moment_rotation_after_lift_off_approaches_w_b() {
    let (bw, k, w): (f64, f64, f64) = (1.0, 1.0e6, 200.0);
    let p = [bw, k, 0.0];
    let theta_lift = (w / (2.0 * k * bw) / bw).asin();
    let mut worst: f64 = 0.0;
    let mut last = 0.0;
    for j in 1..=40 {
        let theta = theta_lift * (1.0 + 0.25 * f64::from(j) * f64::from(j));
        for s in [1.0, -1.0] {
            let t = s * theta;
            // v from vertical equilibrium in the edge state: the lift-off point inside the base.
            let v = settle(
                ground::winkler_edge,
                t,
                w,
                &p,
                -theta.sin() * bw,
                theta.sin() * bw,
            );
            let out = ground::winkler_edge(&[t, v, 0.0, 0.0], s, &p);
            let x0 = -v / t.sin();
            assert!(x0.abs() < bw, "lift-off point {x0} outside the base");
            let contact = (1.0 - s * x0 / bw) / 2.0;
            assert!(rel(out[ground::winkler_edge::CONTACT_FRACTION], contact) < 1e-12);
            let l = (2.0 * w / (k * theta.sin())).sqrt();
            let closed = s * w * theta.cos() * (bw - l / 3.0);
            worst = worst.max(rel(-out[Q_THETA], closed));
            last = closed.abs() / (w * bw);
        }
    }
    assert!(worst < 1e-12, "moment against its closed form: {worst:e}");
    // At theta = 401 theta_lift = 0.040 the contact is 5 % of the base and M = 0.966 W B.
    assert!((last - 0.9660).abs() < 1e-3, "M / (W B) = {last}");
}

#[test]
fn two_springs_after_lift_off_carry_w_b_cos_theta() {
    let (bw, k, w) = (2.0, 5.0e3, 100.0);
    let p = [bw, k, 0.0];
    for theta in [0.02, 0.1, 0.4] {
        let v = settle(ground::two_spring_edge, theta, w, &p, -1.0, 1.0);
        let out = ground::two_spring_edge(&[theta, v, 0.0, 0.0], 1.0, &p);
        assert!(rel(-out[Q_THETA], w * bw * theta.cos()) < 1e-13);
        assert!(rel(out[ground::two_spring_edge::PRESSURE_HI], w) < 1e-13);
        assert_eq!(out[ground::two_spring_edge::PRESSURE_LO], 0.0);
    }
}

/// A state with the lift-off point at x0 = -v / sin(theta) in the base (|x0| < B) for the edge
/// kernels, full contact (both corners pressing) otherwise.
fn states(edge: bool) -> Vec<([f64; 4], f64)> {
    let mut out = Vec::new();
    for (theta, x0, rate) in [
        (0.05, -0.4, 0.3),
        (-0.2, 0.7, -1.1),
        (0.3, 0.9, 0.05),
        (-0.01, -0.2, 2.0),
    ] {
        let v = if edge {
            -x0 * f64::sin(theta)
        } else {
            0.03 + f64::abs(f64::sin(theta))
        };
        out.push(([theta, v, rate, -0.7 * rate], f64::signum(theta)));
    }
    out
}

#[test]
fn springs_are_conservative_and_the_power_balance_closes() {
    let p = [1.0, 3.0e3, 40.0];
    let spring = [p[0], p[1], 0.0];
    for (name, kernel) in KERNELS {
        for (y, s) in states(name.ends_with("edge")) {
            let g = kernel(&y, s, &p);
            let spring_only = kernel(&y, s, &spring);
            // Q_spring = -grad V, by central differences in theta and v.
            for (i, q) in [(0, Q_THETA), (1, Q_V)] {
                let h = 1e-7;
                let mut a = y;
                let mut b = y;
                a[i] += h;
                b[i] -= h;
                let dv = (kernel(&a, s, &p)[STRAIN] - kernel(&b, s, &p)[STRAIN]) / (2.0 * h);
                let scale = spring_only[q].abs().max(1e-3 * p[1]);
                assert!(
                    (spring_only[q] + dv).abs() < 1e-6 * scale,
                    "{name} at {y:?}: Q {} vs -dV {}",
                    spring_only[q],
                    -dv
                );
            }
            // The ground's power on the base is -(dV/dt + D): dV/dt along (theta', v').
            let h = 1e-7;
            let step = |t: f64| {
                let z = [y[0] + t * y[2], y[1] + t * y[3], y[2], y[3]];
                kernel(&z, s, &p)[STRAIN]
            };
            let dvdt = (step(h) - step(-h)) / (2.0 * h);
            let power = g[Q_THETA] * y[2] + g[Q_V] * y[3];
            let scale = power.abs().max(g[DISSIPATION]).max(1e-3);
            assert!(
                (power + dvdt + g[DISSIPATION]).abs() < 1e-6 * scale,
                "{name} at {y:?}: power {power} vs -(dV/dt + D) {}",
                -(dvdt + g[DISSIPATION])
            );
            assert!(g[DISSIPATION] >= 0.0, "{name}: D = {}", g[DISSIPATION]);
        }
    }
}

#[test]
fn states_agree_where_they_meet() {
    let p: [f64; 3] = [1.2, 4.0e3, 25.0];
    for s in [1.0, -1.0] {
        let theta: f64 = s * 0.08;
        // The left (s = +1) or right corner exactly at the ground: full contact and one edge
        // lifted are the same forces, energy and power there.
        let v = p[0] * f64::sin(theta.abs());
        let y = [theta, v, 0.4 * s, 0.1];
        // The bed: the same forces, energy and power (the lost edge has no length).
        let a = ground::winkler_full(&y, s, &p);
        let b = ground::winkler_edge(&y, s, &p);
        for k in [Q_THETA, Q_V, STRAIN, DISSIPATION] {
            assert!(
                (a[k] - b[k]).abs() <= 1e-12 * a[k].abs().max(1.0),
                "{k}: {a:?} {b:?}"
            );
        }
        // Two springs: the springs agree; the lifting corner's dashpot force c d' is dropped (or,
        // landing, taken up) at once: a jump of c d' in R_v, of c d' B cos(theta) in the moment.
        let a = ground::two_spring_full(&y, s, &p);
        let b = ground::two_spring_edge(&y, s, &p);
        let rate = y[3] - s * p[0] * theta.cos() * y[2]; // d' of the corner -s B
        assert!((a[STRAIN] - b[STRAIN]).abs() <= 1e-12 * a[STRAIN]);
        assert!((a[Q_V] - b[Q_V] + p[2] * rate).abs() <= 1e-12 * a[Q_V].abs());
        let jump = p[2] * rate * s * p[0] * theta.cos();
        assert!((a[Q_THETA] - b[Q_THETA] - jump).abs() <= 1e-12 * a[Q_THETA].abs());
        assert!(
            (a[DISSIPATION] - b[DISSIPATION] - p[2] * rate * rate).abs() <= 1e-12 * a[DISSIPATION]
        );
        // The pressing corner at the ground with the base centre above it: edge meets flight.
        let y = [theta, -p[0] * f64::sin(theta.abs()), 0.4 * s, 0.1];
        for edge in [ground::winkler_edge as Kernel, ground::two_spring_edge] {
            let b = edge(&y, s, &p);
            assert!(b[STRAIN].abs() < 1e-20, "{b:?}");
        }
        let b = ground::winkler_edge(&y, s, &p);
        assert!(b[Q_V].abs() < 1e-12 && b[Q_THETA].abs() < 1e-12, "{b:?}");
    }
}

#[test]
fn mirror_symmetry() {
    let p = [0.8, 1.0e4, 60.0];
    for (name, kernel) in KERNELS {
        for (y, s) in states(name.ends_with("edge")) {
            let a = kernel(&y, s, &p);
            let b = kernel(&[-y[0], y[1], -y[2], y[3]], -s, &p);
            use ground::winkler_full as o;
            let pairs = [
                (a[o::Q_THETA], -b[o::Q_THETA]),
                (a[o::Q_V], b[o::Q_V]),
                (a[o::STRAIN], b[o::STRAIN]),
                (a[o::DISSIPATION], b[o::DISSIPATION]),
                (a[o::CONTACT_FRACTION], b[o::CONTACT_FRACTION]),
                (a[o::PRESSURE_LO], b[o::PRESSURE_HI]),
                (a[o::DEPTH_LEFT], b[o::DEPTH_RIGHT]),
            ];
            for (k, (u, v)) in pairs.iter().enumerate() {
                assert!(
                    (u - v).abs() <= 1e-12 * u.abs().max(1.0),
                    "{name} pair {k}: {u} vs {v}"
                );
            }
        }
    }
}
