//! The models of several deformation coordinates against Euler–Bernoulli: the fixed-base
//! frequencies of the kernels' M and K ([`rocking_kernels::modes`]) are the cantilever's exact
//! frequencies when the basis holds its modes, and bound them from above otherwise, falling
//! towards them as functions are added (Rayleigh–Ritz).

use rocking_kernels::kernels::{
    CantileverModes1, CantileverModes2, CantileverModes3, CantileverModes4, CantileverModes5,
    CantileverModes6, CantileverModes7, CantileverModes8, Full, Polynomial2, Polynomial3,
};
use rocking_kernels::modes::Matrices;
use rocking_kernels::{Array, Physical, Variant};

/// β_k of the clamped-free cantilever, 1 + cos β cosh β = 0 (the digits; the higher roots
/// come from [`tip_mass_roots`] and are checked against their asymptote (2k − 1) π / 2).
const BETA: [f64; 3] = [1.8751040687, 4.6940911330, 7.8547574382];

/// The fixed-base frequencies of `cantilever_modes1` .. `cantilever_modes8`, in order.
fn cantilever_bases(phys: &Physical) -> Vec<Vec<f64>> {
    vec![
        fixed_base::<CantileverModes1>(phys),
        fixed_base::<CantileverModes2>(phys),
        fixed_base::<CantileverModes3>(phys),
        fixed_base::<CantileverModes4>(phys),
        fixed_base::<CantileverModes5>(phys),
        fixed_base::<CantileverModes6>(phys),
        fixed_base::<CantileverModes7>(phys),
        fixed_base::<CantileverModes8>(phys),
    ]
}

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
    let roots = tip_mass_roots(0.0, 8);
    for (got, want) in roots.iter().zip(BETA) {
        assert!((got - want).abs() < 1e-9, "{got} vs {want}");
    }
    // The higher roots approach (2k − 1) π / 2 from both sides, within e^-β.
    for (k, got) in roots.iter().enumerate().skip(3) {
        let asymptote = (2 * k + 1) as f64 * std::f64::consts::FRAC_PI_2;
        assert!(
            (got - asymptote).abs() < 2.0 * (-got).exp(),
            "root {}: {got}",
            k + 1
        );
    }
}

/// Without a top mass the first N cantilever modes are exact for N = 1 .. 8: the fixed-base
/// frequencies of `cantilever_modesN` are β_k² √(EI / (m_c H³)), k = 1 .. N, with β_k the
/// roots of 1 + cos β cosh β = 0 (bisection, [`tip_mass_roots`] with r = 0).
#[test]
fn cantilever_modes_1_to_8_give_the_euler_bernoulli_frequencies() {
    let phys = column(0.0);
    let beta = tip_mass_roots(0.0, 8);
    let mut worst: f64 = 0.0;
    for (n, omega) in cantilever_bases(&phys).iter().enumerate() {
        assert_eq!(
            omega.len(),
            n + 1,
            "cantilever_modes{} has {} modes",
            n + 1,
            n + 1
        );
        for (k, w) in omega.iter().enumerate() {
            let exact = beta[k] * beta[k] * unit(&phys);
            let err = (w - exact).abs() / exact;
            worst = worst.max(err);
            assert!(
                err < 1e-10,
                "cantilever_modes{}, mode {}: {w} vs Euler-Bernoulli {exact} ({err:.1e})",
                n + 1,
                k + 1
            );
        }
    }
    eprintln!("cantilever_modes1..8 without top mass: worst relative error {worst:.1e}");
}

/// With a top mass (m/m_c = 0.1, 0.5, 2) the cantilever modes are a Ritz basis: for N = 1 .. 8
/// every frequency of `cantilever_modesN` is above the exact one (the roots of the tip-mass
/// frequency equation), each basis's frequencies are at or below the smaller basis's (nested
/// spaces), and the first frequency's excess falls with N (printed: the rate of convergence).
#[test]
fn cantilever_modes_1_to_8_converge_from_above_with_a_tip_mass() {
    for ratio in [0.1, 0.5, 2.0] {
        let phys = column(ratio * 3.0e5);
        let exact: Vec<f64> = tip_mass_roots(ratio, 8)
            .iter()
            .map(|b| b * b * unit(&phys))
            .collect();
        let bases = cantilever_bases(&phys);
        for (n, omega) in bases.iter().enumerate() {
            for (k, (w, e)) in omega.iter().zip(&exact).enumerate() {
                assert!(
                    *w >= e * (1.0 - 1e-12),
                    "m/m_c = {ratio}, cantilever_modes{}, mode {}: {w} below the exact {e}",
                    n + 1,
                    k + 1
                );
            }
        }
        for (n, pair) in bases.windows(2).enumerate() {
            for (k, (a, b)) in pair[0].iter().zip(&pair[1]).enumerate() {
                assert!(
                    *b <= a * (1.0 + 1e-13),
                    "m/m_c = {ratio}, mode {}: cantilever_modes{} gives {b} above {a} with one \
                     function fewer",
                    k + 1,
                    n + 2
                );
            }
        }
        let first: Vec<f64> = bases.iter().map(|w| w[0] / exact[0] - 1.0).collect();
        eprintln!(
            "m/m_c = {ratio}: first frequency's relative excess, N = 1..8: {}",
            first
                .iter()
                .map(|e| format!("{e:.2e}"))
                .collect::<Vec<_>>()
                .join(" ")
        );
        // The tip mass moves the modes: one cantilever mode is off by more than 1e-4; the
        // excess falls at every N (slowly, about as N^-3: no cantilever mode has the tip mass's
        // shear jump), eight modes by a factor above 50.
        assert!(first[0] > 1e-4, "m/m_c = {ratio}: {first:?}");
        assert!(first[7] < first[0] / 50.0, "m/m_c = {ratio}: {first:?}");
        for pair in first.windows(2) {
            assert!(pair[1] < pair[0], "m/m_c = {ratio}: {first:?}");
        }
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
    damping_per_mode::<CantileverModes8>(&[0.005, 0.01, 0.02, 0.03, 0.04, 0.05, 0.06, 0.08]);
}
