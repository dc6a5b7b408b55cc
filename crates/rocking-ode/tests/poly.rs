//! Root isolation on a step: every sign change is found, double roots and grazing included.

use rocking_ode::events::Direction;
use rocking_ode::poly::{abs_tail, first_root, horner};

const EPS: f64 = f64::EPSILON;

/// Coefficients of Π (τ − r_i) · lead.
fn from_roots(roots: &[f64], lead: f64) -> Vec<f64> {
    let mut c = vec![lead];
    for &r in roots {
        let mut next = vec![0.0; c.len() + 1];
        for (k, &ck) in c.iter().enumerate() {
            next[k + 1] += ck;
            next[k] -= r * ck;
        }
        c = next;
    }
    c
}

#[test]
fn double_root_just_inside_the_step_is_found() {
    // g = −(τ − r)² (1 + τ), r = 1 − 2⁻²⁰: exact coefficients, touches 0 from below at r < h = 1.
    let r = 1.0 - (2.0f64).powi(-20);
    let q = [r * r, -2.0 * r, 1.0]; // (τ − r)², exact
    let g = [-q[0], -(q[0] + q[1]), -(q[1] + q[2]), -q[2]];
    let root = first_root(&g, 1.0, Direction::Rising).expect("touching root missed");
    println!(
        "double root: tau − r = {:.2e}, cluster {}",
        root.tau - r,
        root.cluster
    );
    // Placed at the extremum (Newton on g' from where |g| falls below the rounding bound).
    assert!((root.tau - r).abs() <= 1e-12, "{root:?}");
    assert!(root.rising);
    assert!(first_root(&g, 1.0, Direction::Falling).is_none());
    // The mirror image touches from above: a falling event.
    let gm: Vec<f64> = g.iter().map(|v| -v).collect();
    let root = first_root(&gm, 1.0, Direction::Falling).expect("touch from above missed");
    assert!((root.tau - r).abs() <= 1e-12 && !root.rising);
    // A non-dyadic double root, close to the step end: (τ − 0.7)² (τ − 3) · (−1) touches zero
    // within rounding; it must be reported or, if rounding pushes the maximum below zero, the
    // maximum must be within rounding of zero.
    let g = from_roots(&[0.7, 0.7, 3.0], 1.0);
    let root = first_root(&g, 0.7000001, Direction::Rising).expect("non-dyadic double root");
    println!(
        "non-dyadic double root: tau − 0.7 = {:.2e} (cluster {})",
        root.tau - 0.7,
        root.cluster
    );
    assert!((root.tau - 0.7).abs() <= 1e-12);
}

#[test]
fn two_close_roots_are_both_found() {
    let (r1, r2) = (0.5, 0.5 + (2.0f64).powi(-30));
    let g = [r1 * r2, -(r1 + r2), 1.0]; // exact
    let a = first_root(&g, 1.0, Direction::Falling).unwrap();
    let b = first_root(&g, 1.0, Direction::Rising).unwrap();
    let e = first_root(&g, 1.0, Direction::Either).unwrap();
    println!(
        "close roots 2^-30 apart: errors {:.1e} {:.1e}",
        a.tau - r1,
        b.tau - r2
    );
    assert!((a.tau - r1).abs() <= 2.0 * EPS && (b.tau - r2).abs() <= 2.0 * EPS);
    assert_eq!(e, a);
    assert!(!a.cluster && !b.cluster);
    assert!(a.tau_before <= a.tau && a.tau - a.tau_before <= 2.0 * EPS * a.tau);
}

#[test]
fn root_exactly_at_the_step_end() {
    // (τ − 1)(τ + 2), h = 1: rising exactly at the end.
    let g = [-2.0, 1.0, 1.0];
    let r = first_root(&g, 1.0, Direction::Rising).unwrap();
    assert_eq!(r.tau, 1.0);
    assert!(r.rising && r.tau_before < r.tau);
    assert!(first_root(&g, 1.0, Direction::Falling).is_none());
    // Same at a non-unit step: (τ − 0.25)(τ − 3) · (−1), h = 0.25 exactly.
    let g = [-0.75, 3.25, -1.0];
    let r = first_root(&g, 0.25, Direction::Rising).unwrap();
    assert_eq!(r.tau, 0.25);
    // An interior root followed by one at the end.
    let g = from_roots(&[0.5, 1.0], 1.0); // + on (0, .5), − on (.5, 1), 0 at 1
    assert_eq!(first_root(&g, 1.0, Direction::Rising).unwrap().tau, 1.0);
    assert!((first_root(&g, 1.0, Direction::Falling).unwrap().tau - 0.5).abs() <= 2.0 * EPS);
}

#[test]
fn zero_at_the_step_start_does_not_trigger() {
    // g = τ (τ − 0.5): zero at 0 (a restart on the event surface), rising at 0.5.
    let g = [0.0, -0.5, 1.0];
    assert!(first_root(&g, 1.0, Direction::Falling).is_none());
    let r = first_root(&g, 1.0, Direction::Rising).unwrap();
    assert!((r.tau - 0.5).abs() <= 2.0 * EPS);
    // θ = τ² (0.5 − τ): leaves 0 at the start and falls back through it at 0.5 (an impact after
    // uplift in one step).
    let g = [0.0, 0.0, 0.5, -1.0];
    let r = first_root(&g, 1.0, Direction::Falling).unwrap();
    assert!((r.tau - 0.5).abs() <= 2.0 * EPS);
    assert!(first_root(&[0.0, 0.0, 0.0], 1.0, Direction::Either).is_none());
    assert!(first_root(&[1.0, 0.0], 1.0, Direction::Either).is_none());
}

