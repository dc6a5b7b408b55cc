//! The solver with several deformation coordinates (issue 28): for the two- and three-function
//! bases of the paper's masses (`polynomial2`, `polynomial3`, `cantilever_modes2`,
//! `cantilever_modes3`) and the eight-mode basis (`cantilever_modes8`, issue 45), through impacts of every impact model, the energy balance closes at the
//! reference preset, no impact creates kinetic energy, the response to the negated ground motion
//! is the mirror image, and the Taylor and DOP853 paths agree.

use rocking::{
    find_model, DampingConvention, Dimensionless, Effects, History, ImpactModel, Method, Options,
    Preset, Run, Structure,
};
use rocking_motion::SinePulse;
use rocking_verification::*;

/// The models of several coordinates.
const MODELS: [&str; 5] = [
    "polynomial2",
    "polynomial3",
    "cantilever_modes2",
    "cantilever_modes3",
    "cantilever_modes8",
];

const IMPACTS: [ImpactModel; 4] = [
    ImpactModel::Vvel,
    ImpactModel::Adjex,
    ImpactModel::Housner,
    ImpactModel::Restitution(0.9),
];

/// The Fig.-5 flexible structure's groups (α = 0.1, γ_mc = 1, γ_mb = 2, ζ = 2 %) with the
/// column of `model`, ω_n/p = 5 (its first fixed-base frequency).
fn structure(model: &str) -> Structure {
    let d = Dimensionless {
        omega_n_over_p: 5.0,
        alpha: 0.1,
        gamma_mc: 1.0,
        gamma_mb: 2.0,
        gamma_ib: 1.0,
        zeta: 0.02,
        damping: DampingConvention::FixedBase,
    };
    let model = find_model(model).expect("a generated model");
    Structure::dimensionless_of_model(model, &d, &[], None).expect("valid structure")
}

/// A pulse that rocks the Fig.-5 structure through several impacts: a_p/(g tan α) = 3,
/// ω_p/p = 4 (`sign` -1: the same pulse negated).
fn pulse(sign: f64) -> SinePulse {
    SinePulse::new(sign * 3.0 * 0.1f64.tan(), 4.0)
}

fn reference(impact: ImpactModel, method: Method) -> Options {
    let mut o = Options {
        accuracy: Preset::Reference.accuracy(),
        impact,
        t_end: 12.0,
        energy: true,
        event_log: true,
        ..Options::default()
    };
    o.accuracy.method = method;
    o
}

fn run(model: &str, impact: ImpactModel, method: Method, sign: f64, history: History) -> Run {
    let opts = Options {
        history,
        ..reference(impact, method)
    };
    let label = format!("{model} {impact:?} {method:?} sign {sign}");
    run_checked(
        &structure(model),
        &pulse(sign),
        &Effects::default(),
        &opts,
        &label,
    )
}

/// The energy balance closes to 1e-8 E_ref at the reference preset, by both methods, through
/// impacts of every model; no impact creates kinetic energy.
#[test]
fn energy_balance_closes_with_several_coordinates() {
    let mut worst: f64 = 0.0;
    for model in MODELS {
        for impact in IMPACTS {
            for method in [Method::Dop853, Method::Taylor] {
                let r = run(model, impact, method, 1.0, History::None);
                let s = &r.summary;
                let res = s.energy_balance_residual.unwrap();
                eprintln!(
                    "{model} {impact:?} {method:?}: {} impacts, max θ/α {:.5}, max u/u_cr {:.4}, \
                     residual {res:.2e} E_ref",
                    s.impacts, s.max_theta_over_alpha, s.max_u_over_ucr
                );
                assert_eq!(s.kernel_variant, model);
                assert!(s.impacts >= 2, "{model} {impact:?}: the pulse must rock it");
                assert!(
                    res.abs() <= 1e-8,
                    "{model} {impact:?} {method:?}: residual {res:e} E_ref"
                );
                for e in impacts(&r) {
                    assert!(
                        e.energy_after <= e.energy_before * (1.0 + 1e-9) + 1e-15,
                        "{model} {impact:?} {method:?}: an impact gains energy: {e:?}"
                    );
                }
                worst = worst.max(res.abs());
            }
        }
    }
    eprintln!("worst residual {worst:.2e} E_ref");
}

