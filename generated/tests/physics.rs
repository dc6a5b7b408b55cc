//! Physics tests of the generated kernels, run on every variant: the mass matrix, mirror symmetry,
//! the energy balance, the frequencies of eqs (18) and (20), exact shape integrals, and agreement
//! between variants where the physics says they must agree.

use rocking_kernels::kernels::{
    AddedMass, CosineShape, Full, MasslessBase, MasslessColumn, PointMass, Rigid, SmallAngle,
};
use rocking_kernels::{OneCoordinate, Physical, Variant};

#[macro_use]
mod common;
use common::{close, state, structure, Rng};

fn mass_matrix_spd_and_consistent<V: OneCoordinate>() {
    let mut rng = Rng(0x5eed_0001);
    for _ in 0..500 {
        let phys = structure(&mut rng);
        let p = V::params(&phys);
        let x = state::<V>(&mut rng, &phys);
        for s in [1.0, -1.0] {
            let [mtt, mtu, muu] = V::mass_matrix(&[x[0], x[1]], s, &p);
            assert!(mtt > 0.0 && muu > 0.0, "{}: diagonal {mtt} {muu}", V::NAME);
            let det = mtt * muu - mtu * mtu;
            assert!(
                det > 1e-9 * mtt * muu,
                "{}: det {det} at {x:?} s={s}",
                V::NAME
            );
            // T = 1/2 q'^T M q' must be the kinetic energy the kernels report.
            let t = V::energy(&x, s, &p)[0];
            let quad = 0.5 * (mtt * x[2] * x[2] + 2.0 * mtu * x[2] * x[3] + muu * x[3] * x[3]);
            assert!(
                close(t, quad, 1e-12, 0.0),
                "{}: T {t} vs 1/2 q'Mq' {quad}",
                V::NAME
            );
        }
    }
}

#[test]
fn mass_matrix_is_symmetric_positive_definite_and_is_the_hessian_of_t() {
    for_each_variant!(mass_matrix_spd_and_consistent);
}

fn neg<const N: usize>(a: [f64; N]) -> [f64; N] {
    a.map(|v| -v)
}

fn mirror<V: OneCoordinate>() {
    let mut rng = Rng(0x5eed_0002);
    for _ in 0..300 {
        let phys = structure(&mut rng);
        let p = V::params(&phys);
        let x = state::<V>(&mut rng, &phys);
        let ug = rng.range(-2.0, 2.0) * phys.g;
        let s = if rng.next() < 0.5 { 1.0 } else { -1.0 };
        let name = V::NAME;
        // (θ, u, s, üg) -> -(θ, u, s, üg) maps solutions onto solutions: bitwise for these kernels.
        assert_eq!(
            V::rocking_rhs(&neg(x), -ug, -s, &p),
            neg(V::rocking_rhs(&x, ug, s, &p)),
            "{name}"
        );
        let xc = [x[1], x[3]];
        assert_eq!(
            V::contact_rhs(&neg(xc), -ug, &p),
            neg(V::contact_rhs(&xc, ug, &p)),
            "{name}"
        );
        assert_eq!(
            V::uplift(&neg(xc), -ug, -s, &p),
            V::uplift(&xc, ug, s, &p),
            "{name}"
        );
        let (e, em) = (V::energy(&x, s, &p), V::energy(&neg(x), -s, &p));
        assert_eq!([em[0], em[1], em[2], -em[3]], e, "{name}");
        let xi = [x[1], x[3], -s * x[2].abs()];
        let (a, b) = (
            V::impact_adjex(&xi, s, &p),
            V::impact_adjex(&neg(xi), -s, &p),
        );
        for k in [0, 2, 3, 6] {
            assert_eq!(a[k], -b[k], "{name} adjex[{k}]");
        }
        for k in [1, 4, 5, 7] {
            assert_eq!(a[k], b[k], "{name} adjex[{k}]");
        }
        let (a, b) = (V::impact_vvel(&xi, s, &p), V::impact_vvel(&neg(xi), -s, &p));
        assert_eq!([a[0], -a[1], -a[2], a[3], a[4]], b, "{name} vvel");
    }
}

#[test]
fn every_variant_is_mirror_symmetric() {
    for_each_variant!(mirror);
}

