//! The Taylor-mode kernels (`rocking_kernels::taylor`) on every variant.
//!
//! The identity checked is the energy balance, order by order: along the series solution
//! x(t0 + h) = Σ x_k h^k of the rocking (or contact) equations, the series of the total energy
//! E = T + V_g + V_s and of the power P = ground − damping must satisfy k E_k = P_{k−1} for every
//! k ≥ 1. Energy and power come from other kernels than the right-hand side, so one wrong
//! coefficient anywhere in x breaks the identity at its order. The first coefficient is also
//! compared with the ordinary right-hand-side kernel. Second, independently, the coefficients
//! of the right-hand sides are compared with CasADi's own derivatives (the IR's `taylor_golden`).

use rocking_kernels::{kernels, taylor, Physical};

/// Coefficients per series: order 23 of the solution.
const N: usize = 24;

mod common;
use common::Rng;

/// Taylor coefficients of a sine ground motion `a sin(ω t + φ)` about t0 = 0.
fn sine_series(a: f64, omega: f64, phi: f64) -> [f64; N] {
    let mut out = [0.0; N];
    let mut factor = a; // a ω^k / k!
    for (k, c) in out.iter_mut().enumerate() {
        *c = factor * (phi + k as f64 * std::f64::consts::FRAC_PI_2).sin();
        factor *= omega / (k + 1) as f64;
    }
    out
}

/// Worst violation of k E_k = P_{k-1}, relative to the size of the terms at each order.
fn energy_identity(energy: &[[f64; N]; 4], power: &[[f64; N]; 2]) -> f64 {
    let mut worst: f64 = 0.0;
    for k in 1..N {
        let kf = k as f64;
        let lhs = kf * (energy[0][k] + energy[1][k] + energy[2][k]);
        let rhs = power[0][k - 1] - power[1][k - 1];
        let scale = kf * (energy[0][k].abs() + energy[1][k].abs() + energy[2][k].abs())
            + power[0][k - 1].abs()
            + power[1][k - 1].abs();
        if scale > 0.0 {
            worst = worst.max((lhs - rhs).abs() / scale);
        }
    }
    worst
}

/// Largest difference of two series solutions, coefficient by coefficient, relative to the
/// largest coefficient of the same order (at least 1e-300).
fn series_difference<const D: usize>(a: &[[f64; N]; D], b: &[[f64; N]; D]) -> f64 {
    let mut worst: f64 = 0.0;
    for k in 0..N {
        let scale = (0..D).map(|i| a[i][k].abs()).fold(1e-300, f64::max);
        for i in 0..D {
            worst = worst.max((a[i][k] - b[i][k]).abs() / scale);
        }
    }
    worst
}

