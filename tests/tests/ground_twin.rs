//! The linear-foundation twin on compliant ground and the bearing-pressure check (issue 44,
//! docs/ground.md): the twin (`Options::uplift` false, as the fixed-base twin on the rigid
//! surface) is the same structure on the same bed with springs that also pull, the full-contact
//! kernels at every state and no contact events.

use rocking::{
    simulate_on_ground, DampingConvention, Dimensionless, Effects, Ground, GroundKind, History,
    Options, Run, Structure,
};
use rocking_motion::SinePulse;

/// A flexible dimensionless structure (R = g = m = 1, α = 0.2, ω_n/p = 10, m_b = m/2, ζ = 0.02).
fn structure() -> Structure {
    let d = Dimensionless {
        omega_n_over_p: 10.0,
        alpha: 0.2,
        gamma_mc: 0.0,
        gamma_mb: 0.5,
        gamma_ib: 1.0,
        zeta: 0.02,
        damping: DampingConvention::FixedBase,
    };
    Structure::from_dimensionless(&d, None).unwrap()
}

/// The Winkler bed with ω_v = 30 p and ζ_v = 0.05.
fn bed(s: &Structure) -> Ground {
    let mass = s.static_uplift().weight; // g = 1
    let k_v = mass * (30.0 * s.derived().p).powi(2);
    let c_v = 2.0 * 0.05 * (k_v * mass).sqrt();
    Ground::from_vertical(GroundKind::Winkler, s.param("b").unwrap(), k_v, c_v)
}

fn options() -> Options {
    let mut o = Options {
        t_end: 8.0,
        energy: true,
        event_log: true,
        history: History::Grid(0.01),
        ..Options::default()
    };
    o.accuracy.method = rocking::Method::Dop853;
    o.accuracy.tol = 1e-10;
    o
}

/// A one-cycle sine pulse of `amplitude` g tan α at ω_p = 5 p: the run and its twin.
fn pair(amplitude: f64, o: &Options) -> (Run, Run) {
    let s = structure();
    let g = bed(&s);
    let pulse = SinePulse::new(amplitude * 0.2f64.tan(), 5.0 * s.derived().p);
    let fx = Effects::default();
    let run = simulate_on_ground(&s, &g, &pulse, &fx, o).unwrap();
    let twin = simulate_on_ground(&s, &g, &pulse, &fx, &o.fixed_base_twin()).unwrap();
    (run, twin)
}

/// Below lift-off the tensionless bed never pulls: the twin is the same run, bit for bit
/// (the same kernels at every state, no event either way); with lift-off it differs and keeps
/// full contact; the twin's energy balance closes with its springs' strain energy, which holds
/// the tension too.
#[test]
fn the_linear_foundation_is_the_run_below_lift_off_and_differs_above() {
    let o = options();
    let (run, twin) = pair(0.05, &o);
    let gr = run.summary.ground.unwrap();
    assert_eq!(gr.lift_offs, 0, "a small pulse lifts no edge");
    assert_eq!(run.history.len(), twin.history.len());
    let same = run.history == twin.history && run.summary == twin.summary;
    println!(
        "a_p = 0.05 g tan α: no lift-off, min contact {}, twin identical: {same}",
        gr.min_contact_fraction
    );
    assert!(same, "{:?}\n{:?}", run.summary, twin.summary);

    let (run, twin) = pair(2.0, &o);
    let (gr, gt) = (run.summary.ground.unwrap(), twin.summary.ground.unwrap());
    let (a, b) = (
        run.summary.max_theta_over_alpha,
        twin.summary.max_theta_over_alpha,
    );
    let residual = twin.summary.energy_balance_residual.unwrap();
    let (mr, mt) = (
        run.summary.forces.unwrap().max_base_moment_over_wb,
        twin.summary.forces.unwrap().max_base_moment_over_wb,
    );
    println!(
        "a_p = 2 g tan α: run {} lift-offs, min contact {:.3}, θ_max/α {a:.4}, M_b {mr:.4} W B; \
         twin {} lift-offs, contact {}, θ_max/α {b:.4}, M_b {mt:.4} W B, energy residual \
         {residual:.1e} E_ref, ground dissipation {:.4} E_ref",
        gr.lift_offs,
        gr.min_contact_fraction,
        gt.lift_offs,
        gt.min_contact_fraction,
        gt.ground_energy_dissipated
    );
    assert!(gr.lift_offs > 0 && gr.min_contact_fraction < 0.9);
    assert_eq!(gt.lift_offs, 0);
    assert_eq!(gt.min_contact_fraction, 1.0);
    assert!(twin.summary.impacts == 0 && twin.summary.first_uplift_time.is_none());
    assert!((a - b).abs() > 1e-2 * a, "{a} {b}");
    assert!(residual.abs() <= 1e-9, "{residual:e}");
    assert!(gt.ground_energy_dissipated > 0.0);
}

/// `bearing_over_mean` = q: the first time the largest pressure under the base exceeds q is
/// reported, the crossing inside its step (on a history grid of 1e-4 τ from the same dense
/// output: no earlier row above q, a row above it within 1e-3 τ after); above the run's largest
/// pressure it is given and never exceeded; not given, not reported.
#[test]
fn the_bearing_pressure_is_reported_when_first_exceeded() {
    let mut o = Options {
        history: History::Grid(1e-4),
        ..options()
    };
    let (run, _) = pair(2.0, &o);
    let max = run.summary.ground.unwrap().max_ground_pressure_over_mean;
    assert_eq!(
        run.summary.ground.unwrap().first_bearing_exceeded_time,
        None
    );
    let q = 0.5 * (1.0 + max);
    o.bearing_over_mean = Some(q);
    let (checked, _) = pair(2.0, &o);
    assert_eq!(checked.history, run.history, "the check changes no state");
    let t = checked
        .summary
        .ground
        .unwrap()
        .first_bearing_exceeded_time
        .expect("given")
        .expect("exceeded")
        .tau;
    // Dimensionless: t = τ. The rows hold the pressure in the model's units.
    let s = structure();
    let mean = bed(&s).mean_pressure(s.static_uplift().weight);
    let over_mean = |h: &rocking::HistoryRow| h.ground.unwrap().ground_pressure / mean;
    let earlier = run
        .history
        .iter()
        .filter(|h| h.t < t)
        .map(over_mean)
        .fold(0.0, f64::max);
    let after = run
        .history
        .iter()
        .filter(|h| h.t >= t && h.t <= t + 1e-3)
        .map(over_mean)
        .fold(0.0, f64::max);
    println!("max pressure {max:.4} × mean; q = {q:.4}: first exceeded at τ = {t:.6}, largest history row before {earlier:.4}, within 1e-3 τ after {after:.4}");
    assert!(earlier <= q, "{earlier} > {q} before τ = {t}");
    assert!(after > q, "{after} <= {q} after τ = {t}");
    o.bearing_over_mean = Some(1.01 * max);
    let (never, _) = pair(2.0, &o);
    assert_eq!(
        never.summary.ground.unwrap().first_bearing_exceeded_time,
        Some(None)
    );
}