fn energy_rate<V: OneCoordinate>() {
    let mut rng = Rng(0x5eed_0003);
    for _ in 0..300 {
        let phys = structure(&mut rng);
        let p = V::params(&phys);
        let x = state::<V>(&mut rng, &phys);
        let ug = rng.range(-2.0, 2.0) * phys.g;
        let s = if x[0] >= 0.0 { 1.0 } else { -1.0 };
        let dx = V::rocking_rhs(&x, ug, s, &p);
        let total = |y: &[f64; 4]| {
            let e = V::energy(y, s, &p);
            e[0] + e[1] + e[2]
        };
        // dE/dt along the flow by a central difference (E is smooth), against the power kernel.
        let h = 1e-6 / dx.iter().map(|v| v.abs()).fold(1e-30, f64::max);
        let fwd: [f64; 4] = std::array::from_fn(|i| x[i] + h * dx[i]);
        let bwd: [f64; 4] = std::array::from_fn(|i| x[i] - h * dx[i]);
        let rate = (total(&fwd) - total(&bwd)) / (2.0 * h);
        let [ground, damping] = V::power(&x, ug, s, &p);
        let e = V::energy(&x, s, &p);
        let scale = (e[0].abs() + e[1].abs() + e[2].abs()) / h * 1e-6; // energy per unit step time
        assert!(
            close(rate, ground - damping, 1e-6, scale * 1e-3),
            "{}: dE/dt {rate} vs ground - damping {}",
            V::NAME,
            ground - damping
        );
    }
}

#[test]
fn energy_changes_only_by_ground_work_and_damping() {
    for_each_variant!(energy_rate);
}

/// Eq (18): the uplifted frequency from the paper's closed form.
fn omega_up_eq18(phys: &Physical, omega_n: f64) -> f64 {
    let (m, mc, h, b) = (phys.m, phys.m_c, phys.h, phys.b);
    let j = phys.i_bc + mc * (h * h / 3.0 + b * b) + m * (h * h + b * b);
    let c = (m + 11.0 / 40.0 * mc).powi(2) * h * h / (m + 33.0 / 140.0 * mc);
    omega_n * (j / (j - c)).sqrt()
}

fn frequencies<V: OneCoordinate>() {
    use rocking_kernels::kernels::full::structure as st;
    if V::NAME == "rigid" {
        return; // u is frozen: no column vibration (its `structure` is checked with the full model)
    }
    let mut rng = Rng(0x5eed_0004);
    for _ in 0..200 {
        let phys = structure(&mut rng);
        let p = V::params(&phys);
        let s = V::structure(&p);
        // Fixed base: u'' = -ω_n² u - ... in full contact (the kernel is linear in u).
        let du = 1e-3 * phys.h;
        let w2 = -(V::contact_rhs(&[du, 0.0], 0.0, &p)[1]
            - V::contact_rhs(&[0.0, 0.0], 0.0, &p)[1])
            / du;
        assert!(close(w2.sqrt(), s[st::OMEGA_N], 1e-9, 0.0), "{}", V::NAME);
        // Uplifted: det(K - ω² M) = 0 with K = diag(0, k~) and M at θ = u = 0.
        let [mtt, mtu, muu] = V::mass_matrix(&[0.0, 0.0], 1.0, &p);
        let w_up = (s[st::K_TILDE] * mtt / (mtt * muu - mtu * mtu)).sqrt();
        assert!(close(w_up, s[st::OMEGA_UP], 1e-12, 0.0), "{}", V::NAME);
        if V::MODEL == "cubic" && V::NAME != "added_mass" {
            // Eq (18), with the masses this variant keeps.
            let mut kept = phys;
            if V::NAME.contains("column") || V::NAME == "point_mass" {
                kept.m_c = 0.0;
            }
            if V::NAME.contains("base") || V::NAME == "point_mass" {
                kept.m_b = 0.0;
                kept.i_bc = 0.0;
            }
            let eq18 = omega_up_eq18(&kept, s[st::OMEGA_N]);
            assert!(
                close(s[st::OMEGA_UP], eq18, 1e-12, 0.0),
                "{}: {} vs eq (18) {eq18}",
                V::NAME,
                s[st::OMEGA_UP]
            );
        }
        if V::NAME == "point_mass" {
            let eq20 = s[st::OMEGA_N] * phys.h.hypot(phys.b) / phys.b;
            assert!(close(s[st::OMEGA_UP], eq20, 1e-12, 0.0), "eq (20)");
        }
    }
}

