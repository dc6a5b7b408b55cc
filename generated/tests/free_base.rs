//! The structure on compliant ground (issue 44, `derive/rocking_derive/free_base.py`), every
//! variant: the free-base mass matrix over q = [θ, v, u] is symmetric positive definite and is
//! the Hessian of the kinetic energy, it does not depend on the leaning corner at θ = 0 (so the
//! switch of s there needs no impact map), the base forces agree with the equations of motion
//! (R_v = −Q_v: Newton's law for the whole body against Lagrange's equation for v), and the
//! energy is conserved along an integration on an undamped bed with no structural damping.

#![allow(clippy::needless_range_loop)] // dense matrices by index, as written in the maths

use rocking_kernels::ground as gk;
use rocking_kernels::kernels::index::static_uplift as su;
use rocking_kernels::{Array, Physical, Variant};

#[macro_use]
mod common;
use common::{state, structure, Rng};

/// Solves A x = b for the SPD A given by its upper triangle row by row; None when a pivot is not
/// positive (relative to A's diagonal).
fn solve(upper: &[f64], b: &[f64]) -> Option<Vec<f64>> {
    let n = b.len();
    let mut a = vec![vec![0.0; n]; n];
    let mut k = 0;
    for i in 0..n {
        for j in i..n {
            a[i][j] = upper[k];
            a[j][i] = upper[k];
            k += 1;
        }
    }
    let mut low = vec![vec![0.0; n]; n];
    let mut d = vec![0.0; n];
    for j in 0..n {
        d[j] = a[j][j] - (0..j).map(|k| low[j][k] * low[j][k] * d[k]).sum::<f64>();
        if d[j].is_nan() || d[j] <= 1e-12 * a[j][j] {
            return None;
        }
        for i in j + 1..n {
            low[i][j] =
                (a[i][j] - (0..j).map(|k| low[i][k] * low[j][k] * d[k]).sum::<f64>()) / d[j];
        }
    }
    let mut x = b.to_vec();
    for i in 0..n {
        for k in 0..i {
            x[i] -= low[i][k] * x[k];
        }
    }
    for i in (0..n).rev() {
        x[i] /= d[i];
        for k in i + 1..n {
            x[i] -= low[k][i] * x[k];
        }
    }
    Some(x)
}

/// `y = [θ, v, u, θ', v', u']` from a rocking state `x = [θ, u, θ', u']` and v, v'.
fn free_state<V: Variant>(x: &V::X, v: f64, v_dot: f64) -> V::Y {
    let (n, x) = (V::Qf::LEN, x.values());
    let nq = V::NQ;
    V::Y::from_fn(|i| match i {
        0 => x[0],
        1 => v,
        i if i < n => x[i - 1],
        i if i == n => x[nq + 1],
        i if i == n + 1 => v_dot,
        i => x[i - n - 2 + nq + 2],
    })
}

