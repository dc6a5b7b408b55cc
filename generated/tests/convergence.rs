//! Ritz convergence of the section forces: with more shape functions the column's deflection
//! under a quasi-static ground acceleration approaches the continuum's, so the base moment from
//! equilibrium (`moment`: the loads of every mass above the section, gravity on the deflected
//! masses included) and the moment of the base curvature (`moment_elastic`: EI Σ ψ_i''(0) u_i / H²)
//! approach each other. One function (the paper's cubic, the static shape of a tip load) cannot
//! follow the distributed column mass's share of the load; η², η³, η⁴ span the continuum's
//! deflection under a tip load and a uniform load, so only P-Δ's small part remains.

use nalgebra::{DMatrix, DVector};
use rocking_kernels::kernels::{
    index::forces_contact as fc, CantileverModes2, CantileverModes3, Full, Polynomial2, Polynomial3,
};
use rocking_kernels::{Array, Layout, Physical, Variant};

/// The ground acceleration held: about a third of what uplifts these structures.
const UG_OVER_G_TAN_ALPHA: f64 = -0.3;

/// |M_b − M_el| / |M_b| at the static deflection in full contact under a constant ground
/// acceleration. With u' = 0 the contact accelerations u'' are affine in u, so n + 1 evaluations
/// of `contact_rhs` give the deflection where they vanish.
fn moment_gap<V: Variant>(phys: &Physical, gravity: bool) -> f64 {
    let ug = UG_OVER_G_TAN_ALPHA * phys.g * phys.b / phys.h;
    let phys = &Physical {
        g: if gravity { phys.g } else { 0.0 },
        ..*phys
    };
    let p = V::params(phys);
    let n = V::NQ;
    let accel = |u: &DVector<f64>| {
        let xc = V::Xc::from_fn(|i| if i < n { u[i] } else { 0.0 });
        let rhs = V::contact_rhs(&xc, ug, &p);
        DVector::from_fn(n, |i, _| rhs.values()[n + i])
    };
    let zero = DVector::zeros(n);
    let r0 = accel(&zero);
    let step = phys.h * 1e-3;
    let a = DMatrix::from_fn(n, n, |i, j| {
        let mut u = zero.clone();
        u[j] = step;
        (accel(&u)[i] - r0[i]) / step
    });
    let u = a
        .lu()
        .solve(&(-&r0))
        .expect("a stiff column has a regular static problem");
    let xc = V::Xc::from_fn(|i| if i < n { u[i] } else { 0.0 });
    let f = V::forces_contact(&xc, ug, &p);
    assert!(
        accel(&u).amax() < 1e-9 * r0.amax().max(1e-300),
        "{}: not static",
        V::NAME
    );
    (f[fc::MOMENT] - f[fc::MOMENT_ELASTIC]).abs() / f[fc::MOMENT].abs()
}

/// The paper's Fig. 5 flexible structure (dimensionless) and the 123 m wind turbine (SI).
fn structures() -> [(&'static str, Physical); 2] {
    let fig5 = Physical::dimensionless(0.1, 5.0, 1.0, 2.0, 1.0, 0.005);
    let turbine = Physical {
        h: 120.0,
        b: 6.0,
        ei: 4.163e11,
        m: 3.0e5,
        m_c: 3.0e5,
        m_b: 6.0e5,
        i_bc: 4.0 / 3.0 * 6.0e5 * 36.0,
        zeta: 0.01,
        g: 9.81,
    };
    [("Fig. 5 flexible", fig5), ("wind turbine", turbine)]
}

/// The gaps of the five models in a structure: cubic; η², η³; η², η³, η⁴; two and three
/// cantilever modes.
fn gaps(phys: &Physical, gravity: bool) -> [f64; 5] {
    [
        moment_gap::<Full>(phys, gravity),
        moment_gap::<Polynomial2>(phys, gravity),
        moment_gap::<Polynomial3>(phys, gravity),
        moment_gap::<CantileverModes2>(phys, gravity),
        moment_gap::<CantileverModes3>(phys, gravity),
    ]
}

/// Without gravity the model has no P-Δ, and the continuum's deflection under a tip load and a
/// uniform load is a quartic: {η², η³, η⁴} gives it exactly (the gap is round-off), and every
/// basis closes the gap as functions are added.
#[test]
fn equilibrium_and_elastic_base_moments_meet_as_functions_are_added() {
    for (name, phys) in structures() {
        let [cubic, p2, p3, c2, c3] = gaps(&phys, false);
        println!(
            "{name}, no gravity: |M_b - M_el|/|M_b|: cubic {cubic:.2e}; eta^2..: 2 {p2:.2e}, \
             3 {p3:.2e}; cantilever modes: 2 {c2:.2e}, 3 {c3:.2e}"
        );
        assert!(
            cubic > 0.05,
            "{name}: the cubic misses the column's load: {cubic:e}"
        );
        assert!(
            p2 < 0.9 * cubic && c2 < 0.9 * cubic,
            "{name}: {p2:e} {c2:e}"
        );
        assert!(p3 < 1e-12, "{name}: the quartic basis is exact: {p3:e}");
        assert!(c3 < 0.6 * c2, "{name}: {c2:e} -> {c3:e}");
    }
}

/// With gravity the equilibrium moment also carries the weights' lever on the deflected column
/// (P-Δ), which the model's strain energy does not: the gaps fall as functions are added, towards
/// that share, about g/(ω_n² H) of the moment.
#[test]
fn with_gravity_the_gap_falls_towards_the_p_delta_share() {
    for (name, phys) in structures() {
        let [cubic, p2, p3, c2, c3] = gaps(&phys, true);
        println!(
            "{name}: |M_b - M_el|/|M_b|: cubic {cubic:.2e}; eta^2..: 2 {p2:.2e}, 3 {p3:.2e}; \
             cantilever modes: 2 {c2:.2e}, 3 {c3:.2e}"
        );
        assert!(cubic > p2 && p2 > p3, "{name}: {cubic:e} {p2:e} {p3:e}");
        assert!(cubic > c2 && c2 > c3, "{name}: {cubic:e} {c2:e} {c3:e}");
        let omega_n = Full::structure_value(&Full::structure(&Full::params(&phys)), "omega_n");
        let p_delta = phys.g / (omega_n * omega_n * phys.h);
        assert!(
            (p3 / p_delta - 1.0).abs() < 0.1,
            "{name}: the quartic basis leaves about the P-Δ share {p_delta:.2e}, not {p3:.2e}"
        );
    }
}
