//! The paper's Fig. 3 case: A = 1.30, ω_n/p = 11.9, ω_p/p = 5.1, α = 0.2, ζ = 0.005 fixed-base,
//! point mass (verification.md §1).

use rocking::{Effects, EventKind, History, ImpactModel, Options, Preset, Run};
use rocking_verification::*;

fn run(impact: ImpactModel) -> Run {
    let opts = Options {
        accuracy: Preset::Reference.accuracy(),
        impact,
        t_end: 8.0,
        energy: true,
        event_log: true,
        history: History::Grid(0.01),
        ..Options::default()
    };
    let r = run_checked(
        &fig3_structure(),
        &fig3_pulse(),
        &Effects::default(),
        &opts,
        "Fig. 3",
    );
    assert_eq!(r.summary.kernel_variant, "point_mass");
    assert!(!r.summary.overturned);
    r
}

/// Impact clusters: impacts closer than 0.1 in τ to the previous one belong to its cluster.
fn clusters(r: &Run) -> Vec<Vec<rocking::EventRecord>> {
    let mut out: Vec<Vec<rocking::EventRecord>> = Vec::new();
    for e in impacts(r) {
        match out.last_mut() {
            Some(c) if e.time.tau - c.last().unwrap().time.tau < 0.1 => c.push(e),
            _ => out.push(vec![e]),
        }
    }
    out
}

#[test]
fn fig3_impact_times_double_impact_and_dissipation() {
    let vvel = run(ImpactModel::Vvel);
    let adjex = run(ImpactModel::Adjex);
    let (cv, ca) = (clusters(&vvel), clusters(&adjex));
    for (name, r, c) in [("VVEL", &vvel, &cv), ("ADJex", &adjex, &ca)] {
        let times: Vec<String> = impacts(r)
            .iter()
            .take(8)
            .map(|e| format!("{:.4} ({})", e.time.tau, e.branch))
            .collect();
        let e = r.summary.energy.unwrap();
        eprintln!(
            "Fig. 3 {name}: first uplift τ = {:.4}, impacts {}; first two impact clusters at τ = {:.4}, {:.4}; \
             impact losses Σ = {:.5} E_ref, E(τ = 8) = {:.5} E_ref, max θ/α = {:.4}, residual {:.1e}",
            r.summary.first_uplift_time.unwrap().tau,
            times.join(", "),
            c[0][0].time.tau,
            c[1][0].time.tau,
            e.impact_losses,
            e.last,
            r.summary.max_theta_over_alpha,
            r.summary.energy_balance_residual.unwrap()
        );
        assert!(
            (c[0][0].time.tau - 0.9).abs() <= 0.1,
            "{name}: first impact at {}",
            c[0][0].time.tau
        );
        assert!(
            (c[1][0].time.tau - 2.5).abs() <= 0.15,
            "{name}: second impact at {}",
            c[1][0].time.tau
        );
    }
    // ADJex: double impact at the first impact — immediate rocking, then another impact within 0.1
    let a0 = &ca[0];
    assert!(
        a0.len() >= 2,
        "ADJex: no double impact at the first impact: {a0:?}"
    );
    assert_eq!(a0[0].branch, "adjex-rocking");
    assert_eq!(a0[0].kind, EventKind::Impact);
    let dt = a0[1].time.tau - a0[0].time.tau;
    eprintln!(
        "ADJex double impact: Δτ = {dt:.4}, branches {} → {}",
        a0[0].branch, a0[1].branch
    );
    assert!(dt > 0.0 && dt < 0.1);
    // VVEL: no two impacts within 0.1 anywhere
    assert!(
        cv.iter().all(|c| c.len() == 1),
        "VVEL has a multiple impact: {cv:?}"
    );
    assert_eq!(cv.len(), impacts(&vvel).len());
    // VVEL dissipates less: smaller impact losses and more energy left at τ = 8
    let (ev, ea) = (vvel.summary.energy.unwrap(), adjex.summary.energy.unwrap());
    assert!(ev.impact_losses < ea.impact_losses);
    assert!(ev.last > ea.last);
    let (hv, ha) = (vvel.history.last().unwrap(), adjex.history.last().unwrap());
    eprintln!(
        "e_total at the last grid row τ = {:.2}: VVEL {:.5}, ADJex {:.5}",
        hv.t, hv.e_total, ha.e_total
    );
    assert!(hv.e_total > ha.e_total);
}