fn mass_matrix_and_newton<V: Variant>() {
    let mut rng = Rng(0x5eed_0044);
    let n = V::Qf::LEN;
    for _ in 0..200 {
        let phys = structure(&mut rng);
        let p = V::params(&phys);
        let mut x = state::<V>(&mut rng, &phys);
        if V::SMALL_ANGLE {
            // The small-angle kinematics (sin θ → θ, cos θ → 1 − θ²/2) is not a rotation beyond
            // small angles, and its kinetic energy with the sinking pivot is not a sum of squares
            // there: within ±0.3 rad only.
            x.values_mut()[0] *= 0.2;
        }
        let (v, v_dot) = (rng.range(-0.02, 0.05) * phys.b, rng.range(-1.0, 1.0));
        let y = free_state::<V>(&x, v, v_dot);
        let q = V::Qf::from_fn(|i| y.values()[i]);
        let weight = V::static_uplift(&p).values()[su::WEIGHT];
        for s in [1.0, -1.0] {
            let m = V::free_mass_matrix(&q, s, &p);
            let qd: Vec<f64> = y.values()[n..].to_vec();
            // Positive definite (the rigid column's frozen u row is the identity).
            let Some(x0) = solve(m.values(), &qd) else {
                // Only a structure of point masses on the column axis (no column, no base mass)
                // has no rotational inertia once the base is free to sink: M is singular there,
                // and the solver refuses it (docs/ground.md). Nor is M regular where the column's
                // own mass block (u, u) is singular, as for a basis of two functions carrying one
                // lumped mass (`cargo xtask try-model`'s tank at its default m_t = 0): that
                // structure is singular on any ground, not because the base sinks.
                assert!(
                    point_masses_only::<V>() || column_block_singular(m.values(), n),
                    "{}: M not SPD",
                    V::NAME
                );
                return;
            };
            // T = 1/2 q'^T M q' (the rigid column's u' is 0 in `state`).
            let quad: f64 = 0.5
                * qd.iter()
                    .zip(&solve_back(m.values(), &x0))
                    .map(|(a, b)| a * b)
                    .sum::<f64>();
            let t = V::free_energy(&y, s, &p)[0];
            let mut quad2 = 0.0;
            let mut k = 0;
            for i in 0..n {
                for j in i..n {
                    let f = if i == j { 0.5 } else { 1.0 };
                    quad2 += f * m.values()[k] * qd[i] * qd[j];
                    k += 1;
                }
            }
            let _ = quad;
            assert!(
                (t - quad2).abs() <= 1e-11 * t.abs().max(1e-300),
                "{}: T {t} vs {quad2}",
                V::NAME
            );
            // Newton against Lagrange: with any ground forces Q_θ, Q_v the accelerations of
            // M q'' = F + Q give a body whose vertical force from the ground is −Q_v.
            let ug = rng.range(-2.0, 2.0) * phys.g;
            let (q_theta, q_v) = (
                rng.range(-1.0, 1.0) * weight * phys.b,
                -rng.range(0.0, 2.0) * weight,
            );
            let mut f = V::free_forcing(&y, ug, s, &p).values().to_vec();
            f[0] += q_theta;
            f[1] += q_v;
            let acc = solve(m.values(), &f).unwrap();
            let qdd = V::Qf::from_fn(|i| acc[i]);
            let forces = V::free_forces(&y, &qdd, ug, s, &p);
            let rv = forces[5];
            // The accelerations come from a solve whose entries can reach 1e6 W (stiff columns,
            // ω_n/p up to 1000, large deflections): the error is rounding of that size.
            let size = f.iter().map(|v| v.abs()).fold(weight, f64::max);
            let err = (rv + q_v).abs() / size;
            if !V::SMALL_ANGLE {
                WORST.with(|w| w.set(w.get().max(err)));
            }
            // (A small-angle variant's equations are not Newton's for the exact rotation its
            // forces use: checked for exact rotations only.)
            assert!(
                V::SMALL_ANGLE || err <= 1e-8,
                "{}: R_v {rv} vs -Q_v {} (W {weight}, largest force {size})",
                V::NAME,
                -q_v
            );
        }
        // At θ = 0 the leaning corner does not matter: M and T are the same for s = ±1.
        let mut y0 = y;
        y0.values_mut()[0] = 0.0;
        let q0 = V::Qf::from_fn(|i| y0.values()[i]);
        let (mp, mm) = (
            V::free_mass_matrix(&q0, 1.0, &p),
            V::free_mass_matrix(&q0, -1.0, &p),
        );
        let scale = mp.values().iter().fold(0.0f64, |a, b| a.max(b.abs()));
        for (a, b) in mp.values().iter().zip(mm.values()) {
            assert!(
                (a - b).abs() <= 1e-12 * scale,
                "{}: M(θ=0) depends on s: {a} {b}",
                V::NAME
            );
        }
    }
}

/// Whether the variant has neither a column mass nor a base mass.
/// Whether the block of M over the deformation coordinates u (rows and columns 2.. of
/// q = [θ, v, u]) is singular; `upper` is M's packed upper triangle of order `n`.
fn column_block_singular(upper: &[f64], n: usize) -> bool {
    let mut block = Vec::new();
    let mut k = 0;
    for i in 0..n {
        for _ in i..n {
            if i >= 2 {
                block.push(upper[k]);
            }
            k += 1;
        }
    }
    n > 2 && solve(&block, &vec![0.0; n - 2]).is_none()
}

fn point_masses_only<V: Variant>() -> bool {
    ["m_c", "m_b"].iter().all(|m| V::REMOVED.contains(m))
}

/// A q'' = M x with M's upper triangle (to form q'^T M q' from x = M^-1 q').
fn solve_back(upper: &[f64], x: &[f64]) -> Vec<f64> {
    let n = x.len();
    let mut out = vec![0.0; n];
    let mut k = 0;
    for i in 0..n {
        for j in i..n {
            out[i] += upper[k] * x[j];
            if i != j {
                out[j] += upper[k] * x[i];
            }
            k += 1;
        }
    }
    out
}

thread_local! {
    static WORST: std::cell::Cell<f64> = const { std::cell::Cell::new(0.0) };
}