#[test]
fn fixed_base_and_uplifted_frequencies_match_eqs_18_and_20() {
    for_each_variant!(frequencies);
}

#[test]
fn figure_5_models_have_the_uplifted_frequencies_23_08_and_92_32() {
    use rocking_kernels::kernels::full::structure as st;
    for (omega_n, expected) in [(5.0, 23.080), (20.0, 92.322)] {
        let p = Full::params(&Physical::dimensionless(0.1, omega_n, 1.0, 2.0, 1.0, 0.005));
        let w = Full::structure(&p)[st::OMEGA_UP];
        assert!(
            (w - expected).abs() < 6e-4,
            "ω_up/p = {w}, equations.md §4 gives {expected}"
        );
    }
}

#[test]
fn cubic_shape_integrals_are_exact() {
    use rocking_kernels::kernels::full::structure as st;
    for gamma in [0.5, 1.0, 2.0, 7.0] {
        let phys = Physical::dimensionless(0.2, 10.0, gamma, 0.0, 1.0, 0.0);
        let p = Full::params(&phys);
        let s = Full::structure(&p);
        assert!(
            close(s[st::M_TILDE], 1.0 + 33.0 / 140.0 * gamma, 2e-16, 0.0),
            "∫ψ² dm = 33/140 m_c"
        );
        let gt = (1.0 + 3.0 / 8.0 * gamma) / (1.0 + 33.0 / 140.0 * gamma);
        assert!(close(s[st::GAMMA_TILDE], gt, 4e-16, 0.0), "∫ψ dm = 3/8 m_c");
        let mtu = Full::mass_matrix(&[0.0, 0.0], 1.0, &p)[1];
        assert!(
            close(mtu, (1.0 + 11.0 / 40.0 * gamma) * phys.h, 4e-16, 0.0),
            "∫ξψ dm = 11/40 m_c H"
        );
        assert!(
            close(s[st::K_TILDE], 3.0 * phys.ei / phys.h.powi(3), 4e-16, 0.0),
            "k~ = 3EI/H³"
        );
    }
}

#[test]
fn cosine_shape_integrals() {
    use rocking_kernels::kernels::cosine_shape::structure as st;
    use std::f64::consts::PI;
    let phys = Physical::dimensionless(0.2, 10.0, 1.5, 0.0, 1.0, 0.0);
    let s = CosineShape::structure(&CosineShape::params(&phys));
    let m_tilde = 1.0 + 1.5 * (1.5 - 4.0 / PI);
    assert!(close(s[st::M_TILDE], m_tilde, 1e-14, 0.0));
    assert!(close(
        s[st::K_TILDE],
        phys.ei / phys.h.powi(3) * PI.powi(4) / 32.0,
        1e-14,
        0.0
    ));
    assert!(close(
        s[st::GAMMA_TILDE],
        (1.0 + 1.5 * (1.0 - 2.0 / PI)) / m_tilde,
        1e-14,
        0.0
    ));
}

