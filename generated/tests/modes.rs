//! The models of several deformation coordinates against Euler–Bernoulli: the fixed-base
//! frequencies of the kernels' M and K ([`rocking_kernels::modes`]) are the cantilever's exact
//! frequencies when the basis holds its modes, and bound them from above otherwise, falling
//! towards them as functions are added (Rayleigh–Ritz).

use rocking_kernels::kernels::{
    CantileverModes2, CantileverModes3, Full, Polynomial2, Polynomial3,
};
use rocking_kernels::modes::Matrices;
use rocking_kernels::{Array, Physical, Variant};

/// β_k of the clamped-free cantilever, 1 + cos β cosh β = 0 (the digits).
const BETA: [f64; 3] = [1.8751040687, 4.6940911330, 7.8547574382];

/// A uniform column in SI units: H = 40 m, EI = 2e11 N m², m_c = 3e5 kg, with a top mass `m`
/// (kg) and the paper's base; no damping.
fn column(m: f64) -> Physical {
    Physical {
        h: 40.0,
        b: 4.0,
        ei: 2.0e11,
        m,
        m_c: 3.0e5,
        m_b: 1.0e5,
        i_bc: 1.0e5 * 16.0 * 4.0 / 3.0,
        zeta: 0.0,
        g: 9.81,
    }
}

/// √(EI / (m_c H³)): ω_k = β_k² times this.
fn unit(phys: &Physical) -> f64 {
    (phys.ei / (phys.m_c * phys.h.powi(3))).sqrt()
}

fn fixed_base<V: Variant>(phys: &Physical) -> Vec<f64> {
    Matrices::of::<V>(&V::params(phys))
        .fixed_base()
        .expect("M is positive definite")
        .omega
}

/// The first `n` roots β of 1 + cos β cosh β + r β (cos β sinh β − sin β cosh β) = 0, the
/// cantilever with a tip mass r m_c (r = 0: no tip mass), by bisection on a fine grid; the
/// function is divided by cosh β so that it stays of order one.
fn tip_mass_roots(r: f64, n: usize) -> Vec<f64> {
    let f = |b: f64| 1.0 / b.cosh() + b.cos() + r * b * (b.cos() * b.tanh() - b.sin());
    let mut roots = Vec::new();
    let (mut lo, step) = (1e-3, 1e-3);
    while roots.len() < n {
        let hi = lo + step;
        if f(lo) * f(hi) < 0.0 {
            let (mut a, mut b) = (lo, hi);
            for _ in 0..200 {
                let mid = 0.5 * (a + b);
                if f(a) * f(mid) <= 0.0 {
                    b = mid;
                } else {
                    a = mid;
                }
            }
            roots.push(0.5 * (a + b));
        }
        lo = hi;
    }
    roots
}

#[test]
fn the_bisection_finds_the_clamped_free_roots() {
    for (got, want) in tip_mass_roots(0.0, 3).iter().zip(BETA) {
        assert!((got - want).abs() < 1e-9, "{got} vs {want}");
    }
}

/// Without a top mass the basis of the first cantilever modes is exact: its fixed-base
/// frequencies are β_k² √(EI / (m_c H³)).
#[test]
fn cantilever_modes_give_the_euler_bernoulli_frequencies() {
    let phys = column(0.0);
    let mut worst: f64 = 0.0;
    for omega in [
        fixed_base::<CantileverModes2>(&phys),
        fixed_base::<CantileverModes3>(&phys),
    ] {
        for (k, w) in omega.iter().enumerate() {
            let exact = BETA[k] * BETA[k] * unit(&phys);
            let err = (w - exact).abs() / exact;
            worst = worst.max(err);
            assert!(
                err < 1e-10,
                "mode {}: {w} vs Euler-Bernoulli {exact} ({err:.1e})",
                k + 1
            );
        }
    }
    eprintln!("cantilever modes without top mass: worst relative error {worst:.1e}");
}