/// One module per variant (its own codegen unit: the inlined series kernels of every variant in
/// one function took 3.5 min to compile on one core), with one test.
macro_rules! check_variant {
    ($m:ident, $rigid:expr) => {
        mod $m {
            use super::*;

            #[test]
            fn series_solutions_balance_energy_order_by_order() {
        let mut rng = Rng(0x7a71_0e00 ^ stringify!($m).len() as u64);
        let mut worst: f64 = 0.0;
        // The first coefficient against the pointwise kernel (the same tape, regrouped).
        let mut first: f64 = 0.0;
        // The `_free` twins against the kernels with ug ≡ 0 (the same tape without the input).
        let mut free: f64 = 0.0;
        for _ in 0..50 {
            let alpha = rng.range(0.05, 0.4);
            let phys = Physical::dimensionless(
                alpha,
                rng.range(2.0, 30.0),
                rng.range(0.0, 2.0),
                rng.range(0.0, 2.0),
                rng.range(0.9, 1.2),
                rng.range(0.0, 0.1),
            );
            let p = kernels::$m::params(&phys);
            let ug = sine_series(
                rng.range(-0.5, 0.5),
                rng.range(1.0, 8.0),
                rng.range(0.0, 6.3),
            );
            let (u, ud) = if $rigid {
                (0.0, 0.0)
            } else {
                (rng.range(-0.02, 0.02), rng.range(-0.1, 0.1))
            };
            // Rocking about either corner.
            for s in [1.0, -1.0] {
                let x0 = [s * rng.range(0.0, alpha), u, rng.range(-0.5, 0.5), ud];
                let mut x = [[0.0; N]; 4];
                for i in 0..4 {
                    x[i][0] = x0[i];
                }
                taylor::$m::rocking_rhs::<N>(&mut x, &ug, s, &p);
                let f = kernels::$m::rocking_rhs(&x0, ug[0], s, &p);
                for i in 0..4 {
                    first = first.max((x[i][1] - f[i]).abs() / f[i].abs().max(1.0));
                }
                let e = taylor::$m::energy::<N>(&x, s, &p);
                let pw = taylor::$m::power::<N>(&x, &ug, s, &p);
                worst = worst.max(energy_identity(&e, &pw));
                let (mut with_zero, mut twin) = ([[0.0; N]; 4], [[0.0; N]; 4]);
                for i in 0..4 {
                    with_zero[i][0] = x0[i];
                    twin[i][0] = x0[i];
                }
                taylor::$m::rocking_rhs::<N>(&mut with_zero, &[0.0; N], s, &p);
                taylor::$m::rocking_rhs_free::<N>(&mut twin, s, &p);
                free = free.max(series_difference(&with_zero, &twin));
            }
            // Full contact: θ ≡ 0, the column vibrates.
            let mut xc = [[0.0; N]; 2];
            xc[0][0] = u;
            xc[1][0] = ud;
            let (mut with_zero, mut twin) = (xc, xc);
            taylor::$m::contact_rhs::<N>(&mut with_zero, &[0.0; N], &p);
            taylor::$m::contact_rhs_free::<N>(&mut twin, &p);
            free = free.max(series_difference(&with_zero, &twin));
            taylor::$m::contact_rhs::<N>(&mut xc, &ug, &p);
            let x = [[0.0; N], xc[0], [0.0; N], xc[1]];
            let e = taylor::$m::energy::<N>(&x, 1.0, &p);
            let pw = taylor::$m::power::<N>(&x, &ug, 1.0, &p);
            worst = worst.max(energy_identity(&e, &pw));
        }
        eprintln!(
            "taylor {}: worst relative violation of k E_k = P_(k-1) up to order {}: {worst:.1e}",
            stringify!($m),
            N - 1
        );
        eprintln!(
            "taylor {}: first coefficient against the rhs: {first:.1e}",
            stringify!($m)
        );
        eprintln!(
            "taylor {}: free twins against ug = 0: {free:.1e}",
            stringify!($m)
        );
        // The twin's tape is regrouped (its products with ug are gone), so its rounding differs:
        // up to 8.8e-13 of the order's scale at order 23 (massless_base). A wrong term would be
        // of the order of the coefficient itself.
        assert!(free < 1e-11, "{}: free twin {free:e}", stringify!($m));
        assert!(
            first < 1e-13,
            "{}: first coefficient {first:e}",
            stringify!($m)
        );
        assert!(worst < 1e-11, "{}: {worst:e}", stringify!($m));
            }
        }
    };
}

check_variant!(full, false);
check_variant!(massless_column, false);
check_variant!(massless_base, false);
check_variant!(point_mass, false);
check_variant!(rigid, true);
check_variant!(small_angle, false);
check_variant!(cosine_shape, false);
check_variant!(added_mass, false);
check_variant!(cantilever_modes1, false);

/// The uplift function's series along a contact solution matches its values at nearby times,
/// computed by the ordinary kernels on the series state: the series of a composition is the
/// composition of the series (to the truncation error at a small step).
#[test]
fn uplift_series_agrees_with_pointwise_evaluation() {
    let phys = Physical::dimensionless(0.2, 5.0, 1.0, 1.0, 1.0, 0.02);
    let p = kernels::full::params(&phys);
    let ug = sine_series(0.1, 3.0, 0.4);
    let mut xc = [[0.0; N]; 2];
    xc[0][0] = 0.01;
    xc[1][0] = -0.03;
    taylor::full::contact_rhs::<N>(&mut xc, &ug, &p);
    let fs = taylor::full::uplift::<N>(&xc, &ug, 1.0, &p);
    let eval = |c: &[f64; N], h: f64| c.iter().rev().fold(0.0, |acc, v| acc * h + v);
    for h in [0.01, 0.05, 0.1] {
        let state = [eval(&xc[0], h), eval(&xc[1], h)];
        let direct = kernels::full::uplift(&state, eval(&ug, h), 1.0, &p);
        let series = eval(&fs[0], h);
        assert!(
            (direct - series).abs() <= 1e-13 * direct.abs().max(1.0),
            "h = {h}: uplift {direct} vs its series {series}"
        );
    }
}

