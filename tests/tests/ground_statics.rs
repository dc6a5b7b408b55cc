//! The statics and small vibrations of compliant ground (issue 44, docs/ground.md), from
//! `rocking::ground_statics` and `rocking::ground_modes` (root searches and an eigenproblem on
//! the generated kernels), against their closed forms: the settlement, the rotational
//! stiffness, the first lift-off, the moment–rotation curve after it, a slow quasi-static push
//! through `simulate_on_ground`, and the small-amplitude frequencies.

use rocking::ground_statics::{moment_at, moment_rotation, statics};
use rocking::{Ground, GroundKind};

/// A ground with bed stiffness (or corner spring) `k` under a base of half-width `b`.
fn ground(kind: GroundKind, b: f64, k: f64) -> Ground {
    Ground { kind, b, k, c: 0.0 }
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

/// v0 = W / K_v with K_v = 2 k B (bed), 2 k (springs); k_θ = (2/3) k B³ (bed), 2 k B² (springs),
/// and the same as a centred difference of the moment–rotation curve at θ = 0 (step h = 1e-3
/// θ_lift: its h² error is 0 for the full contact's M ∝ sin θ cos θ up to 4 h²/6 ≈ 1e-13, and
/// its rounding ≈ 1e-16 / 1e-3 θ_lift relative).
#[test]
fn settlement_and_rotational_stiffness_before_lift_off() {
    let (b, k, w): (f64, f64, f64) = (1.3, 2.0e6, 450.0);
    for (kind, k_v, k_rot) in [
        (GroundKind::Winkler, 2.0 * k * b, 2.0 / 3.0 * k * b.powi(3)),
        (GroundKind::TwoSpring, 2.0 * k, 2.0 * k * b * b),
    ] {
        let g = ground(kind, b, k);
        let st = statics(&g, w);
        let h = 1e-3 * st.lift_off.theta;
        let difference = (moment_at(&g, w, h).moment - moment_at(&g, w, -h).moment) / (2.0 * h);
        println!(
            "{kind:?}: v0 {:.6e} (error {:.1e}), k_θ {:.6e} (error {:.1e}), centred difference \
             error {:.1e}",
            st.settlement,
            rel(st.settlement, w / k_v),
            st.k_rot,
            rel(st.k_rot, k_rot),
            rel(difference, k_rot)
        );
        assert!(rel(st.k_v, k_v) <= 1e-15, "{kind:?}: {st:?}");
        assert!(rel(st.settlement, w / k_v) <= 1e-15, "{kind:?}: {st:?}");
        assert!(rel(st.k_rot, k_rot) <= 1e-14, "{kind:?}: {st:?}");
        assert!(rel(difference, k_rot) <= 1e-10, "{kind:?}: {difference}");
        // The mean pressure (moved from the driver into `Ground`) is the full-contact kernel's
        // pressure at rest.
        let at_rest = g.full(&[0.0, st.settlement, 0.0, 0.0])[5];
        assert!(
            rel(st.mean_pressure, at_rest) <= 1e-15,
            "{kind:?}: {at_rest}"
        );
    }
}

/// The first edge lifts at sin θ = v0 / B, with M = W B cos θ / 3 on the bed (the textbook
/// W B / 3 at small rotation) and W B cos θ on two springs: the root search on the kernels
/// against the closed forms, and against the derivation's own `*_statics` kernel.
#[test]
fn first_edge_lift_off() {
    let (b, k, w) = (0.8, 5.0e5, 300.0);
    for (kind, k_v, third) in [
        (GroundKind::Winkler, 2.0 * k * b, 1.0 / 3.0),
        (GroundKind::TwoSpring, 2.0 * k, 1.0),
    ] {
        let g = ground(kind, b, k);
        let lift = statics(&g, w).lift_off;
        let theta = (w / k_v / b).asin();
        let moment = w * b * theta.cos() * third;
        println!(
            "{kind:?}: θ_lift {:.9e} (error {:.1e}), M {:.9} W B (error {:.1e}, closed form {:.9} W B)",
            lift.theta,
            rel(lift.theta, theta),
            lift.moment / (w * b),
            rel(lift.moment, moment),
            moment / (w * b)
        );
        assert!(rel(lift.theta, theta) <= 1e-13, "{kind:?}: {lift:?}");
        assert!(rel(lift.moment, moment) <= 1e-12, "{kind:?}: {lift:?}");
        assert_eq!(lift.contact_fraction, 1.0);
        let kernel = g.statics(w);
        assert!(rel(lift.theta, kernel.theta_lift_off) <= 1e-13);
        assert!(rel(lift.moment, kernel.moment_lift_off) <= 1e-12);
    }
}

/// After lift-off the bed carries W on a triangle of contact length L: vertical equilibrium
/// W = k sin θ L² / 2 gives L = √(2 W / (k sin θ)), the resultant acts at L / 3 from the
/// pressing corner, so M = W cos θ (B − L / 3) (the moment about the base centre of a force W
/// at B − L/3 along the base, cos θ from the exact rotation) and v = (L − B) sin θ; it rises
/// towards W B as the contact shrinks. Two springs carry W on the one corner: M = W B cos θ.
#[test]
fn moment_rotation_after_lift_off() {
    let (b, k, w) = (1.0, 1.0e6, 200.0);
    let bed = ground(GroundKind::Winkler, b, k);
    let lift = statics(&bed, w).lift_off.theta;
    let thetas: Vec<f64> = (0..=30)
        .map(|i| lift * 1.001 * 400f64.powf(f64::from(i) / 30.0))
        .collect();
    let curve = moment_rotation(&bed, w, &thetas);
    let mut worst = 0.0f64;
    for (pt, &theta) in curve.iter().zip(&thetas) {
        let l = (2.0 * w / (k * theta.sin())).sqrt();
        let m = w * theta.cos() * (b - l / 3.0);
        worst = worst
            .max(rel(pt.moment, m))
            .max(rel(pt.contact_fraction, l / (2.0 * b)))
            .max((pt.settlement - (l - b) * theta.sin()).abs() / (w / (2.0 * k * b)));
    }
    let last = curve.last().unwrap();
    println!(
        "bed after lift-off: worst relative error {worst:.1e} over θ = 1.001 .. {:.0} θ_lift; \
         at the largest, contact {:.4} and M = {:.4} W B",
        400.0 * 1.001,
        last.contact_fraction,
        last.moment / (w * b)
    );
    assert!(worst <= 1e-10, "{worst:e}");
    assert!(curve.windows(2).all(|p| p[1].moment > p[0].moment));
    assert!(last.moment > 0.95 * w * b && last.moment < w * b);
    let springs = ground(GroundKind::TwoSpring, b, k);
    let lift = statics(&springs, w).lift_off.theta;
    for i in 1..=20 {
        let theta = lift * (1.0 + 0.5 * f64::from(i));
        let pt = moment_at(&springs, w, theta);
        let m = w * b * theta.cos();
        assert!(rel(pt.moment, m) <= 1e-12, "two springs at {theta}: {pt:?}");
        assert_eq!(pt.contact_fraction, 0.5);
    }
}
