//! Dimensionless invariance (eq 34): physical structures in SI with the same dimensionless
//! groups give the same θ/α(τ), u/u_cr(τ) and summary as each other and as the dimensionless
//! structure (verification.md §4).

use rocking::{Effects, History, ImpactModel, Options, Preset, Run, Structure};
use rocking_kernels::Physical;
use rocking_motion::SinePulse;
use rocking_verification::*;

const ALPHA: f64 = 0.1;
const WN: f64 = 5.0; // ω_n/p
const GMC: f64 = 1.0;
const GMB: f64 = 2.0;
const GIB: f64 = 1.0;
const ZETA: f64 = 0.005;
const A: f64 = 3.0; // a_p/(g tan α)
const WP: f64 = 4.0; // ω_p/p
const TAU_END: f64 = 10.0;
const DTAU: f64 = 0.01;

fn si_structure(r: f64, m: f64) -> Structure {
    let g = 9.81;
    let (b, h) = (r * ALPHA.sin(), r * ALPHA.cos());
    let m_c = GMC * m;
    let m_b = GMB * m;
    let p = (g / r).sqrt();
    let m_tilde = m + 33.0 / 140.0 * m_c;
    let k_tilde = m_tilde * (WN * p).powi(2); // ω_n = sqrt(k̃/m̃)
    let ei = k_tilde * h.powi(3) / 3.0; // k̃ = 3EI/H³
    Structure::from_physical(Physical {
        h,
        b,
        ei,
        m,
        m_c,
        m_b,
        i_bc: GIB * 4.0 / 3.0 * m_b * b * b,
        zeta: ZETA,
        g,
    })
    .unwrap()
}

fn run(s: &Structure, impact: ImpactModel, label: &str) -> Run {
    let d = s.derived();
    let (p, g) = (d.p, s.physical().g);
    let pulse = SinePulse::new(A * g * ALPHA.tan(), WP * p);
    let opts = Options {
        accuracy: Preset::Reference.accuracy(),
        impact,
        t_end: TAU_END / p,
        energy: true,
        event_log: true,
        history: History::Grid(DTAU / p),
        ..Options::default()
    };
    run_checked(s, &pulse, &Effects::default(), &opts, label)
}

#[test]
fn si_structures_with_equal_groups_give_equal_dimensionless_response() {
    let small = si_structure(16.0, 1e5);
    let large = si_structure(140.0, 3e6);
    let dimless = dimensionless(
        ALPHA,
        WN,
        GMC,
        GMB,
        ZETA,
        rocking::DampingConvention::FixedBase,
    );
    // the groups agree
    for s in [&small, &large] {
        let d = s.dimensionless();
        let r = dimless.dimensionless();
        for (a, b) in [
            (d.alpha, r.alpha),
            (d.omega_n_over_p, r.omega_n_over_p),
            (d.gamma_mc, r.gamma_mc),
            (d.gamma_mb, r.gamma_mb),
            (d.gamma_ib, r.gamma_ib),
            (d.zeta, r.zeta),
        ] {
            assert!(
                (a - b).abs() <= 1e-12 * b.abs().max(1.0),
                "groups differ: {d:?} vs {r:?}"
            );
        }
        assert!(s.p_per_second().is_some());
    }
    eprintln!(
        "p = {:.5} 1/s (R = 16 m), {:.5} 1/s (R = 140 m)",
        small.derived().p,
        large.derived().p
    );
    for impact in [ImpactModel::Vvel, ImpactModel::Adjex] {
        let runs = [
            ("R = 16 m", run(&small, impact, "R = 16 m")),
            ("R = 140 m", run(&large, impact, "R = 140 m")),
        ];
        let reference = run(&dimless, impact, "dimensionless");
        let dr = dimless.derived();
        assert!(reference.summary.impacts >= 2, "should rock");
        for (name, r) in &runs {
            let d = match *name {
                "R = 16 m" => small.derived(),
                _ => large.derived(),
            };
            let n = r.history.len().min(reference.history.len());
            assert!(
                r.history.len().abs_diff(reference.history.len()) <= 1,
                "{name}: row counts {} vs {}",
                r.history.len(),
                reference.history.len()
            );
            let mut worst = [0.0f64; 4];
            for (a, b) in r.history[..n].iter().zip(&reference.history[..n]) {
                worst[0] = worst[0].max((a.t * d.p - b.t * dr.p).abs());
                worst[1] = worst[1].max((a.theta / d.alpha - b.theta / dr.alpha).abs());
                worst[2] = worst[2].max((a.u / d.u_cr - b.u / dr.u_cr).abs());
                worst[3] = worst[3].max((a.e_total / d.e_ref - b.e_total / dr.e_ref).abs());
                assert_eq!(a.phase, b.phase, "{name}: phase at τ = {}", b.t * dr.p);
            }
            let (sa, sb) = (&r.summary, &reference.summary);
            let t = |x: Option<rocking::Time>| x.unwrap().tau;
            let pairs = [
                ("max θ/α", sa.max_theta_over_alpha, sb.max_theta_over_alpha),
                ("max u/u_cr", sa.max_u_over_ucr, sb.max_u_over_ucr),
                (
                    "first uplift τ",
                    t(sa.first_uplift_time),
                    t(sb.first_uplift_time),
                ),
                (
                    "first impact τ",
                    t(sa.first_impact_time),
                    t(sb.first_impact_time),
                ),
                ("end τ", sa.end_time.tau, sb.end_time.tau),
                ("E_end", sa.energy.unwrap().last, sb.energy.unwrap().last),
                (
                    "impact losses",
                    sa.energy.unwrap().impact_losses,
                    sb.energy.unwrap().impact_losses,
                ),
                (
                    "ground work",
                    sa.energy.unwrap().ground_work,
                    sb.energy.unwrap().ground_work,
                ),
            ];
            let worst_s = pairs
                .iter()
                .map(|(_, a, b)| (a - b).abs() / b.abs().max(1e-300))
                .fold(0.0f64, f64::max);
            eprintln!(
                "{impact:?}, {name} vs dimensionless: {n} rows, max |Δτ| = {:.1e}, max |Δ θ/α| = {:.1e}, max |Δ u/u_cr| = {:.1e}, max |Δ e_total| = {:.1e} E_ref; \
                 summary max rel diff {worst_s:.1e}; impacts {} vs {}; seconds of first impact {:.4} s; steps {} vs {}",
                worst[0], worst[1], worst[2], worst[3], sa.impacts, sb.impacts,
                sa.first_impact_time.unwrap().seconds.unwrap(), sa.solver_stats.steps, sb.solver_stats.steps
            );
            assert!(worst[0] <= 1e-9, "{name}: τ grids differ by {}", worst[0]);
            assert!(
                worst[1] <= 1e-7 && worst[2] <= 1e-7,
                "{name}: responses differ: {worst:?}"
            );
            assert!(worst[3] <= 1e-7);
            assert_eq!(sa.impacts, sb.impacts);
            assert_eq!(sa.significant_impacts, sb.significant_impacts);
            assert_eq!(sa.overturned, sb.overturned);
            assert_eq!(sa.final_phase, sb.final_phase);
            assert!(worst_s <= 1e-7, "{name}: summaries differ: {pairs:?}");
            // seconds = τ / p
            let secs = sa.first_impact_time.unwrap().seconds.unwrap();
            assert!((secs * d.p - t(sa.first_impact_time)).abs() < 1e-12);
        }
    }
}