/// Every function of `A` and `B` agrees at random inputs (parameters from the same physics), to
/// `rel` of the outputs' scale; the functions that solve the rocking phase's M q'' = F to `rel`
/// times M's condition: the two variants' expressions round differently, and the solve amplifies
/// that by up to m_tt m_uu / det M (median 8 over the draws, largest 8e6 where the top mass stands
/// almost over the pivot and M is nearly singular).
fn agree<A: OneCoordinate, B: OneCoordinate>(phys_of: impl Fn(&mut Rng) -> Physical, rel: f64) {
    let mut rng = Rng(0x5eed_0005);
    for _ in 0..200 {
        let phys = phys_of(&mut rng);
        let (pa, pb) = (A::params(&phys), B::params(&phys));
        let x = state::<A>(&mut rng, &phys);
        let ug = rng.range(-2.0, 2.0) * phys.g;
        let xc = [x[1], x[3]];
        let xi = [x[1], x[3], x[2]];
        for s in [1.0, -1.0] {
            let [mtt, mtu, muu] = A::mass_matrix(&[x[0], x[1]], s, &pa);
            let solved = rel * (mtt * muu / (mtt * muu - mtu * mtu));
            let pairs: Vec<(Vec<f64>, Vec<f64>, f64)> = vec![
                (
                    A::rocking_rhs(&x, ug, s, &pa).to_vec(),
                    B::rocking_rhs(&x, ug, s, &pb).to_vec(),
                    solved,
                ),
                (
                    A::contact_rhs(&xc, ug, &pa).to_vec(),
                    B::contact_rhs(&xc, ug, &pb).to_vec(),
                    rel,
                ),
                (
                    vec![A::uplift(&xc, ug, s, &pa)],
                    vec![B::uplift(&xc, ug, s, &pb)],
                    rel,
                ),
                (
                    A::energy(&x, s, &pa).to_vec(),
                    B::energy(&x, s, &pb).to_vec(),
                    rel,
                ),
                (
                    A::power(&x, ug, s, &pa).to_vec(),
                    B::power(&x, ug, s, &pb).to_vec(),
                    rel,
                ),
                (
                    A::impact_vvel(&xi, s, &pa).to_vec(),
                    B::impact_vvel(&xi, s, &pb).to_vec(),
                    rel,
                ),
                (
                    A::impact_adjex(&xi, s, &pa).to_vec(),
                    B::impact_adjex(&xi, s, &pb).to_vec(),
                    rel,
                ),
                (
                    A::impact_housner(&xi, s, &pa).to_vec(),
                    B::impact_housner(&xi, s, &pb).to_vec(),
                    rel,
                ),
                (A::structure(&pa).to_vec(), B::structure(&pb).to_vec(), rel),
                (
                    A::forces_contact(&xc, ug, &pa).to_vec(),
                    B::forces_contact(&xc, ug, &pb).to_vec(),
                    rel,
                ),
                (
                    A::forces_rocking(&x, ug, s, &pa).to_vec(),
                    B::forces_rocking(&x, ug, s, &pb).to_vec(),
                    solved,
                ),
                (
                    A::static_uplift(&pa).to_vec(),
                    B::static_uplift(&pb).to_vec(),
                    rel,
                ),
            ];
            for (k, (a, b, rel)) in pairs.iter().enumerate() {
                let scale = a
                    .iter()
                    .chain(b)
                    .map(|v| v.abs())
                    .filter(|v| v.is_finite())
                    .fold(0.0, f64::max);
                for (va, vb) in a.iter().zip(b) {
                    assert!(
                        va == vb || close(*va, *vb, *rel, scale),
                        "{} vs {} (function #{k}): {a:?} vs {b:?}",
                        A::NAME,
                        B::NAME
                    );
                }
            }
        }
    }
}

#[test]
fn specialised_variants_equal_the_full_model_with_those_masses_zero() {
    agree::<Full, MasslessColumn>(
        |r| Physical {
            m_c: 0.0,
            ..structure(r)
        },
        1e-12,
    );
    agree::<Full, MasslessBase>(
        |r| Physical {
            m_b: 0.0,
            i_bc: 0.0,
            ..structure(r)
        },
        1e-12,
    );
    agree::<Full, PointMass>(
        |r| Physical {
            m_c: 0.0,
            m_b: 0.0,
            i_bc: 0.0,
            ..structure(r)
        },
        1e-12,
    );
    // The added-mass example with its default height and m_a = 0 (its default) is the paper's model.
    agree::<Full, AddedMass>(structure, 1e-12);
}

#[test]
fn small_angle_model_agrees_to_second_order_in_theta() {
    let mut rng = Rng(0x5eed_0006);
    for _ in 0..200 {
        let phys = structure(&mut rng);
        let (pf, ps) = (Full::params(&phys), SmallAngle::params(&phys));
        let mut x = state::<Full>(&mut rng, &phys);
        for theta in [0.0, 1e-3, 1e-2] {
            x[0] = theta;
            let (f, s) = (
                Full::rocking_rhs(&x, 0.3, 1.0, &pf),
                SmallAngle::rocking_rhs(&x, 0.3, 1.0, &ps),
            );
            let scale = f.iter().map(|v| v.abs()).fold(0.0, f64::max);
            for k in 0..4 {
                // The difference is O(θ²) relative to the terms (plus rounding).
                assert!(
                    (f[k] - s[k]).abs() <= (theta * theta + 1e-13) * 10.0 * scale,
                    "θ = {theta}: {f:?} vs {s:?}"
                );
            }
        }
    }
}