/// The negated ground motion gives the mirror image: θ, u and every coordinate negated, the
/// same impacts at the same times.
#[test]
fn negated_ground_motion_mirrors_the_response() {
    let mut worst: f64 = 0.0;
    for model in MODELS {
        for impact in IMPACTS {
            let grid = History::Grid(0.05);
            let a = run(model, impact, Method::Dop853, 1.0, grid);
            let b = run(model, impact, Method::Dop853, -1.0, grid);
            assert_eq!(a.summary.impacts, b.summary.impacts, "{model} {impact:?}");
            assert_eq!(a.history.len(), b.history.len());
            let (sa, sb) = (&a.summary, &b.summary);
            assert!(rel(sa.max_theta_over_alpha, sb.max_theta_over_alpha, 1e-12) <= 1e-9);
            assert!(rel(sa.max_u_over_ucr, sb.max_u_over_ucr, 1e-12) <= 1e-9);
            for (x, y) in a.history.iter().zip(&b.history) {
                let d = (x.theta + y.theta).abs() / 0.1 + (x.u + y.u).abs();
                worst = worst.max(d);
                assert!(d <= 1e-9, "{model} {impact:?} t {}: {x:?} vs {y:?}", x.t);
            }
        }
    }
    eprintln!("mirror: worst |θ+θ'|/α + |u+u'| = {worst:.2e}");
}

/// The Taylor path and DOP853 agree at the reference tolerance on θ and u (max θ/α, max u/u_cr,
/// the first impact's time and the number of impacts).
#[test]
fn taylor_and_dop853_agree_with_several_coordinates() {
    let mut worst: f64 = 0.0;
    for model in MODELS {
        for impact in [ImpactModel::Vvel, ImpactModel::Adjex] {
            let a = run(model, impact, Method::Dop853, 1.0, History::None).summary;
            let b = run(model, impact, Method::Taylor, 1.0, History::None).summary;
            let d = [
                rel(a.max_theta_over_alpha, b.max_theta_over_alpha, 1e-3),
                rel(a.max_u_over_ucr, b.max_u_over_ucr, 1e-3),
                rel(
                    a.first_impact_time.unwrap().tau,
                    b.first_impact_time.unwrap().tau,
                    1.0,
                ),
            ];
            let d = d.into_iter().fold(0.0, f64::max);
            eprintln!("{model} {impact:?}: Taylor against DOP853 {d:.2e}");
            assert_eq!(a.impacts, b.impacts, "{model} {impact:?}");
            assert!(d <= 1e-6, "{model} {impact:?}: {d:e}");
            worst = worst.max(d);
        }
    }
    eprintln!("worst Taylor-DOP853 difference {worst:.2e}");
}

/// Basis invariance: {η², η³} (`polynomial2`) and {ψ_cubic, η²} (`cubic_quadratic`) span the same
/// functions, so the motion (θ and the top deflection u) is the same through impacts of every
/// map, to the integrator's tolerance; the impact maps nearest in the kinetic-energy norm do not
/// depend on the basis (docs/modes.md).
#[test]
fn the_motion_does_not_depend_on_the_basis() {
    let mut worst: f64 = 0.0;
    for impact in IMPACTS {
        let grid = History::Grid(0.05);
        let a = run("polynomial2", impact, Method::Dop853, 1.0, grid);
        let b = run("cubic_quadratic", impact, Method::Dop853, 1.0, grid);
        assert_eq!(a.summary.impacts, b.summary.impacts, "{impact:?}");
        assert_eq!(a.history.len(), b.history.len(), "{impact:?}");
        let u_cr = structure("polynomial2").derived().u_cr;
        let mut d: f64 = 0.0;
        for (x, y) in a.history.iter().zip(&b.history) {
            d = d
                .max((x.theta - y.theta).abs() / 0.1)
                .max((x.u - y.u).abs() / u_cr);
        }
        let (sa, sb) = (&a.summary, &b.summary);
        d = d
            .max(rel(sa.max_theta_over_alpha, sb.max_theta_over_alpha, 1e-3))
            .max(rel(sa.max_u_over_ucr, sb.max_u_over_ucr, 1e-3));
        eprintln!(
            "{impact:?}: {} impacts, largest difference {d:.2e} (θ/α, u/u_cr)",
            sa.impacts
        );
        assert!(d <= 1e-9, "{impact:?}: the bases differ by {d:e}");
        worst = worst.max(d);
    }
    eprintln!("basis invariance: worst {worst:.2e}");
}