/// Coefficients 1..=order of every component of a series solution, order by order.
fn coefficients<const D: usize>(x: &[[f64; N]; D], order: usize) -> Vec<f64> {
    (1..=order)
        .flat_map(|n| x.iter().map(move |c| c[n]))
        .collect()
}

/// A series state whose first coefficients are `values`.
fn state<const D: usize>(values: Vec<f64>) -> [[f64; N]; D] {
    assert_eq!(values.len(), D, "state length");
    let mut x = [[0.0; N]; D];
    for (c, v) in x.iter_mut().zip(values) {
        c[0] = v;
    }
    x
}

/// Defines `taylor_rhs(variant, function, input, order)`: the Taylor-mode right-hand side
/// `function` of `variant` run on inputs looked up by their IR name (the state's values, the
/// ground acceleration's coefficients, s, the parameters), returning coefficients 1..=order of
/// every state component in the layout of the IR's `taylor_golden` outputs.
macro_rules! taylor_rhs_by_name {
    ($($T:ident => $m:ident: $L:ident),* $(,)?) => {
        fn taylor_rhs(variant: &str, function: &str, input: &dyn Fn(&str) -> Vec<f64>, order: usize) -> Vec<f64> {
            let mut ug = [0.0; N];
            let g = input("ug");
            ug[..g.len()].copy_from_slice(&g);
            match (variant, function) {
                $(
                    (stringify!($m), "rocking_rhs") => by_name::$m::rocking_rhs(&ug, input, order),
                    (stringify!($m), "contact_rhs") => by_name::$m::contact_rhs(&ug, input, order),
                )*
                _ => panic!("{variant}::{function} has no Taylor-mode kernel"),
            }
        }

        /// One module per variant: each its own codegen unit (see `check_variant!`).
        mod by_name {
            $(
                pub mod $m {
                    use super::super::*;

                    pub fn rocking_rhs(ug: &[f64; N], input: &dyn Fn(&str) -> Vec<f64>, order: usize) -> Vec<f64> {
                        let p: kernels::$m::Params = input("p").try_into().expect("parameter count");
                        let mut x = state::<{ kernels::layout::$L::X }>(input("x"));
                        taylor::$m::rocking_rhs::<N>(&mut x, ug, input("s")[0], &p);
                        coefficients(&x, order)
                    }

                    pub fn contact_rhs(ug: &[f64; N], input: &dyn Fn(&str) -> Vec<f64>, order: usize) -> Vec<f64> {
                        let p: kernels::$m::Params = input("p").try_into().expect("parameter count");
                        let mut xc = state::<{ kernels::layout::$L::XC }>(input("xc"));
                        taylor::$m::contact_rhs::<N>(&mut xc, ug, &p);
                        coefficients(&xc, order)
                    }
                }
            )*
        }
    };
}
rocking_kernels::for_each_variant!(taylor_rhs_by_name, layout);

