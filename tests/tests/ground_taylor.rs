//! The Taylor method on compliant ground (issue 44): the free base's series, solved order by
//! order at run time, against DOP853.

use rocking::{
    simulate_on_ground, DampingConvention, Dimensionless, Effects, EventKind, Ground, GroundKind,
    History, Method, Options, Run, Structure,
};
use rocking_motion::{GroundMotion, NoMotion, SinePulse};

/// A dimensionless structure (R = g = m = 1, α = 0.2).
fn structure(omega_n_over_p: f64, gamma_mb: f64, zeta: f64) -> Structure {
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

/// The bed of `kind` with ω_v = `ratio` p and damping ratio `zeta_v` for `s`.
fn bed(s: &Structure, kind: GroundKind, ratio: f64, zeta_v: f64) -> Ground {
    let mass = s.static_uplift().weight; // g = 1
    let k_v = mass * (ratio * s.derived().p).powi(2);
    let c_v = 2.0 * zeta_v * (k_v * mass).sqrt();
    Ground::from_vertical(kind, s.param("b").unwrap(), k_v, c_v)
}

fn options(method: Method, tol: f64, t_end: f64, theta0: f64) -> Options {
    let mut o = Options {
        t_end,
        energy: true,
        event_log: true,
        forces: true,
        history: History::Grid(0.01),
        ..Options::default()
    };
    o.accuracy.method = method;
    o.accuracy.tol = tol;
    o.initial.theta = theta0;
    o
}

fn run(s: &Structure, g: &Ground, m: &dyn GroundMotion, fx: &Effects, o: &Options) -> Run {
    simulate_on_ground(s, g, m, fx, o).unwrap_or_else(|e| panic!("run failed: {e}"))
}

/// The largest difference of θ/α, v/v0 and the top deflection over u_cr between two runs' history
/// rows on the same grid.
fn history_gap(a: &Run, b: &Run, alpha: f64, v0: f64, u_cr: f64) -> f64 {
    assert_eq!(a.history.len(), b.history.len());
    a.history
        .iter()
        .zip(&b.history)
        .map(|(x, y)| {
            let gx = x.ground.as_ref().unwrap();
            let gy = y.ground.as_ref().unwrap();
            ((x.theta - y.theta) / alpha)
                .abs()
                .max(((gx.settlement - gy.settlement) / v0).abs())
                .max(((x.u - y.u) / u_cr).abs())
        })
        .fold(0.0, f64::max)
}

#[test]
fn taylor_against_dop853_on_the_ground() {
    for kind in [GroundKind::Winkler, GroundKind::TwoSpring] {
        let s = structure(10.0, 0.5, 0.05);
        let g = bed(&s, kind, 30.0, 0.1);
        let pulse = SinePulse::new(1.3 * 0.2f64.tan(), 4.0);
        let fx = Effects::default();
        let d = run(&s, &g, &pulse, &fx, &options(Method::Dop853, 1e-13, 8.0, 0.0));
        let t = run(&s, &g, &pulse, &fx, &options(Method::Taylor, 1e-13, 8.0, 0.0));
        let v0 = g.statics(s.static_uplift().weight).settlement;
        let gap = history_gap(&d, &t, 0.2, v0, s.derived().u_cr);
        let gd = d.summary.ground.as_ref().unwrap();
        let gt = t.summary.ground.as_ref().unwrap();
        println!(
            "{kind:?}: gap {gap:e}; lift-offs {} / {}; steps {} / {}; residual {:e} / {:e}",
            gd.lift_offs,
            gt.lift_offs,
            d.summary.solver_stats.steps,
            t.summary.solver_stats.steps,
            d.summary.energy_balance_residual.unwrap(),
            t.summary.energy_balance_residual.unwrap()
        );
    }
}
