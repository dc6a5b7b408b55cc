//! The power-series recurrences on series with known coefficients (an integration test, so that
//! `cargo test` does not compile the generated kernels a second time as a unit-test harness).

use rocking_kernels::series::{div, mul, sin_cos, sq, sqrt};

/// exp-free checks on series with known coefficients.
#[test]
fn recurrences_match_known_series() {
    // a = 1 + t, b = 2 - t + t^2
    let a = [1.0, 1.0, 0.0, 0.0, 0.0, 0.0];
    let b = [2.0, -1.0, 1.0, 0.0, 0.0, 0.0];
    let prod: Vec<f64> = (0..6).map(|k| mul(&a, &b, k)).collect();
    assert_eq!(prod, [2.0, 1.0, 0.0, 1.0, 0.0, 0.0]);
    let squares: Vec<f64> = (0..6).map(|k| sq(&b, k)).collect();
    let cauchy: Vec<f64> = (0..6).map(|k| mul(&b, &b, k)).collect();
    assert_eq!(squares, cauchy);
    // 1 / (1 - t) = Σ t^k
    let one = [1.0, 0.0, 0.0, 0.0, 0.0, 0.0];
    let d = [1.0, -1.0, 0.0, 0.0, 0.0, 0.0];
    let mut q = [0.0; 6];
    for k in 0..6 {
        q[k] = div(one[k], &d, &q, 1.0 / d[0], k);
    }
    assert_eq!(q, [1.0; 6]);
    // √(1 + 2t + t²) = 1 + t
    let mut r = [0.0; 6];
    for k in 0..6 {
        sqrt(&[1.0, 2.0, 1.0, 0.0, 0.0, 0.0], &mut r, k);
    }
    assert_eq!(r, a);
    // sin(t), cos(t): 1/k! with alternating signs
    let t = [0.0, 1.0, 0.0, 0.0, 0.0, 0.0];
    let (mut dt, mut s, mut c) = ([0.0; 6], [0.0; 6], [0.0; 6]);
    for k in 0..6 {
        sin_cos(&t, &mut dt, &mut s, &mut c, k);
    }
    let want_s = [0.0, 1.0, 0.0, -1.0 / 6.0, 0.0, 1.0 / 120.0];
    let want_c = [1.0, 0.0, -0.5, 0.0, 1.0 / 24.0, 0.0];
    for k in 0..6 {
        assert!((s[k] - want_s[k]).abs() < 1e-16, "sin[{k}] = {}", s[k]);
        assert!((c[k] - want_c[k]).abs() < 1e-16, "cos[{k}] = {}", c[k]);
    }
}
