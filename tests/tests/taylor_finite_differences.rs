//! The Taylor coefficients of the rocking equations (`rocking_kernels::taylor`, the series the
//! Taylor integrator steps with) against finite differences of a tight DOP853 solution of the
//! pointwise equations (issue 45), for the cantilever bases of n = 2 and n = 8 modes on a rocking
//! phase under a sine ground motion: the k-th coefficient times k! is the k-th derivative, k = 1 … 4,
//! of every component of the state [θ, u_1..u_n, θ', u_1'..u_n'].
//!
//! The derivatives are central differences of the DOP853 dense output at t_j = j h, j = −3 … 3,
//! about the state the series starts from (the dense output at 0). Their error, per component,
//! is bounded from h (stated, not fitted):
//!
//! - truncation: the central k-th difference of the minimal stencil is y⁽ᵏ⁾ + C_k h² y⁽ᵏ⁺²⁾ + O(h⁴)
//!   with C = 1/6, 1/12, 1/4, 1/6 for k = 1 … 4; y⁽ᵏ⁺²⁾ is itself estimated by the central
//!   (k+2)-th difference of the same samples (never from the series under test), and the bound is
//!   twice C_k h² |y⁽ᵏ⁺²⁾| (the O(h⁴) rest is (hω)² ≈ 2.5e-3 of it);
//! - the solution's own error δ: each sample is off by at most δ = 100 (atol + rtol |y|) (the
//!   tolerances' local error, with a factor 100 for its accumulation over the few steps run and
//!   the dense output between steps), which the stencil amplifies by Σ|w_j| / h^k (1, 4, 3, 16
//!   for k = 1 … 4).
//!
//! h = 0.05 / ω_max, ω_max the highest fixed-base frequency of the basis (the fastest motion in
//! the solution), so that (h ω_max)² = 2.5e-3 and the bound is about 1e-3 of the derivative,
//! while a wrong term of the series (a missing product, a wrong order) changes the coefficient
//! by its own size. The test also checks that the bound is that tight (below 1 % of the largest
//! derivative of the same order), so it cannot pass by being loose.

use nalgebra::SVector;
use rocking_kernels::modes::Matrices;
use rocking_kernels::{kernels, taylor, Physical, Variant};
use rocking_ode::{Integrator, Method, Options, Tolerances};

/// Coefficients of the series: up to order 7 (derivatives 1 … 4 are compared).
const N: usize = 8;
/// The highest derivative compared.
const K: usize = 4;
/// Samples each side of t = 0.
const J: usize = 3;
/// DOP853 tolerances.
const RTOL: f64 = 1e-13;
const ATOL: f64 = 1e-15;

/// Central-difference stencils on j = −3 … 3 (index j + 3) for derivatives 1 … 6, times h^k.
const STENCIL: [[f64; 2 * J + 1]; 6] = [
    [0.0, 0.0, -0.5, 0.0, 0.5, 0.0, 0.0],
    [0.0, 0.0, 1.0, -2.0, 1.0, 0.0, 0.0],
    [0.0, -0.5, 1.0, 0.0, -1.0, 0.5, 0.0],
    [0.0, 1.0, -4.0, 6.0, -4.0, 1.0, 0.0],
    [-0.5, 2.0, -2.5, 0.0, 2.5, -2.0, 0.5],
    [1.0, -6.0, 15.0, -20.0, 15.0, -6.0, 1.0],
];
/// Leading truncation constants C_k of the stencils of derivatives 1 … 4.
const TRUNCATION: [f64; K] = [1.0 / 6.0, 1.0 / 12.0, 1.0 / 4.0, 1.0 / 6.0];

/// The ground acceleration a sin(ω t + φ) and its Taylor series about t = 0.
const A: f64 = 0.4;
const OMEGA: f64 = 3.0;
const PHI: f64 = 0.7;

fn ground(t: f64) -> f64 {
    A * (OMEGA * t + PHI).sin()
}

fn ground_series() -> [f64; N] {
    let mut out = [0.0; N];
    let mut factor = A; // a ω^k / k!
    for (k, c) in out.iter_mut().enumerate() {
        *c = factor * (PHI + k as f64 * std::f64::consts::FRAC_PI_2).sin();
        factor *= OMEGA / (k + 1) as f64;
    }
    out
}

/// What one comparison found: the worst error over its bound, the worst relative error, and the
/// worst bound relative to the largest derivative of its order.
struct Found {
    over_bound: f64,
    relative: f64,
    tightness: f64,
    h: f64,
    omega_max: f64,
}

