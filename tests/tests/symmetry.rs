//! Mirror symmetry (θ, u, s, ü_g) → (−θ, −u, −s, −ü_g): a run under −ü_g gives the mirrored
//! history and the same summary (verification.md §4).

use rocking::{Effects, History, ImpactModel, Options, Phase, Preset, Run, Structure};
use rocking_motion::SinePulse;
use rocking_verification::*;

fn mirrored(p: Phase) -> Phase {
    match p {
        Phase::RockingLeft => Phase::RockingRight,
        Phase::RockingRight => Phase::RockingLeft,
        other => other,
    }
}

fn close(a: f64, b: f64, scale: f64) -> f64 {
    (a - b).abs() / scale
}

/// Runs +A and −A and compares; returns the worst history mismatch (in units of α, u_cr, α p,
/// u_cr ω_n) and the worst summary mismatch.
fn check_mirror(
    s: &Structure,
    effects: &Effects,
    amplitude: f64,
    omega: f64,
    impact: ImpactModel,
    label: &str,
) -> (f64, f64) {
    let opts = Options {
        accuracy: Preset::Accurate.accuracy(),
        impact,
        t_end: 10.0,
        energy: true,
        event_log: true,
        history: History::Grid(0.01),
        ..Options::default()
    };
    let plus: Run = run_checked(s, &SinePulse::new(amplitude, omega), effects, &opts, label);
    let minus: Run = run_checked(s, &SinePulse::new(-amplitude, omega), effects, &opts, label);
    let d = s.derived();
    let (sa, su, sad, sud) = (d.alpha, d.u_cr, d.alpha * d.p, d.u_cr * d.omega_n);
    let lift = s.static_uplift();
    let (w, wb) = (lift.weight, lift.moment);
    assert!(plus.summary.impacts >= 2, "{label}: should rock and impact");
    assert_eq!(
        plus.history.len(),
        minus.history.len(),
        "{label}: history lengths"
    );
    let mut worst_h = 0.0f64;
    for (a, b) in plus.history.iter().zip(&minus.history) {
        assert_eq!(a.t, b.t, "{label}: grids differ");
        assert_eq!(
            a.phase,
            mirrored(b.phase),
            "{label}: phase at τ = {}",
            a.t * d.p
        );
        worst_h = worst_h
            .max(close(a.theta, -b.theta, sa))
            .max(close(a.u, -b.u, su))
            .max(close(a.theta_dot, -b.theta_dot, sad))
            .max(close(a.u_dot, -b.u_dot, sud))
            .max(close(a.ug, -b.ug, 1.0))
            .max((a.e_total - b.e_total).abs() / d.e_ref)
            // The base moment and shear and the horizontal reaction are odd, the vertical even.
            .max(close(a.base_moment, -b.base_moment, wb))
            .max(close(a.base_shear, -b.base_shear, w))
            .max(close(a.elastic_base_moment, -b.elastic_base_moment, wb))
            .max(close(a.horizontal_reaction, -b.horizontal_reaction, w))
            .max(close(a.vertical_reaction, b.vertical_reaction, w));
    }
    let (p, m) = (&plus.summary, &minus.summary);
    assert_eq!(p.impacts, m.impacts);
    assert_eq!(p.solver_stats, m.solver_stats);
    assert_eq!(p.significant_impacts, m.significant_impacts);
    assert_eq!(p.overturned, m.overturned);
    assert_eq!(p.final_phase, mirrored(m.final_phase));
    let t = |x: Option<rocking::Time>| x.map_or(f64::NAN, |t| t.tau);
    let pairs = [
        (p.max_theta_over_alpha, m.max_theta_over_alpha),
        (p.max_u_over_ucr, m.max_u_over_ucr),
        (t(p.first_uplift_time), t(m.first_uplift_time)),
        (t(p.first_impact_time), t(m.first_impact_time)),
        (p.end_time.tau, m.end_time.tau),
        (p.energy.unwrap().last, m.energy.unwrap().last),
        (
            p.energy.unwrap().impact_losses,
            m.energy.unwrap().impact_losses,
        ),
        (p.energy.unwrap().ground_work, m.energy.unwrap().ground_work),
        (p.energy.unwrap().damping, m.energy.unwrap().damping),
        (
            p.forces.unwrap().max_base_moment_over_wb,
            m.forces.unwrap().max_base_moment_over_wb,
        ),
        (
            p.forces.unwrap().max_base_shear_over_w,
            m.forces.unwrap().max_base_shear_over_w,
        ),
        (
            p.forces.unwrap().min_vertical_reaction_over_w,
            m.forces.unwrap().min_vertical_reaction_over_w,
        ),
    ];
    let worst_s = pairs
        .iter()
        .map(|(a, b)| (a - b).abs() / b.abs().max(1e-300))
        .fold(0.0f64, f64::max);
    // events: same times and branches, mirrored rates
    assert_eq!(plus.events.len(), minus.events.len());
    for (a, b) in plus.events.iter().zip(&minus.events) {
        assert_eq!((a.kind, a.branch), (b.kind, b.branch));
        assert_eq!(a.phase_after, mirrored(b.phase_after));
        assert!(close(a.time.tau, b.time.tau, 1.0) <= 1e-10);
        assert!(close(a.theta_dot, -b.theta_dot, sad) <= 1e-10);
    }
    eprintln!(
        "{label} {impact:?}: {} impacts, max θ/α = {:.4}; mirror mismatch: history {worst_h:.2e} (scaled), summary {worst_s:.2e} (relative); solver steps {} vs {}",
        p.impacts, p.max_theta_over_alpha, p.solver_stats.steps, m.solver_stats.steps
    );
    assert!(
        worst_h <= 1e-10,
        "{label}: mirrored history differs by {worst_h}"
    );
    assert!(worst_s <= 1e-10, "{label}: summaries differ by {worst_s}");
    (worst_h, worst_s)
}

#[test]
fn mirror_flexible_full_model() {
    let s = fig5_structure(5.0);
    let a = 3.0 * 0.1f64.tan();
    for impact in [ImpactModel::Vvel, ImpactModel::Adjex] {
        check_mirror(
            &s,
            &Effects::default(),
            a,
            4.0,
            impact,
            "flexible Fig.-5 model",
        );
    }
}

#[test]
fn mirror_fig3_point_mass() {
    let s = fig3_structure();
    for impact in [ImpactModel::Vvel, ImpactModel::Adjex] {
        check_mirror(
            &s,
            &Effects::default(),
            1.30 * 0.2f64.tan(),
            5.1,
            impact,
            "Fig. 3 point mass",
        );
    }
}

#[test]
fn mirror_rigid() {
    let s = fig5_structure(5.0);
    for impact in [ImpactModel::Vvel, ImpactModel::Housner] {
        check_mirror(
            &s,
            &rigid_effects(),
            3.0 * 0.1f64.tan(),
            4.0,
            impact,
            "rigid (Fig.-5 masses)",
        );
    }
}