/// The coefficient kernels against CasADi's own derivatives: each IR's `taylor_golden` holds the
/// solution's Taylor coefficients x_1..x_8 at sampled states, from repeated symbolic Lie
/// derivatives of the right-hand side (derive/rocking_derive/ir.py, `taylor_golden`), an
/// algorithm independent of the Taylor-mode recurrences on the tape. Agreement to 1e-12 of the
/// largest coefficient of the same order, times max(1, κ(M)/100) for a mass matrix of condition
/// number κ (a coefficient near zero by cancellation is compared
/// at its order's scale).
#[test]
fn taylor_kernels_match_casadi_derivatives() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("ir");
    let mut files: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "json")) // ground/: tests/ground.rs
        .collect();
    files.sort();
    let (mut checked, mut worst, mut worst_kappa) = (0usize, 0.0f64, 0.0f64);
    for file in files {
        let ir: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(&file).unwrap()).unwrap();
        let variant = ir["variant"].as_str().unwrap();
        let mut found = 0;
        for function in ir["functions"].as_array().unwrap() {
            let Some(samples) = function.get("taylor_golden") else {
                continue;
            };
            found += 1;
            let name = function["name"].as_str().unwrap();
            let order = function["taylor_order"].as_u64().unwrap() as usize;
            let names: Vec<&str> = function["inputs"]
                .as_array()
                .unwrap()
                .iter()
                .map(|i| i["name"].as_str().unwrap())
                .collect();
            let floats = |v: &serde_json::Value| -> Vec<f64> {
                v.as_array()
                    .unwrap()
                    .iter()
                    .map(|x| x.as_f64().expect("a finite number"))
                    .collect()
            };
            for sample in samples.as_array().unwrap() {
                let inputs = sample["inputs"].as_array().unwrap();
                let input = |n: &str| {
                    let k = names.iter().position(|m| *m == n);
                    floats(&inputs[k.unwrap_or_else(|| panic!("{variant}::{name}: no input {n}"))])
                };
                // Solving M q'' = F loses digits with the condition number of M: 1e-12 for a
                // well-conditioned basis (one function, cantilever modes), more for a monomial
                // basis (eta^2, eta^3, eta^4 are nearly parallel: kappa(M_uu) ~ 1e4).
                let kappa = rocking_kernels::with_variant!(variant, V, L => {
                    let p: <V as rocking_kernels::Variant>::Params =
                        input("p").try_into().expect("parameter count");
                    let m = rocking_kernels::modes::Matrices::of::<V>(&p).mass;
                    let e = m.symmetric_eigenvalues();
                    e.max() / e.min()
                })
                .expect("a registered variant");
                let tolerance = 1e-12 * (kappa / 100.0).max(1.0);
                let want = floats(&sample["output"]);
                let got = taylor_rhs(variant, name, &input, order);
                assert_eq!(got.len(), want.len(), "{variant}::{name}: output length");
                let dim = want.len() / order;
                for n in 0..order {
                    let row = n * dim..(n + 1) * dim;
                    let scale = want[row.clone()]
                        .iter()
                        .fold(f64::MIN_POSITIVE, |m, w| m.max(w.abs()));
                    for k in row {
                        let err = (got[k] - want[k]).abs() / scale;
                        worst = worst.max(err);
                        worst_kappa = worst_kappa.max(err / tolerance * 1e-12);
                        assert!(
                            err <= tolerance,
                            "{variant}::{name}: coefficient {} of component {}: {} vs CasADi {} ({err:.1e} of the order's scale)",
                            n + 1,
                            k % dim,
                            got[k],
                            want[k]
                        );
                        checked += 1;
                    }
                }
            }
        }
        assert_eq!(
            found, 2,
            "{variant}: rocking_rhs and contact_rhs carry taylor_golden"
        );
    }
    assert!(checked > 0, "no Taylor golden coefficients found");
    eprintln!(
        "{checked} Taylor coefficients match CasADi's derivatives; worst {worst:.1e} of their \
         order's scale, {worst_kappa:.1e} after dividing by max(1, kappa(M) / 100)"
    );
}

