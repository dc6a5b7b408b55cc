//! The rigid limit against Housner's exact rigid block (verification.md §2), and the
//! flexible model at ω_n/p = 1000 against the rigid variant (equations.md §4.2).

use rocking::{DampingConvention, Effects, EventKind, ImpactModel, Initial, Options, Preset};
use rocking_motion::NoMotion;
use rocking_verification::*;

const ALPHA: f64 = 0.2;

fn free_rocking(impact: ImpactModel, t_end: f64) -> Options {
    Options {
        accuracy: Preset::Reference.accuracy(),
        impact,
        t_end,
        event_log: true,
        initial: Initial {
            theta: 0.5 * ALPHA,
            ..Initial::default()
        },
        ..Options::default()
    }
}

fn point_mass(omega_n_over_p: f64, zeta_up: f64) -> rocking::Structure {
    dimensionless(
        ALPHA,
        omega_n_over_p,
        0.0,
        0.0,
        zeta_up,
        DampingConvention::Uplifted,
    )
}

/// The quadrature of the exact period reproduces verification.md's table (α = 0.2), and the
/// linearised formula its table.
#[test]
fn period_integral_matches_table() {
    let exact = [
        (0.1, 1.873831),
        (0.25, 3.188153),
        (0.5, 5.274018),
        (0.75, 8.258268),
        (0.9, 11.976509),
    ];
    let linear = [1.868581, 3.181462, 5.267832, 8.253748, 11.972891];
    for ((r, t_exact), t_lin) in exact.iter().zip(linear) {
        let t = 4.0 * housner_quarter_period(ALPHA, r * ALPHA);
        let tl = housner_linear_period(*r);
        eprintln!(
            "θ0/α = {r}: exact pT = {t:.9} (table {t_exact}), linearised {tl:.6} (table {t_lin}), exact/linear − 1 = {:.3e}",
            t / tl - 1.0
        );
        assert!(
            (t - t_exact).abs() < 1.5e-6,
            "exact period {t} vs {t_exact}"
        );
        assert!((tl - t_lin).abs() < 1.5e-6, "linear period {tl} vs {t_lin}");
        // the nonlinear period is slightly longer than the linearised one, by < 0.3 %
        assert!(t > tl && t / tl - 1.0 < 3e-3);
    }
    // quadrature convergence: 32x4 against 48x8 points
    let a = housner_quarter_period(ALPHA, 0.5 * ALPHA);
    let b = integrate(
        |v: f64| {
            let th0 = 0.5 * ALPHA;
            let th = th0 * (1.0 - v * v);
            let diff = 2.0 * (ALPHA - 0.5 * (th0 + th)).sin() * (0.5 * th0 * v * v).sin();
            2.0 * th0 * v / (2.0 * diff).sqrt()
        },
        0.0,
        1.0,
        48,
        8,
    );
    eprintln!(
        "quarter period at θ0/α = 0.5: {a:.15} (finer quadrature differs by {:.1e})",
        (a - b).abs()
    );
    assert!((a - b).abs() < 1e-13);
}

/// The amplitude sequence of verification.md §2 from the exact energy relation.
#[test]
fn amplitude_sequence_matches_table() {
    let e = (2.0 * ALPHA).cos();
    let table = [0.39710, 0.32188, 0.26404, 0.21830, 0.18148];
    let mut th = 0.5 * ALPHA;
    for want in table {
        th = housner_next_amplitude(ALPHA, e, th);
        eprintln!("θ_n/α = {:.6} (table {want})", th / ALPHA);
        assert!((th / ALPHA - want).abs() < 6e-6);
    }
}

/// Rigid variant (point mass, α = 0.2), free rocking from θ0/α = 0.5 with Housner's rule:
/// impact times, impact rates and energy ratios against the exact formulas.
#[test]
fn rigid_housner_free_rocking_exact() {
    let s = point_mass(1e3, 0.0);
    let run = run_checked(
        &s,
        &NoMotion,
        &rigid_effects(),
        &free_rocking(ImpactModel::Housner, 22.0),
        "rigid housner",
    );
    assert_eq!(run.summary.kernel_variant, "rigid");
    let imp = impacts(&run);
    let e = (2.0 * ALPHA).cos();
    // exact sequence
    let mut theta_n = 0.5 * ALPHA;
    let mut t_pred = housner_quarter_period(ALPHA, theta_n);
    let mut sign = -1.0; // rocking right from θ0 > 0: θ' < 0 at the first impact
    let n_check = 6;
    assert!(imp.len() >= n_check, "only {} impacts", imp.len());
    let (mut worst_t, mut worst_v, mut worst_e) = (0.0f64, 0.0f64, 0.0f64);
    for (k, ev) in imp.iter().take(n_check).enumerate() {
        let v_pred = sign * housner_impact_rate(ALPHA, theta_n);
        let (et, ev_) = (
            rel(ev.time.tau, t_pred, 1.0),
            rel(ev.theta_dot, v_pred, 1e-300),
        );
        let er = rel(ev.energy_after / ev.energy_before, e * e, 1.0);
        eprintln!(
            "impact {k}: τ = {:.12} (exact {:.12}, rel err {et:.2e}); θ' = {:.12} (exact {:.12}, rel err {ev_:.2e}); E2/E1 − e² = {er:.2e}; branch {}",
            ev.time.tau, t_pred, ev.theta_dot, v_pred, ev.branch
        );
        assert_eq!(ev.kind, EventKind::Impact);
        assert_eq!(ev.branch, "housner");
        worst_t = worst_t.max(et);
        worst_v = worst_v.max(ev_);
        worst_e = worst_e.max(er);
        theta_n = housner_next_amplitude(ALPHA, e, theta_n);
        t_pred += 2.0 * housner_quarter_period(ALPHA, theta_n);
        sign = -sign;
    }
    eprintln!(
        "rigid Housner, {n_check} impacts: max rel err time {worst_t:.2e}, rate {worst_v:.2e}, energy ratio {worst_e:.2e}"
    );
    assert!(worst_t <= 1e-6, "impact time error {worst_t}");
    assert!(worst_v <= 1e-6, "impact rate error {worst_v}");
    assert!(worst_e <= 1e-9, "energy ratio error {worst_e}");
    // the largest amplitude is the initial one
    assert!((run.summary.max_theta_over_alpha - 0.5).abs() < 1e-12);
}

