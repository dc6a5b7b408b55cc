//! Verification of the rocking solver: closed forms (Housner's rigid block), the paper's own
//! numbers, invariants (energy, mirror symmetry, dimensionless scaling) and hard cases. The
//! checks live in `tests/tests/*.rs`; this library holds the reference formulas they share.

use rocking::{
    simulate, DampingConvention, Dimensionless, Effects, EventKind, EventRecord, Options, Run,
    Structure,
};
use rocking_motion::GroundMotion;

/// The setup of a scene of `scenes/` (e.g. `"fig3-vvel.toml"`) with `--set` overrides, loaded
/// through `rocking-scene` as the `rocking` command loads it: the paper's cases are typed once,
/// in their scene files.
pub fn scene(file: &str, sets: &[&str]) -> rocking_scene::setup::Setup {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../scenes")
        .join(file);
    let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
    let sc = rocking_scene::scene::load(&path, &sets)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    rocking_scene::setup::build(&sc).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// A dimensionless structure of the compliant-ground tests (R = g = m = 1, α = 0.2, γ_mc = 0,
/// γ_ib = 1, damping of the fixed base).
pub fn ground_structure(omega_n_over_p: f64, gamma_mb: f64, zeta: f64) -> Structure {
    let d = Dimensionless {
        omega_n_over_p,
        alpha: 0.2,
        gamma_mc: 0.0,
        gamma_mb,
        gamma_ib: 1.0,
        zeta,
        damping: DampingConvention::FixedBase,
    };
    Structure::from_dimensionless(&d, None).unwrap()
}

/// The ground of `kind` under `s` with ω_v = `ratio` p and damping ratio `zeta_v` (g = 1: the
/// mass is the weight).
pub fn bed(s: &Structure, kind: rocking::GroundKind, ratio: f64, zeta_v: f64) -> rocking::Ground {
    let mass = s.static_uplift().weight;
    let k_v = mass * (ratio * s.derived().p).powi(2);
    let c_v = 2.0 * zeta_v * (k_v * mass).sqrt();
    rocking::Ground::from_vertical(kind, s.param("b").unwrap(), k_v, c_v)
}

/// The frequency of the column mode of the rocking equations linearised about (θ, u) while
/// rocking about `s`, from the variant's own kernels (M(q) and central differences of F at rest
/// velocities and no ground motion): the kernel-based form of [`uplifted_frequency_linearised`]
/// with gravity, for any model.
pub fn uplifted_frequency_kernels<V: rocking_kernels::OneCoordinate>(
    p: &V::Params,
    s: f64,
    theta: f64,
    u: f64,
) -> f64 {
    let [m_tt, m_tu, m_uu] = V::mass_matrix(&[theta, u], s, p);
    let f = |th: f64, uu: f64| V::forcing(&[th, uu, 0.0, 0.0], 0.0, s, p);
    let (ht, hu) = (1e-6 * theta.abs().max(1e-3), 1e-6 * u.abs().max(1e-6));
    let dth = |k: usize| -(f(theta + ht, u)[k] - f(theta - ht, u)[k]) / (2.0 * ht);
    let du = |k: usize| -(f(theta, u + hu)[k] - f(theta, u - hu)[k]) / (2.0 * hu);
    let (k_tt, k_ut, k_tu, k_uu) = (dth(0), dth(1), du(0), du(1));
    let k_off = 0.5 * (k_ut + k_tu);
    let a = m_uu * m_tt - m_tu * m_tu;
    let bq = -(k_uu * m_tt + k_tt * m_uu - 2.0 * k_off * m_tu);
    let c = k_uu * k_tt - k_off * k_off;
    ((-bq + (bq * bq - 4.0 * a * c).sqrt()) / (2.0 * a)).sqrt()
}

/// A structure from the dimensionless groups (R = g = m = 1, time in τ), γ_Ib = 1.
pub fn dimensionless(
    alpha: f64,
    omega_n_over_p: f64,
    gamma_mc: f64,
    gamma_mb: f64,
    zeta: f64,
    damping: DampingConvention,
) -> Structure {
    let d = Dimensionless {
        omega_n_over_p,
        alpha,
        gamma_mc,
        gamma_mb,
        gamma_ib: 1.0,
        zeta,
        damping,
    };
    Structure::from_dimensionless(&d, None).expect("valid dimensionless structure")
}

/// The paper's Fig. 3 structure (point mass, ω_n/p = 11.9, α = 0.2, ζ = 0.005 fixed-base), from
/// `scenes/fig3-vvel.toml`.
pub fn fig3_structure() -> Structure {
    scene("fig3-vvel.toml", &[]).structure
}

/// The paper's Fig. 3 pulse (a_p/(g tan α) = 1.30, ω_p/p = 5.1, α = 0.2), from
/// `scenes/fig3-vvel.toml`.
pub fn fig3_pulse() -> rocking_motion::SinePulse {
    match scene("fig3-vvel.toml", &[]).excitation {
        rocking_motion::Excitation::Sine(p) => p,
        other => panic!("scenes/fig3-vvel.toml: a sine pulse, not {other:?}"),
    }
}

/// The Fig.-5 models (α = 0.1, γ_mc = 1, γ_mb = 2, γ_Ib = 1, ζ = 0.005 fixed-base) at
/// `omega_n_over_p`, from `scenes/fig5-flexible.toml`.
pub fn fig5_structure(omega_n_over_p: f64) -> Structure {
    let set = format!("structure.omega_n_over_p={omega_n_over_p:?}");
    scene("fig5-flexible.toml", &[&set]).structure
}

/// Asserts the sanity every run must have: solver statistics > 0 and no NaN (or infinity)
/// anywhere in the history, the event log or the summary's numbers.
pub fn check_run(run: &Run, label: &str) {
    let s = &run.summary;
    assert!(
        s.solver_stats.steps > 0 && s.solver_stats.rhs_evaluations > 0,
        "{label}: solver statistics are zero: {:?}",
        s.solver_stats
    );
    for (i, r) in run.history.iter().enumerate() {
        let v = [
            r.t,
            r.theta,
            r.u,
            r.theta_dot,
            r.u_dot,
            r.e_kin,
            r.e_total,
            r.ug,
        ];
        assert!(
            v.iter().all(|x| x.is_finite()),
            "{label}: non-finite history row {i}: {r:?}"
        );
    }
    for (i, e) in run.events.iter().enumerate() {
        let v = [
            e.time.tau,
            e.theta_dot,
            e.u,
            e.u_dot,
            e.energy_before,
            e.energy_after,
        ];
        assert!(
            v.iter().all(|x| x.is_finite()),
            "{label}: non-finite event {i}: {e:?}"
        );
    }
    let nums = [
        s.max_theta_over_alpha,
        s.max_theta_over_theta_cr,
        s.max_u_over_ucr,
        s.end_time.tau,
    ];
    assert!(
        nums.iter().all(|x| x.is_finite()),
        "{label}: non-finite summary {s:?}"
    );
    if let Some(r) = s.energy_balance_residual {
        assert!(r.is_finite(), "{label}: non-finite energy residual");
    }
}

/// [`simulate`], unwrapped, followed by [`check_run`].
pub fn run_checked<M: GroundMotion>(
    structure: &Structure,
    motion: &M,
    effects: &Effects,
    options: &Options,
    label: &str,
) -> Run {
    let run = simulate(structure, motion, effects, options)
        .unwrap_or_else(|e| panic!("{label}: simulation failed: {e}"));
    check_run(&run, label);
    run
}

/// The rigid (one-degree-of-freedom) effects.
pub fn rigid_effects() -> Effects {
    Effects {
        flexibility: false,
        ..Effects::default()
    }
}

/// The impacts of a run's event log (kind Impact or Rest: every time θ returned to 0).
pub fn impacts(run: &Run) -> Vec<EventRecord> {
    run.events
        .iter()
        .filter(|e| matches!(e.kind, EventKind::Impact | EventKind::Rest))
        .copied()
        .collect()
}

// ------------------------------------------------------------------------------------------------
// Quadrature

/// Gauss–Legendre nodes and weights on [-1, 1] (Newton on P_n, Golub-free, exact to rounding).
pub fn gauss_legendre(n: usize) -> (Vec<f64>, Vec<f64>) {
    let mut x = vec![0.0; n];
    let mut w = vec![0.0; n];
    for i in 0..n.div_ceil(2) {
        let mut z = (std::f64::consts::PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
        let mut dp = 0.0;
        for _ in 0..100 {
            let (mut p0, mut p1) = (1.0, z);
            for k in 2..=n {
                let p2 = ((2 * k - 1) as f64 * z * p1 - (k - 1) as f64 * p0) / k as f64;
                p0 = p1;
                p1 = p2;
            }
            // p1 = P_n(z), p0 = P_{n-1}(z)
            dp = n as f64 * (z * p1 - p0) / (z * z - 1.0);
            let dz = p1 / dp;
            z -= dz;
            if dz.abs() < 1e-16 {
                break;
            }
        }
        x[i] = -z;
        x[n - 1 - i] = z;
        let wi = 2.0 / ((1.0 - z * z) * dp * dp);
        w[i] = wi;
        w[n - 1 - i] = wi;
    }
    (x, w)
}

/// ∫_a^b f with composite Gauss–Legendre (`panels` panels of `n` points).
pub fn integrate(f: impl Fn(f64) -> f64, a: f64, b: f64, n: usize, panels: usize) -> f64 {
    let (x, w) = gauss_legendre(n);
    let h = (b - a) / panels as f64;
    let mut sum = 0.0;
    for k in 0..panels {
        let (lo, hi) = (a + k as f64 * h, a + (k + 1) as f64 * h);
        let (c, r) = (0.5 * (lo + hi), 0.5 * (hi - lo));
        for (xi, wi) in x.iter().zip(&w) {
            sum += wi * r * f(c + r * xi);
        }
    }
    sum
}

// ------------------------------------------------------------------------------------------------
// Housner's rigid block: point mass on a massless rigid column and base, p = sqrt(g/R) = 1.

/// Exact quarter period (time from rest at θ0 to θ = 0), in τ, of the undamped free rocking of
/// a point mass (θ'' = −sin(α − θ) for θ > 0):
/// T/4 = ∫_0^θ0 dθ / sqrt(2 [cos(α − θ0) − cos(α − θ)]).
/// θ = θ0 (1 − v²) removes the endpoint singularity, and the cosine difference is written as a
/// product of sines so that it has no cancellation near v = 0.
pub fn housner_quarter_period(alpha: f64, theta0: f64) -> f64 {
    let f = |v: f64| {
        if v == 0.0 {
            // limit: 2θ0 v / sqrt(2·2 sin(α − θ0) sin(θ0 v²/2)) → 2θ0 / sqrt(2 θ0 sin(α − θ0))
            return 2.0 * theta0 / (2.0 * theta0 * (alpha - theta0).sin()).sqrt();
        }
        let theta = theta0 * (1.0 - v * v);
        // cos(α − θ0) − cos(α − θ) = 2 sin(α − (θ0 + θ)/2) sin((θ0 − θ)/2)
        let diff = 2.0 * (alpha - 0.5 * (theta0 + theta)).sin() * (0.5 * theta0 * v * v).sin();
        2.0 * theta0 * v / (2.0 * diff).sqrt()
    };
    integrate(f, 0.0, 1.0, 32, 4)
}

/// Linearised free-rocking period p T = 4 arccosh(1/(1 − θ0/α)).
pub fn housner_linear_period(theta0_over_alpha: f64) -> f64 {
    4.0 * (1.0 / (1.0 - theta0_over_alpha)).acosh()
}

/// Impact rate |θ'|/p after falling from rest at θ0: sqrt(2 [cos(α − θ0) − cos α]).
pub fn housner_impact_rate(alpha: f64, theta0: f64) -> f64 {
    // cos(α − θ0) − cos α = 2 sin(α − θ0/2) sin(θ0/2)
    (4.0 * (alpha - 0.5 * theta0).sin() * (0.5 * theta0).sin()).sqrt()
}

/// The next amplitude after an impact with velocity restitution e:
/// cos(α − θ_{n+1}) − cos α = e² [cos(α − θ_n) − cos α].
pub fn housner_next_amplitude(alpha: f64, e: f64, theta: f64) -> f64 {
    let drop = e * e * ((alpha - theta).cos() - alpha.cos());
    alpha - (alpha.cos() + drop).acos()
}

/// Zero crossings (any direction) of samples y(t), by linear interpolation.
pub fn zero_crossings(t: &[f64], y: &[f64]) -> Vec<f64> {
    let mut out = Vec::new();
    for k in 1..t.len() {
        let (y0, y1) = (y[k - 1], y[k]);
        if y0 != 0.0 && y0 * y1 <= 0.0 && y1 != y0 {
            out.push(t[k - 1] + (t[k] - t[k - 1]) * y0 / (y0 - y1));
        }
    }
    out
}

/// Relative difference |a − b| / max(|b|, floor).
pub fn rel(a: f64, b: f64, floor: f64) -> f64 {
    (a - b).abs() / b.abs().max(floor)
}

/// The uplifted (rocking-phase) frequency of the column from the 2×2 linearisation of the
/// rocking equations (equations.md 1.3) about a rocking state with s·u = `u_s`, |θ| = `theta`
/// (θ' and θ'' neglected): det(K − ω² M) = 0, larger root. With `gravity` false the gravity
/// stiffness is dropped, and at u_s = 0 this is eq (18), ω_up = ω_n S.
pub fn uplifted_frequency_linearised(
    ph: &rocking_kernels::Physical,
    u_s: f64,
    theta: f64,
    gravity: bool,
) -> f64 {
    let (m, mc, mb, b, h, g) = (ph.m, ph.m_c, ph.m_b, ph.b, ph.h, ph.g);
    let m_uu = m + 33.0 / 140.0 * mc;
    let m_ut = (m + 11.0 / 40.0 * mc) * h;
    let s1 = m + mc / 2.0;
    let s2 = m + 3.0 / 8.0 * mc;
    let m_tot = m + mc + mb;
    let j0 = ph.i_bc + mc * (b * b + h * h / 3.0) + m * (b * b + h * h);
    let k = 3.0 * ph.ei / (h * h * h);
    let m_tt = j0 + m_uu * u_s * u_s - 2.0 * s2 * b * u_s;
    let gg = if gravity { g } else { 0.0 };
    let k_uu = k;
    let k_ut = -s2 * gg * theta.cos();
    let k_tt = -gg * (m_tot * b * theta.sin() + s1 * h * theta.cos() - s2 * u_s * theta.sin());
    let a = m_uu * m_tt - m_ut * m_ut;
    let bq = -(k_uu * m_tt + k_tt * m_uu - 2.0 * k_ut * m_ut);
    let c = k_uu * k_tt - k_ut * k_ut;
    let w2 = (-bq + (bq * bq - 4.0 * a * c).sqrt()) / (2.0 * a);
    w2.sqrt()
}

/// A history row's forces as the tables write them: [M_b/(W B), V_b/W, M_el/(W B), R_h/W, R_v/W]
/// (the row holds them in the model's units).
pub fn forces_over_weight(s: &Structure, r: &rocking::HistoryRow) -> [f64; 5] {
    let lift = s.static_uplift();
    let (w, wb) = (lift.weight, lift.moment);
    [
        r.base_moment / wb,
        r.base_shear / w,
        r.elastic_base_moment / wb,
        r.horizontal_reaction / w,
        r.vertical_reaction / w,
    ]
}