#[test]
fn free_base_mass_matrix_is_spd_continuous_at_theta_zero_and_newton_agrees() {
    for_each_variant!(mass_matrix_and_newton, any_coordinates);
    println!(
        "worst |R_v + Q_v| / max(W, |F|): {:e}",
        WORST.with(std::cell::Cell::get)
    );
}

/// Energy T + V_g + V_s + V_bed along RK4 steps in full contact on an undamped Winkler bed
/// (ω_v/p = 20), no structural damping, no ground motion: its drift over τ = 0.5.
fn energy_drift<V: Variant>() -> f64 {
    let alpha: f64 = 0.2;
    let phys = Physical::dimensionless_with::<V>(alpha, 8.0, 0.5, 0.5, 1.0, 0.0, &[]);
    let p = V::params(&phys);
    let weight = V::static_uplift(&p).values()[su::WEIGHT];
    let e_ref = {
        let st = V::structure(&p);
        V::structure_value(&st, "e_ref")
    };
    let unit = [phys.b, 1.0, 0.0];
    let k_v_unit = gk::winkler_statics(weight, &unit)[gk::winkler_statics::K_V];
    let mass = weight / phys.g;
    let k = 400.0 * mass / k_v_unit; // ω_v = 20 p, p = 1
    let gp = [phys.b, k, 0.0];
    let v0 = weight / (k_v_unit * k);
    let n = V::Qf::LEN;
    // A small rotation (the base stays in full contact) and a deflection.
    let mut y = V::Y::from_fn(|i| match i {
        0 => 0.2 * v0 / phys.b,
        1 => v0,
        i if i >= 2 && i < n && !V::RIGID => 1e-4 * phys.h / V::NQ as f64,
        _ => 0.0,
    });
    let rhs = |y: &V::Y| -> V::Y {
        let s = if y.values()[0] >= 0.0 { 1.0 } else { -1.0 };
        let q = V::Qf::from_fn(|i| y.values()[i]);
        let m = V::free_mass_matrix(&q, s, &p);
        let v = y.values();
        let g = gk::winkler_full(&[v[0], v[1], v[n], v[n + 1]], 1.0, &gp);
        let mut f = V::free_forcing(y, 0.0, s, &p).values().to_vec();
        f[0] += g[gk::winkler_full::Q_THETA];
        f[1] += g[gk::winkler_full::Q_V];
        let a = solve(m.values(), &f).unwrap();
        V::Y::from_fn(|i| if i < n { v[n + i] } else { a[i - n] })
    };
    let energy = |y: &V::Y| {
        let s = if y.values()[0] >= 0.0 { 1.0 } else { -1.0 };
        let e = V::free_energy(y, s, &p);
        let v = y.values();
        let g = gk::winkler_full(&[v[0], v[1], v[n], v[n + 1]], 1.0, &gp);
        e[0] + e[1] + e[2] + g[gk::winkler_full::STRAIN]
    };
    let e0 = energy(&y);
    let h = 1e-4;
    let mut worst = 0.0f64;
    for _ in 0..5000 {
        let add = |a: &V::Y, b: &V::Y, c: f64| V::Y::from_fn(|i| a.values()[i] + c * b.values()[i]);
        let k1 = rhs(&y);
        let k2 = rhs(&add(&y, &k1, h / 2.0));
        let k3 = rhs(&add(&y, &k2, h / 2.0));
        let k4 = rhs(&add(&y, &k3, h));
        y = V::Y::from_fn(|i| {
            y.values()[i]
                + h / 6.0
                    * (k1.values()[i]
                        + 2.0 * k2.values()[i]
                        + 2.0 * k3.values()[i]
                        + k4.values()[i])
        });
        // Both corners press throughout (the test's premise).
        let v = y.values();
        assert!(v[1] > phys.b * v[0].abs(), "{}: a corner lifted", V::NAME);
        worst = worst.max((energy(&y) - e0).abs() / e_ref);
    }
    worst
}

fn energy_conserved<V: Variant>() {
    assert!(!point_masses_only::<V>());
    let drift = energy_drift::<V>();
    println!("{}: energy drift {drift:e} E_ref", V::NAME);
    assert!(drift < 1e-9, "{}: energy drift {drift:e} E_ref", V::NAME);
}

#[test]
fn energy_is_conserved_on_an_undamped_bed() {
    for name in ["rigid", "full", "massless_base", "cantilever_modes3"] {
        rocking_kernels::with_variant!(name, V, _L => energy_conserved::<V>()).unwrap();
    }
}
