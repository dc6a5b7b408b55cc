//! Every configuration of the suite reports solver statistics > 0 and no NaN in its history or
//! event log. (Every run in the other files also goes through `run_checked`, which asserts the
//! same.) Here each configuration is run once more with a per-step history at default accuracy.

use rocking::{DampingConvention, Effects, History, ImpactModel, Initial, Options, Run};
use rocking_motion::{NoMotion, SinePulse};
use rocking_verification::*;

fn opts(impact: ImpactModel, theta0: f64) -> Options {
    Options {
        impact,
        t_end: 10.0,
        energy: true,
        event_log: true,
        history: History::Steps,
        initial: Initial {
            theta: theta0,
            ..Initial::default()
        },
        ..Options::default()
    }
}

/// name, structure, pulse (None: free rocking), effects, impact model, θ0.
type Case<'a> = (
    &'a str,
    &'a rocking::Structure,
    Option<SinePulse>,
    Effects,
    ImpactModel,
    f64,
);

fn all_runs() -> Vec<(String, Run)> {
    let mut out = Vec::new();
    let fig3 = fig3_structure();
    let fig5 = fig5_structure(5.0);
    let fig5_20 = fig5_structure(20.0);
    let free_full = dimensionless(0.2, 10.0, 1.0, 1.0, 0.0, DampingConvention::FixedBase);
    let stiff = dimensionless(0.2, 1000.0, 0.0, 0.0, 0.05, DampingConvention::Uplifted);
    let pm01 = dimensionless(0.1, 5.0, 0.0, 0.0, 0.005, DampingConvention::FixedBase);
    let pulse5 = SinePulse::new(3.0 * 0.1f64.tan(), 4.0);
    let flex = Effects::default();
    let rigid = rigid_effects();
    let cases: Vec<Case> = vec![
        (
            "Fig. 3 VVEL",
            &fig3,
            Some(fig3_pulse()),
            flex,
            ImpactModel::Vvel,
            0.0,
        ),
        (
            "Fig. 3 ADJex",
            &fig3,
            Some(fig3_pulse()),
            flex,
            ImpactModel::Adjex,
            0.0,
        ),
        (
            "Fig.-5 model VVEL",
            &fig5,
            Some(pulse5),
            flex,
            ImpactModel::Vvel,
            0.0,
        ),
        (
            "Fig.-5 model ADJex",
            &fig5,
            Some(pulse5),
            flex,
            ImpactModel::Adjex,
            0.0,
        ),
        (
            "Fig.-5 model rigid Housner",
            &fig5,
            Some(pulse5),
            rigid,
            ImpactModel::Housner,
            0.0,
        ),
        (
            "free full ζ = 0",
            &free_full,
            None,
            flex,
            ImpactModel::Vvel,
            0.1,
        ),
        (
            "stiff point mass Housner",
            &stiff,
            None,
            flex,
            ImpactModel::Housner,
            0.1,
        ),
        (
            "stiff point mass VVEL",
            &stiff,
            None,
            flex,
            ImpactModel::Vvel,
            0.1,
        ),
        (
            "rigid point mass Housner",
            &stiff,
            None,
            rigid,
            ImpactModel::Housner,
            0.1,
        ),
        (
            "rigid point mass VVEL",
            &stiff,
            None,
            rigid,
            ImpactModel::Vvel,
            0.1,
        ),
        (
            "Fig.-5 ω_n/p = 20 free",
            &fig5_20,
            None,
            flex,
            ImpactModel::Vvel,
            0.09,
        ),
        (
            "point mass α = 0.1 free",
            &pm01,
            None,
            flex,
            ImpactModel::Vvel,
            0.09,
        ),
    ];
    for (name, s, pulse, eff, impact, th0) in cases {
        let o = opts(impact, th0);
        let run = match pulse {
            Some(p) => run_checked(s, &p, &eff, &o, name),
            None => run_checked(s, &NoMotion, &eff, &o, name),
        };
        out.push((name.to_string(), run));
    }
    out
}

#[test]
fn every_configuration_has_stats_and_no_nan() {
    for (name, run) in all_runs() {
        let st = run.summary.solver_stats;
        eprintln!(
            "{name}: variant {}, {} steps ({} rejected), {} RHS evaluations, {} events, {} history rows, {} impacts, residual {:.1e}",
            run.summary.kernel_variant, st.steps, st.rejected_steps, st.rhs_evaluations, st.events,
            run.history.len(), run.summary.impacts, run.summary.energy_balance_residual.unwrap()
        );
        assert!(
            st.steps > 0 && st.rhs_evaluations > 0 && st.events > 0,
            "{name}: {st:?}"
        );
        assert!(!run.history.is_empty());
        assert!(run.summary.impacts > 0, "{name}: expected impacts");
        // default accuracy (1e-7): the balance still closes to well below the tolerance scale
        assert!(
            run.summary.energy_balance_residual.unwrap().abs() < 1e-5,
            "{name}"
        );
    }
}

/// The checker itself catches a NaN.
#[test]
#[should_panic(expected = "non-finite history row")]
fn check_run_catches_nan() {
    let s = fig3_structure();
    let mut run = run_checked(
        &s,
        &fig3_pulse(),
        &Effects::default(),
        &opts(ImpactModel::Vvel, 0.0),
        "nan",
    );
    run.history[3].u = f64::NAN;
    check_run(&run, "nan");
}