macro_rules! compare {
    ($ty:ident, $m:ident, $n:literal) => {{
        const NX: usize = 2 + 2 * $n;
        // A Fig-5-like column (ω_n/p = 5, equal column and base masses) rocking about s = +1.
        let phys = Physical::dimensionless_with::<kernels::$ty>(0.2, 5.0, 1.0, 1.0, 1.0, 0.02, &[]);
        let p = <kernels::$ty as Variant>::params(&phys);
        let s = 1.0;
        let omega_max = Matrices::of::<kernels::$ty>(&p)
            .fixed_base()
            .expect("a positive definite mass matrix")
            .omega
            .iter()
            .fold(0.0f64, |m, &w| m.max(w));
        let h = 0.05 / omega_max;
        // Tilted halfway to α, rocking outwards, each mode deflected and moving.
        let x_start: [f64; NX] = std::array::from_fn(|i| match i {
            0 => 0.1,
            i if i <= $n => 0.01 / (i * i) as f64,
            i if i == $n + 1 => 0.3,
            i => 0.05 / (i - $n - 1) as f64,
        });
        let mut rhs = |t: f64, y: &SVector<f64, NX>| {
            let x: [f64; NX] = std::array::from_fn(|i| y[i]);
            SVector::from(kernels::$m::rocking_rhs(&x, ground(t), s, &p))
        };
        let mut ode = Integrator::<NX>::new(
            Options::new(Method::Dop853),
            Tolerances::uniform(RTOL, ATOL),
        )
        .unwrap();
        let t0 = -10.0 * h;
        ode.reset(t0, SVector::from(x_start), &mut rhs).unwrap();
        let mut samples = [[0.0; NX]; 2 * J + 1];
        let mut next = 0;
        while next < samples.len() {
            ode.step(&mut rhs, (J + 1) as f64 * h).unwrap();
            while next < samples.len() && (next as f64 - J as f64) * h <= ode.t() {
                let y = ode.dense((next as f64 - J as f64) * h);
                samples[next] = std::array::from_fn(|i| y[i]);
                next += 1;
            }
        }
        // The series from the solution's state at t = 0.
        let mut x = [[0.0; N]; NX];
        for i in 0..NX {
            x[i][0] = samples[J][i];
        }
        taylor::$m::rocking_rhs::<N>(&mut x, &ground_series(), s, &p);
        let difference = |k: usize, i: usize| -> f64 {
            (0..2 * J + 1)
                .map(|j| STENCIL[k - 1][j] * samples[j][i])
                .sum::<f64>()
                / h.powi(k as i32)
        };
        let mut found = Found {
            over_bound: 0.0,
            relative: 0.0,
            tightness: 0.0,
            h,
            omega_max,
        };
        let mut factorial = 1.0;
        for k in 1..=K {
            factorial *= k as f64;
            let largest = (0..NX).fold(0.0f64, |m, i| m.max(difference(k, i).abs()));
            let weights: f64 = STENCIL[k - 1].iter().map(|w| w.abs()).sum();
            for i in 0..NX {
                let fd = difference(k, i);
                let series = factorial * x[i][k];
                let size = samples.iter().fold(0.0f64, |m, y| m.max(y[i].abs()));
                let delta = 100.0 * (ATOL + RTOL * size);
                let bound = 2.0 * TRUNCATION[k - 1] * h * h * difference(k + 2, i).abs()
                    + weights * delta / h.powi(k as i32);
                let err = (series - fd).abs();
                assert!(
                    err <= bound,
                    "{}: derivative {k} of component {i}: series {series:e}, finite difference \
                     {fd:e}, |difference| {err:e} > bound {bound:e} (h = {h:e})",
                    stringify!($m)
                );
                found.over_bound = found.over_bound.max(err / bound);
                found.relative = found.relative.max(err / largest);
                found.tightness = found.tightness.max(bound / largest);
            }
        }
        eprintln!(
            "{}: h = {:.3e} (ω_max = {:.1}): worst |k! c_k − D_k y| / bound = {:.2}, / largest \
             derivative of its order = {:.1e}; bound / largest derivative ≤ {:.1e}",
            stringify!($m),
            found.h,
            found.omega_max,
            found.over_bound,
            found.relative,
            found.tightness
        );
        assert!(
            found.tightness < 1e-2,
            "{}: the bound is {:e} of the derivatives: too loose to test anything",
            stringify!($m),
            found.tightness
        );
        found
    }};
}

#[test]
fn taylor_coefficients_equal_finite_differences_of_dop853_with_two_modes() {
    compare!(CantileverModes2, cantilever_modes2, 2);
}

#[test]
fn taylor_coefficients_equal_finite_differences_of_dop853_with_eight_modes() {
    compare!(CantileverModes8, cantilever_modes8, 8);
}