/// With a top mass the cantilever modes are not the structure's modes: every basis gives
/// frequencies above the exact ones (Rayleigh–Ritz), and more functions of the same family give
/// lower ones.
#[test]
fn every_basis_bounds_the_tip_mass_frequencies_from_above_and_converges() {
    for ratio in [0.1, 0.5, 2.0] {
        let phys = column(ratio * 3.0e5);
        let exact: Vec<f64> = tip_mass_roots(ratio, 3)
            .iter()
            .map(|b| b * b * unit(&phys))
            .collect();
        let one = fixed_base::<Full>(&phys);
        let (p2, p3) = (
            fixed_base::<Polynomial2>(&phys),
            fixed_base::<Polynomial3>(&phys),
        );
        let (c2, c3) = (
            fixed_base::<CantileverModes2>(&phys),
            fixed_base::<CantileverModes3>(&phys),
        );
        let excess = |w: &[f64]| -> String {
            let v: Vec<String> = w
                .iter()
                .zip(&exact)
                .map(|(w, e)| format!("{:.1e}", w / e - 1.0))
                .collect();
            v.join(" ")
        };
        eprintln!(
            "m/m_c = {ratio}: relative excess over the exact frequencies: cubic [{}], \
             eta^2..3 [{}], eta^2..4 [{}], 2 modes [{}], 3 modes [{}]",
            excess(&one),
            excess(&p2),
            excess(&p3),
            excess(&c2),
            excess(&c3)
        );
        for w in [&one, &p2, &p3, &c2, &c3] {
            for (k, (w, e)) in w.iter().zip(&exact).enumerate() {
                assert!(
                    *w >= e * (1.0 - 1e-12),
                    "m/m_c = {ratio}, mode {}: {w} below the exact {e}",
                    k + 1
                );
            }
        }
        // Adding a function lowers every frequency the smaller basis has (nested Ritz spaces:
        // the cubic is in the span of {eta^2, eta^3}).
        for (fewer, more) in [(&one, &p2), (&p2, &p3), (&c2, &c3)] {
            for (k, (a, b)) in fewer.iter().zip(more.iter()).enumerate() {
                assert!(
                    b <= a,
                    "m/m_c = {ratio}, mode {}: {b} with more functions above {a}",
                    k + 1
                );
            }
        }
    }
}

/// The first uplifted frequency of one function is eq (18): the generic eigenproblem of
/// [`Matrices::uplifted`] reproduces the kernel's closed form, and with several functions the
/// uplifted frequencies are above the fixed-base ones (rocking removes mass: M − c cᵀ/J0 ≤ M).
#[test]
fn uplifted_frequencies_reduce_to_eq_18_and_exceed_the_fixed_base_ones() {
    use rocking_kernels::kernels::full::structure as st;
    let phys = column(1.0e5);
    let p = Full::params(&phys);
    let m = Matrices::of::<Full>(&p);
    let (fixed, up) = (m.fixed_base().unwrap(), m.uplifted().unwrap());
    let s = Full::structure(&p);
    assert!((fixed.omega[0] / s[st::OMEGA_N] - 1.0).abs() < 1e-14);
    assert!((up.omega[0] / s[st::OMEGA_UP] - 1.0).abs() < 1e-14);
    for m in [
        Matrices::of::<Polynomial3>(&Polynomial3::params(&phys)),
        Matrices::of::<CantileverModes3>(&CantileverModes3::params(&phys)),
    ] {
        let (fixed, up) = (m.fixed_base().unwrap(), m.uplifted().unwrap());
        for (f, u) in fixed.omega.iter().zip(&up.omega) {
            assert!(u >= f, "uplifted {u} below fixed-base {f}");
        }
    }
}

/// Damping per mode reaches the kernels: with C from [`with_modal_damping`] and the ratios
/// ζ_k given one per mode, the full-contact right-hand side at u = 0 with the velocity of mode k
/// (no stiffness or ground force acting) has the modal damping force of that mode alone:
/// φ_jᵀ M u'' = −2 ζ_k ω_k φ_kᵀ M φ_k δ_jk. The modal ratios read back from C are the ones given.
fn damping_per_mode<V: Variant>(zeta: &[f64]) {
    let mut phys = column(1.0e5);
    phys.zeta = 0.0;
    let p = rocking_kernels::modes::with_modal_damping::<V>(V::params(&phys), zeta);
    let m = Matrices::of::<V>(&p);
    let modes = m.fixed_base().expect("M is positive definite");
    let c = rocking_kernels::modes::modal_damping::<V>(&p);
    let read = m.fixed_base_damping_ratios(&c).unwrap();
    let n = V::NQ;
    for k in 0..n {
        assert!(
            (read[k] - zeta[k]).abs() <= 1e-12 * zeta[k],
            "{}: mode {k} read back {} for {}",
            V::NAME,
            read[k],
            zeta[k]
        );
        let phi = &modes.shapes[k];
        let xc = V::Xc::from_fn(|i| if i < n { 0.0 } else { phi[i - n] });
        let rhs = V::contact_rhs(&xc, 0.0, &p);
        let accel = nalgebra::DVector::from_fn(n, |i, _| rhs.values()[n + i]);
        let m_accel = &m.mass * accel;
        let generalised = phi.dot(&(&m.mass * phi));
        let want = -2.0 * zeta[k] * modes.omega[k] * generalised;
        for (j, phi_j) in modes.shapes.iter().enumerate() {
            let got = phi_j.dot(&m_accel);
            let expected = if j == k { want } else { 0.0 };
            assert!(
                (got - expected).abs() <= 1e-9 * want.abs(),
                "{}: velocity of mode {k}, force on mode {j}: {got} vs {expected}",
                V::NAME
            );
        }
    }
}

#[test]
fn damping_ratios_given_per_mode_reach_the_kernels() {
    damping_per_mode::<Polynomial2>(&[0.02, 0.07]);
    damping_per_mode::<CantileverModes2>(&[0.01, 0.04]);
    damping_per_mode::<Polynomial3>(&[0.02, 0.05, 0.003]);
    damping_per_mode::<CantileverModes3>(&[0.005, 0.02, 0.08]);
}