/// The library validates the options it is given (item 15 of issue 11): an overturning angle of
/// NaN, 0, −1 or ∞, a restitution of 2 or −1, a start beyond π/2 and a history grid of 0 or −0.1
/// used to run to nonsense (θ/α = 159) or without end; so would a grid too fine or a step
/// history too long for the row bound, an infinite t_end or no steps; each is an error naming the
/// field.
#[test]
fn invalid_options_are_errors_naming_the_field() {
    use rocking::{simulate, History, ImpactModel, Initial, Options, SimError};
    let s = fig3_structure();
    let ok = Options::default();
    let theta = |t: f64| Initial {
        theta: t,
        ..Initial::default()
    };
    let cases: Vec<(Options, &str)> = vec![
        (
            Options {
                overturn_angle: f64::NAN,
                ..ok
            },
            "overturn_angle",
        ),
        (
            Options {
                overturn_angle: 0.0,
                ..ok
            },
            "overturn_angle",
        ),
        (
            Options {
                overturn_angle: -1.0,
                ..ok
            },
            "overturn_angle",
        ),
        (
            Options {
                overturn_angle: f64::INFINITY,
                ..ok
            },
            "overturn_angle",
        ),
        (
            Options {
                impact: ImpactModel::Restitution(2.0),
                ..ok
            },
            "restitution",
        ),
        (
            Options {
                impact: ImpactModel::Restitution(-1.0),
                ..ok
            },
            "restitution",
        ),
        (
            Options {
                initial: theta(1.6),
                ..ok
            },
            "initial.theta",
        ),
        (
            Options {
                history: History::Grid(0.0),
                ..ok
            },
            "history",
        ),
        (
            Options {
                history: History::Grid(-0.1),
                ..ok
            },
            "history",
        ),
        (
            Options {
                history: History::Grid(1e-9),
                ..ok
            },
            "history",
        ),
        (
            Options {
                history: History::Steps,
                max_steps: 1_000_000_000,
                ..ok
            },
            "max_steps",
        ),
        (
            Options {
                t_end: f64::INFINITY,
                ..ok
            },
            "t_end",
        ),
        (Options { max_steps: 0, ..ok }, "max_steps"),
    ];
    assert_eq!(ok.validate(), Ok(()));
    for (o, field) in cases {
        match simulate(&s, &fig3_pulse(), &rocking::Effects::default(), &o) {
            Err(SimError::InvalidOption(e)) => assert!(e.field.contains(field), "{field}: {e}"),
            Err(e) => panic!("{field}: not an options error: {e}"),
            Ok(r) => panic!(
                "{field}: ran (max θ/α = {})",
                r.summary.max_theta_over_alpha
            ),
        }
    }
}

/// A sweep cell skips the tracking of max |u| (`Options::max_deflection`, off unless a sweep
/// reports it): what a cell keeps, the class's inputs (overturned, impacts, the first uplift),
/// max θ/α, the impacts and the force extremes, is the same bit for bit with and without it, by
/// the Taylor method and by DOP853, on cells that stay in contact, rock and overturn; the
/// skipped max |u| is NaN (which a summary leaves out), never a number that looks measured.
#[test]
fn skipping_max_deflection_changes_nothing_a_sweep_cell_keeps() {
    let s = fig5_structure(5.0);
    let ta = 0.1f64.tan();
    let (mut rocked, mut overturned, mut stayed) = (0, 0, 0);
    for method in [rocking::Method::Taylor, rocking::Method::Dop853] {
        for &(wp, a) in &[
            (4.0, 0.5),
            (4.0, 3.0),
            (2.0, 3.0),
            (6.0, 6.0),
            (1.5, 8.0),
            (9.0, 2.0),
        ] {
            let pulse = SinePulse::new(a * ta, wp);
            let mut on = Options {
                t_end: 2.0 * std::f64::consts::PI / wp + 20.0,
                ..Options::default()
            };
            on.accuracy.method = method;
            let off = Options {
                max_deflection: false,
                ..on
            };
            let label = format!("{method:?}, ω_p/p = {wp}, a_p/(g tan α) = {a}");
            let run = |o: &Options| {
                rocking::simulate(&s, &pulse, &Effects::default(), o)
                    .unwrap_or_else(|e| panic!("{label}: {e}"))
                    .summary
            };
            let (x, y) = (run(&on), run(&off));
            assert_eq!(
                x.max_theta_over_alpha.to_bits(),
                y.max_theta_over_alpha.to_bits(),
                "{label}: max θ/α"
            );
            assert_eq!(x.impacts, y.impacts, "{label}: impacts");
            assert_eq!(x.forces, y.forces, "{label}: force extremes");
            assert!(x.forces.is_some(), "{label}: forces tracked");
            assert_eq!(x.overturned, y.overturned, "{label}: overturned");
            assert_eq!(
                x.first_uplift_time, y.first_uplift_time,
                "{label}: first uplift"
            );
            assert!(
                x.max_u_over_ucr.is_finite() && x.max_u_over_ucr > 0.0,
                "{label}: tracked max |u| {}",
                x.max_u_over_ucr
            );
            assert!(y.max_u_over_ucr.is_nan(), "{label}: untracked max |u|");
            match (x.overturned, x.first_uplift_time.is_some()) {
                (true, _) => overturned += 1,
                (false, true) => rocked += 1,
                (false, false) => stayed += 1,
            }
        }
    }
    // Every kind of cell was compared.
    assert!(
        rocked > 0 && overturned > 0 && stayed > 0,
        "rocked {rocked}, overturned {overturned}, stayed {stayed}"
    );
}
