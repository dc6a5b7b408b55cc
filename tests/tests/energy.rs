//! Energy: conservation between impacts in undamped free rocking, and closure of the energy
//! balance E_final + ∫ü_g P_x dt + ∫c u'² dt + Σ losses = E_initial (verification.md §4).

use rocking::{
    Accuracy, DampingConvention, Effects, EventKind, History, ImpactModel, Initial, Method,
    Options, Preset, Run, Structure,
};
use rocking_motion::{NoMotion, SinePulse};
use rocking_verification::*;

/// Max spread of e_total (in E_ref) over the history rows strictly between consecutive impacts,
/// and the number of such intervals with at least two rows.
fn spread_between_impacts(s: &Structure, run: &Run) -> (f64, usize) {
    let d = s.derived();
    let mut cuts: Vec<f64> = impacts(run).iter().map(|e| e.time.tau).collect();
    cuts.insert(0, f64::NEG_INFINITY);
    cuts.push(f64::INFINITY);
    let mut worst = 0.0f64;
    let mut n = 0;
    for w in cuts.windows(2) {
        let rows: Vec<f64> = run
            .history
            .iter()
            .filter(|r| r.t * d.p > w[0] + 1e-9 && r.t * d.p < w[1] - 1e-9)
            .map(|r| r.e_total / d.e_ref)
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
        let (spread, intervals) = spread_between_impacts(&s, &run);
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

/// The reference accuracy, and the Taylor method at the same tolerance.
const METHODS: [Method; 2] = [Method::Dop853, Method::Taylor];

fn forced_balance(s: &Structure, pulse: &SinePulse, label: &str) -> Vec<f64> {
    let mut out = Vec::new();
    for (impact, method) in [ImpactModel::Vvel, ImpactModel::Adjex]
        .into_iter()
        .flat_map(|i| METHODS.map(|m| (i, m)))
    {
        let mut opts = reference(impact, 12.0);
        opts.accuracy.method = method;
        let label = &format!("{label} ({method:?})");
        let run = run_checked(s, pulse, &Effects::default(), &opts, label);
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

/// The largest relative gain of kinetic energy at any impact of a run (0 when none gains).
fn worst_impact_gain(run: &Run) -> f64 {
    impacts(run)
        .iter()
        .map(|e| (e.energy_after - e.energy_before) / e.energy_before.abs().max(1e-300))
        .fold(0.0f64, f64::max)
}

/// The case: r = 1, no excitation, ζ = 0, ω_n/p = 5, α = 0.2, released from θ/α = 0.5.
/// Fixed restitution scales θ' alone, which on a deformable column raised the kinetic energy at
/// impacts until the column overturned (τ ≈ 20 736). With the energy cap no impact gains energy,
/// the capped impacts are counted and logged, and the column cannot overturn.
#[test]
fn elastic_restitution_on_a_flexible_column_creates_no_energy() {
    let s = dimensionless(0.2, 5.0, 0.0, 0.0, 0.0, DampingConvention::FixedBase);
    let opts = Options {
        impact: ImpactModel::Restitution(1.0),
        t_end: 25_000.0,
        energy: true,
        event_log: true,
        initial: Initial {
            theta: 0.5 * 0.2,
            ..Initial::default()
        },
        ..Options::default()
    };
    let run = run_checked(&s, &NoMotion, &Effects::default(), &opts, "r=1 flexible");
    let sm = &run.summary;
    let e = sm.energy.unwrap();
    let gain = worst_impact_gain(&run);
    let capped_logged = run
        .events
        .iter()
        .filter(|e| e.branch.ends_with("energy-capped"))
        .count() as u64;
    eprintln!(
        "r=1, ω_n/p=5: {} impacts, {} capped, worst gain {gain:.3e}, impact losses {:.3e} E_ref, \
         overturned {}, max θ/α {:.4}",
        sm.impacts,
        sm.energy_capped_impacts,
        e.impact_losses,
        sm.overturned,
        sm.max_theta_over_alpha
    );
    assert!(!sm.overturned, "no energy source: it cannot overturn");
    assert!(
        gain <= 1e-8,
        "an impact gained {gain:e} of its kinetic energy"
    );
    assert!(
        e.impact_losses >= -1e-8,
        "impacts created {} E_ref",
        -e.impact_losses
    );
    assert!(
        sm.energy_capped_impacts > 0,
        "the map would gain: capped impacts counted"
    );
    assert_eq!(
        capped_logged, sm.energy_capped_impacts,
        "each capped impact is logged"
    );
}

/// No impact model increases the kinetic energy at any impact, over a grid of flexible and rigid
/// columns (α, ω_n/p, column and base masses) in free rocking and under a pulse, with DOP853 and
/// with the Taylor method.
#[test]
fn no_impact_model_creates_kinetic_energy() {
    let models = [
        ImpactModel::Vvel,
        ImpactModel::Adjex,
        ImpactModel::Housner,
        ImpactModel::Restitution(1.0),
        ImpactModel::Restitution(0.9),
        ImpactModel::Restitution(0.5),
    ];
    let (mut runs, mut n_impacts, mut n_capped) = (0, 0u64, 0u64);
    let mut worst: f64 = 0.0;
    for alpha in [0.1, 0.2, 0.4] {
        for w in [2.0, 5.0, 20.0, f64::INFINITY] {
            for (gmc, gmb) in [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (1.0, 1.0)] {
                let rigid = w.is_infinite();
                let s = dimensionless(
                    alpha,
                    if rigid { 1000.0 } else { w },
                    gmc,
                    gmb,
                    0.0,
                    DampingConvention::FixedBase,
                );
                let fx = if rigid {
                    rigid_effects()
                } else {
                    Effects::default()
                };
                for (impact, method) in models.into_iter().flat_map(|i| METHODS.map(|m| (i, m))) {
                    for pulse in [false, true] {
                        let opts = Options {
                            accuracy: Accuracy {
                                method,
                                ..Options::default().accuracy
                            },
                            impact,
                            t_end: 60.0,
                            event_log: true,
                            initial: Initial {
                                theta: if pulse { 0.0 } else { 0.5 * alpha },
                                ..Initial::default()
                            },
                            ..Options::default()
                        };
                        let label = format!(
                            "α={alpha} ω_n/p={w} γ=({gmc},{gmb}) {impact:?} {method:?} pulse={pulse}"
                        );
                        let run = if pulse {
                            let a = 3.0 * alpha.tan();
                            run_checked(&s, &SinePulse::new(a, 3.0), &fx, &opts, &label)
                        } else {
                            run_checked(&s, &NoMotion, &fx, &opts, &label)
                        };
                        runs += 1;
                        n_impacts += run.summary.impacts;
                        n_capped += run.summary.energy_capped_impacts;
                        let g = worst_impact_gain(&run);
                        assert!(
                            g <= 1e-8,
                            "{label}: an impact gained {g:e} of its kinetic energy"
                        );
                        worst = worst.max(g);
                    }
                }
            }
        }
    }
    eprintln!(
        "{runs} runs, {n_impacts} impacts, {n_capped} capped, worst relative kinetic-energy gain {worst:.3e}"
    );
    assert!(n_impacts > 1000, "the grid exercises impacts: {n_impacts}");
}