/// The same identities for the variants of n > 1 deformation coordinates (state
/// `[θ, u_1..u_n, θ', u_1'..u_n']`), on structures with a column mass (without one their mass
/// matrix is singular). The first coefficient solves M q'' = F like the pointwise kernel, each
/// with its own rounding, so its bound is 1e-12 × max(1, κ(M)/100) as in
/// `taylor_kernels_match_casadi_derivatives` (the monomial basis η², η³, η⁴ has κ ~ 1e4; the
/// one-coordinate variants meet 1e-13 above); every coefficient of the series solves it again,
/// so the energy identity's 1e-11 is divided by the same factor. So is the `_free` twins' 1e-11:
/// without the excitation's terms the simplifier may group a sum differently, and the solve
/// amplifies that rounding like any other.
macro_rules! check_coordinates {
    ($ty:ident, $m:ident, $n:literal) => {
        mod $m {
            use super::*;

            #[test]
            fn series_solutions_balance_energy_order_by_order() {
        const NX: usize = 2 + 2 * $n;
        const NC: usize = 2 * $n;
        let mut rng = Rng(0x7a71_0e01 ^ stringify!($m).len() as u64);
        let (mut worst, mut first, mut free): (f64, f64, f64) = (0.0, 0.0, 0.0);
        for _ in 0..50 {
            let alpha = rng.range(0.05, 0.4);
            let phys = Physical::dimensionless_with::<kernels::$ty>(
                alpha,
                rng.range(2.0, 30.0),
                rng.range(0.5, 2.0),
                rng.range(0.0, 2.0),
                rng.range(0.9, 1.2),
                rng.range(0.0, 0.1),
                &[],
            );
            let p = <kernels::$ty as rocking_kernels::Variant>::params(&phys);
            let mass = rocking_kernels::modes::Matrices::of::<kernels::$ty>(&p)
                .mass
                .symmetric_eigenvalues();
            let conditioning = (mass.max() / mass.min() / 100.0).max(1.0);
            let bound = 1e-12 * conditioning;
            let ug = sine_series(rng.range(-0.5, 0.5), rng.range(1.0, 8.0), rng.range(0.0, 6.3));
            let u: [f64; $n] = std::array::from_fn(|_| rng.range(-0.02, 0.02));
            let ud: [f64; $n] = std::array::from_fn(|_| rng.range(-0.1, 0.1));
            for s in [1.0, -1.0] {
                let theta = [s * rng.range(0.0, alpha), rng.range(-0.5, 0.5)];
                let x0: [f64; NX] = std::array::from_fn(|i| match i {
                    0 => theta[0],
                    i if i <= $n => u[i - 1],
                    i if i == $n + 1 => theta[1],
                    i => ud[i - $n - 2],
                });
                let mut x = [[0.0; N]; NX];
                for i in 0..NX {
                    x[i][0] = x0[i];
                }
                let mut twin = x;
                taylor::$m::rocking_rhs::<N>(&mut x, &ug, s, &p);
                let f = kernels::$m::rocking_rhs(&x0, ug[0], s, &p);
                // Relative to the largest component: M⁻¹ spreads every coordinate's elastic force
                // over θ'' and the u_i'' (with eight modes K reaches (ω_8/ω_1)² ~ 3e4 times the
                // first mode's stiffness), so a small component is the difference of large terms.
                let largest = f.iter().fold(1.0f64, |m, v| m.max(v.abs()));
                for i in 0..NX {
                    first = first.max((x[i][1] - f[i]).abs() / largest / bound * 1e-12);
                }
                let e = taylor::$m::energy::<N>(&x, s, &p);
                let pw = taylor::$m::power::<N>(&x, &ug, s, &p);
                worst = worst.max(energy_identity(&e, &pw) / conditioning);
                let mut with_zero = twin;
                taylor::$m::rocking_rhs::<N>(&mut with_zero, &[0.0; N], s, &p);
                taylor::$m::rocking_rhs_free::<N>(&mut twin, s, &p);
                free = free.max(series_difference(&with_zero, &twin) / conditioning);
            }
            // Full contact: θ ≡ 0.
            let mut xc = [[0.0; N]; NC];
            for i in 0..$n {
                xc[i][0] = u[i];
                xc[$n + i][0] = ud[i];
            }
            let (mut with_zero, mut twin) = (xc, xc);
            taylor::$m::contact_rhs::<N>(&mut with_zero, &[0.0; N], &p);
            taylor::$m::contact_rhs_free::<N>(&mut twin, &p);
            free = free.max(series_difference(&with_zero, &twin) / conditioning);
            taylor::$m::contact_rhs::<N>(&mut xc, &ug, &p);
            let mut x = [[0.0; N]; NX];
            for i in 0..$n {
                x[1 + i] = xc[i];
                x[$n + 2 + i] = xc[$n + i];
            }
            let e = taylor::$m::energy::<N>(&x, 1.0, &p);
            let pw = taylor::$m::power::<N>(&x, &ug, 1.0, &p);
            worst = worst.max(energy_identity(&e, &pw) / conditioning);
        }
        eprintln!(
            "taylor {}: k E_k = P_(k-1) up to order {}: {worst:.1e} (divided by max(1, kappa/100)); first coefficient {first:.1e} \
             (of 1e-12 x max(1, kappa/100)); free twins {free:.1e} (divided by max(1, kappa/100))",
            stringify!($m),
            N - 1
        );
        assert!(free < 1e-11, "{}: free twin {free:e}", stringify!($m));
        assert!(first < 1e-12, "{}: first coefficient {first:e}", stringify!($m));
        assert!(worst < 1e-11, "{}: {worst:e}", stringify!($m));
            }
        }
    };
}

check_coordinates!(Polynomial2, polynomial2, 2);
check_coordinates!(Polynomial3, polynomial3, 3);
check_coordinates!(CantileverModes2, cantilever_modes2, 2);
check_coordinates!(CantileverModes3, cantilever_modes3, 3);
check_coordinates!(CantileverModes4, cantilever_modes4, 4);
check_coordinates!(CantileverModes5, cantilever_modes5, 5);
check_coordinates!(CantileverModes6, cantilever_modes6, 6);
check_coordinates!(CantileverModes7, cantilever_modes7, 7);
check_coordinates!(CantileverModes8, cantilever_modes8, 8);
check_coordinates!(CubicQuadratic, cubic_quadratic, 2);