/// `damping = "uplifted"` with several coordinates: one fixed-base ratio for every mode, chosen
/// so that the first uplifted mode has the scene's ratio (for one coordinate, eq (19): ζ/S).
#[test]
fn uplifted_damping_gives_the_first_uplifted_mode_the_scenes_ratio() {
    for model in MODELS.into_iter().chain(["cubic"]) {
        for zeta in [0.001, 0.01, 0.05] {
            let d = Dimensionless {
                zeta,
                damping: DampingConvention::Uplifted,
                ..structure(model).dimensionless()
            };
            let s = Structure::dimensionless_of_model(find_model(model).unwrap(), &d, &[], None)
                .unwrap_or_else(|e| panic!("{model}, ζ = {zeta}: {e:?}"));
            let derived = s.derived();
            let rel = (derived.zeta_uplifted / zeta - 1.0).abs();
            // Every uplifted mode has its ratio, the first the scene's.
            let ratios = s.frequencies().uplifted_damping;
            assert_eq!(ratios.len(), s.model().coordinates, "{model}: {ratios:?}");
            assert!(
                ratios.iter().all(|r| r.is_finite() && *r > 0.0),
                "{model}: {ratios:?}"
            );
            assert!((ratios[0] / zeta - 1.0).abs() < 1e-9, "{model}: {ratios:?}");
            assert!(rel < 1e-9, "{model}, ζ = {zeta}: uplifted {derived:?}");
            // Rocking adds the base's inertia to the mode: its ratio grows, as eq (19)'s S > 1.
            assert!(derived.zeta_fixed_base < zeta / 2.0, "{model}: {derived:?}");
        }
    }
}

/// Damping ratios given per mode (`zeta = [..]`) reach the simulation: with the higher modes
/// damped more than the first, the energy balance still closes at the reference preset by both
/// methods, the column dissipates more than with the first mode's ratio everywhere, and the
/// ratios read back from the damping matrix are the ones given. The same ratio for every mode is
/// the one-ratio structure, bit for bit.
#[test]
fn damping_ratios_per_mode_reach_the_simulation() {
    for model in MODELS {
        let n = find_model(model).unwrap().coordinates;
        let per_mode: Vec<f64> = [0.02, 0.1, 0.3, 0.3, 0.3, 0.3, 0.3, 0.3][..n].to_vec();
        let uniform = structure(model);
        let graded = uniform.with_modal_damping_ratios(&per_mode).unwrap();
        let read = graded.frequencies().fixed_base_damping;
        for (r, z) in read.iter().zip(&per_mode) {
            assert!(
                (r / z - 1.0).abs() < 1e-12,
                "{model}: {read:?} for {per_mode:?}"
            );
        }
        assert_eq!(graded.modal_damping_ratios(), &per_mode[..]);
        let same = uniform.with_modal_damping_ratios(&vec![0.02; n]).unwrap();
        for method in [Method::Dop853, Method::Taylor] {
            let opts = reference(ImpactModel::Vvel, method);
            let label = format!("{model} per-mode damping {method:?}");
            let dissipated = |s: &Structure| {
                let r = run_checked(s, &pulse(1.0), &Effects::default(), &opts, &label);
                let res = r.summary.energy_balance_residual.unwrap();
                assert!(res.abs() <= 1e-8, "{label}: residual {res:e} E_ref");
                (r.summary.energy.unwrap().damping, r.summary)
            };
            let (d_uniform, s_uniform) = dissipated(&uniform);
            let (d_graded, _) = dissipated(&graded);
            let (_, s_same) = dissipated(&same);
            eprintln!("{label}: dissipated {d_uniform:.4e} (ζ = 0.02) vs {d_graded:.4e} E_ref ({per_mode:?})");
            assert!(d_graded > d_uniform, "{label}: {d_graded} vs {d_uniform}");
            assert_eq!(s_same, s_uniform, "{label}: one ratio per mode, all equal");
        }
    }
}
