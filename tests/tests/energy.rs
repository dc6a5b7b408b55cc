//! Energy: conservation between impacts in undamped free rocking, and closure of the energy
//! balance E_final + ∫ü_g P_x dt + ∫c u'² dt + Σ losses = E_initial (verification.md §4).

use rocking::{
    DampingConvention, Effects, EventKind, History, ImpactModel, Initial, Options, Preset, Run,
    Structure,
};
use rocking_motion::{NoMotion, SinePulse};
use rocking_verification::*;

/// Max spread of e_total (in E_ref) over the history rows strictly between consecutive impacts,
/// and the number of such intervals with at least two rows.
fn spread_between_impacts(run: &Run) -> (f64, usize) {
    let mut cuts: Vec<f64> = impacts(run).iter().map(|e| e.time.tau).collect();
    cuts.insert(0, f64::NEG_INFINITY);
    cuts.push(f64::INFINITY);
    let mut worst = 0.0f64;
    let mut n = 0;
    for w in cuts.windows(2) {
        let rows: Vec<f64> = run
            .history
            .iter()
            .filter(|r| r.tau > w[0] + 1e-9 && r.tau < w[1] - 1e-9)
            .map(|r| r.e_total)
            .collect();
        if rows.len() < 2 {
            continue;
        }
        n += 1;
        let (lo, hi) = rows
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| {
                (a.min(x), b.max(x))
            });
        worst = worst.max(hi - lo);
    }
    (worst, n)
}

fn reference(impact: ImpactModel, t_end: f64) -> Options {
    Options {
        accuracy: Preset::Reference.accuracy(),
        impact,
        t_end,
        energy: true,
        event_log: true,
        ..Options::default()
    }
}

/// ζ = 0, no excitation, full flexible model (ω_n/p = 10, γ_mc = γ_mb = 1): the total energy is
/// constant between impacts, and the balance closes.
#[test]
fn free_rocking_energy_constant_between_impacts() {
    let s = dimensionless(0.2, 10.0, 1.0, 1.0, 0.0, DampingConvention::FixedBase);
    for impact in [ImpactModel::Vvel, ImpactModel::Adjex] {
        let opts = Options {
            history: History::Grid(0.005),
            initial: Initial {
                theta: 0.5 * 0.2,
                ..Initial::default()
            },
            ..reference(impact, 12.0)
        };
        let run = run_checked(&s, &NoMotion, &Effects::default(), &opts, "free rocking");
        assert_eq!(run.summary.kernel_variant, "full");
        let n_imp = impacts(&run).len();
        let (spread, intervals) = spread_between_impacts(&run);
        let res = run.summary.energy_balance_residual.unwrap();
        let e = run.summary.energy.unwrap();
        eprintln!(
            "free rocking {impact:?}: {n_imp} impacts, {intervals} inter-impact intervals, max spread of e_total = {spread:.2e} E_ref; \
             E0 = {:.6}, E_end = {:.6}, losses = {:.6}, damping = {:.1e}, ground work = {:.1e}, residual = {res:.2e} E_ref; {} steps",
            e.initial, e.last, e.impact_losses, e.damping, e.ground_work, run.summary.solver_stats.steps
        );
        assert!(n_imp >= 3 && intervals >= 3);
        assert!(
            spread <= 1e-9,
            "energy drifts by {spread} E_ref between impacts"
        );
        assert!(res.abs() <= 1e-9, "balance residual {res}");
        assert_eq!(e.damping, 0.0);
        assert_eq!(e.ground_work, 0.0);
        // impacts dissipate: losses > 0 and the final energy is below the initial one
        assert!(e.impact_losses > 0.0 && e.last < e.initial);
        for ev in run.events.iter().filter(|e| e.kind == EventKind::Impact) {
            assert!(
                ev.energy_after <= ev.energy_before * (1.0 + 1e-12),
                "impact gains energy: {ev:?}"
            );
        }
    }
}

fn forced_balance(s: &Structure, pulse: &SinePulse, label: &str) -> Vec<f64> {
    let mut out = Vec::new();
    for impact in [ImpactModel::Vvel, ImpactModel::Adjex] {
        let run = run_checked(
            s,
            pulse,
            &Effects::default(),
            &reference(impact, 12.0),
            label,
        );
        let res = run.summary.energy_balance_residual.unwrap();
        let e = run.summary.energy.unwrap();
        eprintln!(
            "{label} {impact:?}: {} impacts, max θ/α = {:.4}, E_end = {:.6}, ground work = {:.6}, damping = {:.6}, losses = {:.6}, residual = {res:.2e} E_ref",
            run.summary.impacts, run.summary.max_theta_over_alpha, e.last, e.ground_work, e.damping, e.impact_losses
        );
        assert!(
            run.summary.impacts >= 2,
            "{label}: the pulse should make it rock"
        );
        assert!(!run.summary.overturned);
        assert!(e.ground_work.abs() > 1e-3 && e.damping > 0.0 && e.impact_losses > 0.0);
        assert!(
            res.abs() <= 1e-8,
            "{label} {impact:?}: balance residual {res}"
        );
        out.push(res);
    }
    out
}

/// The balance closes at reference accuracy in the paper's Fig. 3 case.
#[test]
fn fig3_energy_balance_closes() {
    forced_balance(&fig3_structure(), &fig3_pulse(), "Fig. 3");
}

/// The balance closes for the Fig.-5 flexible model (γ_mc = 1, γ_mb = 2, α = 0.1, ω_n/p = 5)
/// under a rocking sine pulse (a_p/(g tan α) = 3, ω_p/p = 4).
#[test]
fn fig5_model_energy_balance_closes() {
    let s = fig5_structure(5.0);
    forced_balance(&s, &SinePulse::new(3.0 * 0.1f64.tan(), 4.0), "Fig.-5 model");
}

/// The energy integrals are carried only when asked for, and outside the error control: the
/// steps and the answer are the same with and without them (to rounding: the error norm sums
/// 4 or 6 components in a different order).
#[test]
fn energy_bookkeeping_does_not_change_the_run() {
    use rocking::{simulate, DampingConvention, Dimensionless, Effects, Options, Structure};
    use rocking_motion::SinePulse;
    let d = Dimensionless {
        omega_n_over_p: 5.0,
        alpha: 0.1,
        gamma_mc: 1.0,
        gamma_mb: 2.0,
        gamma_ib: 1.0,
        zeta: 0.005,
        damping: DampingConvention::FixedBase,
    };
    let s = Structure::from_dimensionless(&d, None).unwrap();
    let pulse = SinePulse::new(3.0 * 0.1f64.tan(), 4.0);
    let run = |energy: bool| {
        let o = Options {
            t_end: 20.0,
            energy,
            ..Options::default()
        };
        simulate(&s, &pulse, &Effects::default(), &o)
            .unwrap()
            .summary
    };
    let (with, without) = (run(true), run(false));
    assert!(with.energy_balance_residual.is_some() && without.energy_balance_residual.is_none());
    let close = |a: f64, b: f64| (a - b).abs() <= 1e-12 * a.abs().max(b.abs());
    assert!(close(
        with.max_theta_over_alpha,
        without.max_theta_over_alpha
    ));
    assert!(close(with.max_u_over_ucr, without.max_u_over_ucr));
    assert_eq!(with.impacts, without.impacts);
    assert_eq!(with.solver_stats.steps, without.solver_stats.steps);
    assert!(close(with.end_time.tau, without.end_time.tau));
}