#[test]
fn grazing_at_one_plus_minus_1e9_is_decided() {
    // g = δ − (τ − r)²: a maximum δ near zero at r. δ = ±1e-9 r² and ±1e-12 r².
    let r = 0.75;
    for rel in [1e-9, -1e-9, 1e-12, -1e-12, 0.0] {
        let delta = rel * r * r;
        let g = [delta - r * r, 2.0 * r, -1.0];
        let res = first_root(&g, 1.0, Direction::Rising);
        if rel > 0.0 {
            // Exact roots of the stored polynomial: r ± √(r² + c0) (r² + c0 exact, Sterbenz).
            let want = r - (r * r + g[0]).sqrt();
            let got = res.expect("grazing crossing missed");
            println!(
                "graze +{rel:.0e}: root {:.17} error {:.1e}",
                got.tau,
                got.tau - want
            );
            // Root condition: rounding of g (ε Σ|c_k τ^k|) over |g'(τ)| = 2√δ.
            let cond = |t: f64| {
                4.0 * EPS * (g[0].abs() + g[1].abs() * t + t * t) / (2.0 * (r - t).abs())
                    + 4.0 * EPS
            };
            assert!((got.tau - want).abs() <= cond(want), "{got:?} vs {want}");
            assert!(!got.cluster);
            let fall = first_root(&g, 1.0, Direction::Falling).unwrap();
            let want = r + (r * r + g[0]).sqrt();
            assert!((fall.tau - want).abs() <= cond(want));
        } else if rel < 0.0 {
            assert!(res.is_none(), "no crossing at {rel:e}: {res:?}");
            assert!(first_root(&g, 1.0, Direction::Either).is_none());
        } else {
            let got = res.expect("touch at exactly zero is reached");
            println!("touch at 0: tau − r = {:.2e}", got.tau - r);
            assert!((got.tau - r).abs() <= 1e-12);
        }
    }
}

/// Deterministic LCG in [-1, 1).
struct Lcg(u64);
impl Lcg {
    fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((self.0 >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0
    }
}

#[test]
fn no_sign_change_is_missed_on_random_polynomials() {
    // Polynomials with 1..6 roots in (0, 1) (some in pairs 1e-6 apart) and random extra factors;
    // the first sign change on a fine grid must be the root found (or the root must lie before
    // the grid's first change, in a gap the grid cannot see).
    let mut rng = Lcg(42);
    let mut checked = 0;
    for case in 0..2000 {
        let k = 1 + case % 6;
        let mut roots: Vec<f64> = (0..k).map(|_| 0.5 + 0.5 * rng.next()).collect();
        if case % 3 == 0 {
            roots.push(roots[0] + 1e-6);
        }
        roots.push(2.0 + rng.next()); // outside the step
        let g = from_roots(&roots, 1.0 + rng.next().abs());
        for dir in [Direction::Rising, Direction::Falling, Direction::Either] {
            let found = first_root(&g, 1.0, dir);
            // Grid scan.
            let n = 20_000;
            let mut prev = horner(&g, 0.0);
            let mut grid = None;
            for i in 1..=n {
                let t = i as f64 / n as f64;
                let v = horner(&g, t);
                if dir.triggers(prev, v) {
                    grid = Some(t);
                    break;
                }
                prev = v;
            }
            match (grid, found) {
                (Some(t), Some(r)) => {
                    assert!(
                        r.tau <= t + 1e-12,
                        "case {case}: root {r:?} after grid change {t}"
                    );
                    checked += 1;
                }
                (Some(t), None) => panic!("case {case} {dir:?}: missed change at {t}, g = {g:?}"),
                (None, Some(r)) => {
                    // Only roots the grid cannot resolve (pairs closer than its spacing).
                    let v = horner(&g, r.tau);
                    assert!(v.abs() < 1e-9 || roots.iter().any(|&x| (x - r.tau).abs() < 1e-4));
                }
                (None, None) => {}
            }
        }
    }
    println!("random polynomials: {checked} grid crossings matched");
    assert!(checked > 3000);
}

#[test]
fn abs_tail_is_the_sum_of_the_terms_beyond_the_first() {
    for n in 0..=21i32 {
        let c: Vec<f64> = (0..n)
            .map(|k| ((f64::from(k) * 1.7).sin() - 0.3) * 10f64.powi(k % 5 - 2))
            .collect();
        for h in [0.0f64, 1e-3, 0.37, 1.0, 2.5] {
            let exact: f64 = c
                .iter()
                .enumerate()
                .skip(1)
                .map(|(k, v)| v.abs() * h.powi(i32::try_from(k).unwrap()))
                .sum();
            let got = abs_tail(&c, h);
            assert!(
                (got - exact).abs() <= 4.0 * f64::from(n) * EPS * exact,
                "{n} coefficients, h = {h}: {got:e} against {exact:e}"
            );
        }
    }
}