#[test]
fn rigid_variant_is_the_full_model_with_the_column_frozen() {
    let mut rng = Rng(0x5eed_0007);
    for _ in 0..200 {
        let phys = structure(&mut rng);
        let (pf, pr) = (Full::params(&phys), Rigid::params(&phys));
        let x = [rng.range(-1.5, 1.5), 0.0, rng.range(-2.0, 2.0), 0.0];
        let ug = rng.range(-2.0, 2.0);
        let s = if x[0] >= 0.0 { 1.0 } else { -1.0 };
        // With u frozen the θ row alone governs: θ'' = F_θ / M_θθ at u = u' = 0.
        let f = Full::forcing(&x, ug, s, &pf)[0];
        let m = Full::mass_matrix(&[x[0], 0.0], s, &pf)[0];
        let r = Rigid::rocking_rhs(&x, ug, s, &pr);
        assert!(close(r[2], f / m, 1e-12, 0.0) && r[3] == 0.0);
        assert_eq!(Rigid::energy(&x, s, &pr), Full::energy(&x, s, &pf));
        // Reference quantities come from the flexible twin.
        assert_eq!(Rigid::static_uplift(&pr), Full::static_uplift(&pf));
    }
}

#[test]
fn rigid_block_uplifts_when_the_ground_acceleration_exceeds_g_tan_alpha() {
    let alpha: f64 = 0.2;
    let p = PointMass::params(&Physical::dimensionless(alpha, 1e6, 0.0, 0.0, 1.0, 0.0));
    let pr = Rigid::params(&Physical::dimensionless(alpha, 1e6, 0.0, 0.0, 1.0, 0.0));
    let threshold = alpha.tan(); // g = 1
    for s in [1.0, -1.0] {
        // Uplift about the right corner (s = +1) needs the ground to accelerate to the left.
        let below = -s * threshold * (1.0 - 1e-9);
        let above = -s * threshold * (1.0 + 1e-9);
        assert!(Rigid::uplift(&[0.0, 0.0], below, s, &pr) < 0.0);
        assert!(Rigid::uplift(&[0.0, 0.0], above, s, &pr) > 0.0);
        // The flexible point-mass model at rest needs the same static threshold.
        assert!(PointMass::uplift(&[0.0, 0.0], below, s, &p) < 0.0);
    }
}

#[test]
fn impact_maps_in_the_rigid_state_match_verification_table_3() {
    use rocking_kernels::kernels::full::{impact_adjex as adj, impact_vvel as vv};
    // (γ_mc, γ_mb, α, ADJex θ2'/θ1', VVEL E2/E1), verification.md §3, γ_Ib = 1.
    let table = [
        (0.0, 0.0, 0.1, 0.98007, 0.99003),
        (1.0, 1.0, 0.1, 0.95581, 0.97545),
        (2.0, 2.0, 0.1, 0.94160, 0.96690),
        (0.0, 0.0, 0.2, 0.92106, 0.96053),
        (1.0, 1.0, 0.2, 0.83231, 0.90684),
        (2.0, 2.0, 0.2, 0.78367, 0.87742),
    ];
    for (gmc, gmb, alpha, ratio, energy) in table {
        let p = Full::params(&Physical::dimensionless(alpha, 10.0, gmc, gmb, 1.0, 0.0));
        for s in [1.0, -1.0] {
            let xi = [0.0, 0.0, -s * 0.3];
            let a = Full::impact_adjex(&xi, s, &p);
            assert!((a[adj::THETA_DOT_ROCKING] / xi[2] - ratio).abs() < 6e-6);
            let v = Full::impact_vvel(&xi, s, &p);
            assert!((v[vv::ENERGY_AFTER] / v[vv::ENERGY_BEFORE] - energy).abs() < 6e-6);
        }
    }
    // Rigid limit of VVEL for a point mass: θ2'/θ1' = cos²α (equations.md §4.2).
    let alpha: f64 = 0.2;
    let p = Rigid::params(&Physical::dimensionless(alpha, 10.0, 0.0, 0.0, 1.0, 0.0));
    let v = Rigid::impact_vvel(&[0.0, 0.0, -0.3], 1.0, &p);
    assert!((v[1] / -0.3 - alpha.cos().powi(2)).abs() < 1e-15);
    let h = Rigid::impact_housner(&[0.0, 0.0, -0.3], 1.0, &p);
    assert!(
        (h[0] / -0.3 - (2.0 * alpha).cos()).abs() < 1e-15,
        "Housner e = cos 2α"
    );
}