/// The rigid variant with VVEL: post-impact rate is exactly cos² α times the pre-impact rate
/// (effective restitution of a point mass), and successive impact rates keep that ratio.
#[test]
fn rigid_vvel_restitution_is_cos2_alpha() {
    let s = point_mass(1e3, 0.0);
    let run = run_checked(
        &s,
        &NoMotion,
        &rigid_effects(),
        &free_rocking(ImpactModel::Vvel, 20.0),
        "rigid vvel",
    );
    let imp = impacts(&run);
    assert!(imp.len() >= 5);
    let want = ALPHA.cos().powi(2);
    let mut worst = 0.0f64;
    for k in 1..5 {
        let r = imp[k].theta_dot.abs() / imp[k - 1].theta_dot.abs();
        eprintln!(
            "rigid VVEL: |θ'_{k}|/|θ'_{}| = {r:.12} (cos²α = {want:.12}), branch {}",
            k - 1,
            imp[k - 1].branch
        );
        worst = worst.max((r - want).abs());
        // the map itself keeps cos² α of the energy (rigid point mass: energy ∝ θ'^2, θ'2/θ'1 = cos² α → cos⁴ α)
        let er = imp[k - 1].energy_after / imp[k - 1].energy_before;
        assert!(
            (er - want * want).abs() < 1e-9,
            "energy ratio {er} vs cos⁴α {}",
            want * want
        );
    }
    eprintln!("rigid VVEL restitution: max |ratio − cos²α| = {worst:.2e}");
    assert!(worst < 1e-8);
}

/// The full point-mass model at ω_n/p = 1000 with Housner's rule matches the rigid variant's
/// first impact (time and rate) to ~1e-3.
#[test]
fn stiff_flexible_housner_matches_rigid() {
    let s = point_mass(1000.0, 0.05);
    let opts = free_rocking(ImpactModel::Housner, 3.0);
    let flex = run_checked(
        &s,
        &NoMotion,
        &Effects::default(),
        &opts,
        "stiff flexible housner",
    );
    let rigid = run_checked(&s, &NoMotion, &rigid_effects(), &opts, "rigid housner");
    assert_eq!(flex.summary.kernel_variant, "point_mass");
    let (fi, ri) = (impacts(&flex), impacts(&rigid));
    let exact = housner_quarter_period(ALPHA, 0.5 * ALPHA);
    let (tf, tr) = (fi[0].time.tau, ri[0].time.tau);
    let (vf, vr) = (fi[0].theta_dot, ri[0].theta_dot);
    eprintln!(
        "ω_n/p = 1000, Housner: first impact τ flexible {tf:.9}, rigid {tr:.9}, exact {exact:.9}: rel diff {:.2e}; rate flexible {vf:.9}, rigid {vr:.9}: rel diff {:.2e}; flexible steps {}",
        rel(tf, tr, 1.0), rel(vf, vr, 1e-300), flex.summary.solver_stats.steps
    );
    assert!(rel(tf, tr, 1.0) < 1e-3);
    assert!(rel(vf, vr, 1e-300) < 1e-3);
    assert!(rel(tr, exact, 1.0) < 1e-6);
}

/// The full point-mass model at ω_n/p = 1000 with VVEL and uplifted ζ = 0.05: the effective
/// rocking restitution (ratio of successive impact rates) is cos² α = 0.96053 within ~1e-3.
#[test]
fn stiff_flexible_vvel_restitution_is_cos2_alpha() {
    let s = point_mass(1000.0, 0.05);
    let run = run_checked(
        &s,
        &NoMotion,
        &Effects::default(),
        &free_rocking(ImpactModel::Vvel, 10.0),
        "stiff flexible vvel",
    );
    let imp: Vec<_> = impacts(&run);
    assert!(imp.len() >= 4, "only {} impacts", imp.len());
    let want = ALPHA.cos().powi(2);
    let mut worst = 0.0f64;
    for k in 1..imp.len().min(5) {
        let r = imp[k].theta_dot.abs() / imp[k - 1].theta_dot.abs();
        eprintln!(
            "ω_n/p = 1000 VVEL: impact {k} at τ = {:.6}, |θ'_{k}|/|θ'_{}| = {r:.6} (cos²α = {want:.6}, diff {:.2e}), branch {}",
            imp[k].time.tau, k - 1, r - want, imp[k - 1].branch
        );
        worst = worst.max((r - want).abs());
    }
    eprintln!(
        "ω_n/p = 1000 VVEL: max |restitution − cos²α| = {worst:.2e}, steps {}",
        run.summary.solver_stats.steps
    );
    // the brief asks ~1e-3; the finite-stiffness error measured is a few 1e-6
    assert!(worst < 1e-4, "effective restitution off cos²α by {worst}");
}
