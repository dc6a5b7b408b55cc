//! The statics and small vibrations of compliant ground (issue 44, docs/ground.md), from
//! `rocking::ground_statics` and `rocking::ground_modes` (root searches and an eigenproblem on
//! the generated kernels), against their closed forms: the settlement, the rotational
//! stiffness, the first lift-off, the moment–rotation curve after it, a slow quasi-static push
//! through `simulate_on_ground`, and the small-amplitude frequencies.

use rocking::ground_modes::{small_vibrations, Coordinate};
use rocking::ground_statics::{moment_at, moment_rotation, statics};
use rocking::{
    simulate_on_ground, DampingConvention, Dimensionless, Effects, EventKind, Ground, GroundKind,
    History, Options, Structure,
};
use rocking_motion::{GroundMotion, NoMotion};

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

/// A dimensionless structure (R = g = m = 1, α = 0.2).
fn structure(gamma_mb: f64) -> Structure {
    let d = Dimensionless {
        omega_n_over_p: 10.0,
        alpha: 0.2,
        gamma_mc: 0.0,
        gamma_mb,
        gamma_ib: 1.0,
        zeta: 0.0,
        damping: DampingConvention::FixedBase,
    };
    Structure::from_dimensionless(&d, None).unwrap()
}

/// The undamped bed with ω_v = `ratio` p for `s`.
fn bed(s: &Structure, kind: GroundKind, ratio: f64) -> Ground {
    let mass = s.static_uplift().weight; // g = 1
    let k_v = mass * (ratio * s.derived().p).powi(2);
    Ground::from_vertical(kind, s.param("b").unwrap(), k_v, 0.0)
}

fn rigid() -> Effects {
    Effects {
        flexibility: false,
        ..Effects::default()
    }
}

/// ü_g = −rate t: a slow push that tilts the structure towards θ > 0.
struct Ramp {
    rate: f64,
}

impl GroundMotion for Ramp {
    fn accel(&self, t: f64) -> f64 {
        -self.rate * t
    }
    fn end(&self) -> f64 {
        f64::INFINITY
    }
    fn next_kink(&self, _t: f64) -> Option<f64> {
        None
    }
}

/// A rigid column (top mass m at H, base mass m_b at the base centre) pushed by a slow
/// ground-acceleration ramp on the bed: at every recorded instant the ground acceleration is the
/// static one that holds the structure at its θ, ü_g = (g m H sin θ − M(θ)) / ((m + m_b) B
/// sin θ + m H cos θ) (moments of gravity and of the inertia forces about the base centre, with
/// the no-sliding kinematics: the mass is at B (1 − cos θ) + H sin θ), M(θ) the ground's
/// moment–rotation curve of `ground_statics`, to the ramp's overshoot: a ramp started from rest
/// leaves an oscillation of amplitude rate / ω in ü_g (ω the small-amplitude rocking frequency
/// on the ground; the tangent frequency falls after lift-off, hence the bound 3 rate / ω).
#[test]
fn a_slow_push_follows_the_static_curve() {
    let s = structure(0.5);
    let g = bed(&s, GroundKind::Winkler, 30.0);
    let (m, m_b, h, b) = (
        s.param("m").unwrap(),
        s.param("m_b").unwrap(),
        s.param("h").unwrap(),
        s.param("b").unwrap(),
    );
    let w = s.static_uplift().weight;
    let gacc = s.param("g").unwrap_or(1.0);
    let modes = small_vibrations(&s, &rigid(), &g).unwrap();
    let omega = modes.omega[0];
    // The static curve's peak (the largest ground acceleration the structure can stand on the
    // bed, P-Δ included) over a grid of rotations; the ramp stops at 3/4 of it.
    let curve_ug = |theta: f64| {
        let moment = moment_at(&g, w, theta).moment;
        (gacc * m * h * theta.sin() - moment) / ((m + m_b) * b * theta.sin() + m * h * theta.cos())
    };
    let peak = (1..=2000)
        .map(|i| curve_ug(0.2 * f64::from(i) / 2000.0))
        .fold(f64::INFINITY, f64::min);
    let target = -0.75 * peak;
    let t_end = 400.0 / s.derived().p;
    let rate = target / t_end;
    let mut o = Options {
        t_end,
        event_log: true,
        history: History::Grid(t_end / 400.0),
        ..Options::default()
    };
    o.accuracy.method = rocking::Method::Dop853;
    o.accuracy.tol = 1e-10;
    let r = simulate_on_ground(&s, &g, &Ramp { rate }, &rigid(), &o).unwrap();
    let lift_offs = r.summary.ground.unwrap().lift_offs;
    let mut worst = 0.0f64;
    let mut min_contact = 1.0f64;
    for row in r.history.iter().skip(1) {
        let ug = curve_ug(row.theta);
        worst = worst.max((row.ug - ug).abs());
        min_contact = min_contact.min(row.ground.unwrap().contact_fraction);
    }
    let overshoot = rate / omega;
    println!(
        "static peak {:.4} g tan α; ramp to {:.3} g tan α over τ = 400: {lift_offs} lift-off(s), contact down to {min_contact:.3}, \
         θ_max/α = {:.3}; worst |ü_g − static| = {worst:.3e} = {:.2} × rate/ω (ω = {omega:.4})",
        -peak / (gacc * 0.2f64.tan()),
        target / (gacc * 0.2f64.tan()),
        r.summary.max_theta_over_alpha,
        worst / overshoot
    );
    assert_eq!(lift_offs, 1, "the push lifts one edge, once");
    // Measured: contact down to 0.762 of the base at 3/4 of the peak.
    assert!(
        min_contact < 0.8,
        "the push goes past lift-off: {min_contact}"
    );
    assert!(
        r.events.iter().all(|e| e.kind != EventKind::Landing),
        "a quasi-static push never lands"
    );
    assert!(
        worst <= 3.0 * overshoot,
        "{worst:e} against rate/ω {overshoot:e}"
    );
}

/// A rigid column on the bed: the rocking frequency of the linear eigenproblem against the
/// closed form of a body with masses on its axis, ω² = (K_v B²/3 − g m H) / (m H² + I_b), with
/// K_v = (m + m_b) ω_v² and I_b = I_bc − m_b B² the base's inertia about its centre (for a
/// point mass alone, m_b → 0: the (ω_v² B²/3 − g H)/H²), and the vertical one ω_v; then
/// a small-amplitude run's period against it.
#[test]
fn small_amplitude_frequencies_on_the_bed() {
    for gamma_mb in [1e-4, 0.5] {
        let s = structure(gamma_mb);
        let ratio = 30.0;
        let g = bed(&s, GroundKind::Winkler, ratio);
        let (m, m_b, h, b, i_bc) = (
            s.param("m").unwrap(),
            s.param("m_b").unwrap(),
            s.param("h").unwrap(),
            s.param("b").unwrap(),
            s.param("i_bc").unwrap(),
        );
        let gacc = s.param("g").unwrap_or(1.0);
        let omega_v = ratio * s.derived().p;
        let k_v = (m + m_b) * omega_v * omega_v;
        let rocking =
            ((k_v * b * b / 3.0 - gacc * m * h) / (m * h * h + i_bc - m_b * b * b)).sqrt();
        let modes = small_vibrations(&s, &rigid(), &g).unwrap();
        assert_eq!(
            modes.dominant,
            [Coordinate::Rotation, Coordinate::Settlement]
        );
        let (e_rock, e_vert) = (rel(modes.omega[0], rocking), rel(modes.omega[1], omega_v));
        println!(
            "γ_mb = {gamma_mb}: ω_rock {:.12} (closed form {rocking:.12}, error {e_rock:.1e}), \
             ω_v {:.12} (error {e_vert:.1e}); K's estimated error {:.1e}, equilibrium residual {:.1e}",
            modes.omega[0], modes.omega[1], modes.stiffness_error, modes.equilibrium_residual
        );
        assert!(e_rock <= 1e-10 && e_vert <= 1e-10, "{modes:?}");
        assert!(modes.stiffness_error <= 1e-10 && modes.equilibrium_residual <= 1e-14);
        // A run released at θ0 = 0.01 θ_lift: its period from the θ = 0 crossings. The
        // nonlinearity of the full contact is of relative order θ0² (the ground's sin θ cos θ
        // and gravity's sin θ), the event location at rtol 1e-12.
        let st = g.statics(s.static_uplift().weight);
        let mut o = Options {
            t_end: 10.0,
            event_log: true,
            history: History::None,
            ..Options::default()
        };
        o.accuracy.method = rocking::Method::Dop853;
        o.accuracy.tol = 1e-12;
        o.initial.theta = 0.01 * st.theta_lift_off;
        let r = simulate_on_ground(&s, &g, &NoMotion, &rigid(), &o).unwrap();
        assert_eq!(r.summary.ground.unwrap().lift_offs, 0);
        let crossings: Vec<f64> = r
            .events
            .iter()
            .filter(|e| e.kind == EventKind::PivotSwitch)
            .map(|e| e.time.tau)
            .collect();
        let n = crossings.len() - 1;
        let period = 2.0 * (crossings[n] - crossings[0]) / n as f64 / s.derived().p;
        let expected = 2.0 * std::f64::consts::PI / modes.omega[0];
        println!(
            "  run period {period:.10} against 2π/ω {expected:.10}: relative {:.1e} (θ0 = {:.1e})",
            rel(period, expected),
            o.initial.theta
        );
        // First order in the amplitude: the no-sliding kinematics move the base centre by
        // s B (1 − cos θ), which adds to T a term of relative order θ0 B / H.
        assert!(
            rel(period, expected) <= o.initial.theta,
            "{period} {expected}"
        );
    }
}

/// A flexible column on the bed: the eigenproblem in (θ, v, u) has the vertical mode at ω_v
/// exactly (symmetric structure: v decouples at θ = 0); its rocking–deflection pair brackets
/// the fixed-base frequency ω_n (θ = 0 is a constraint of the pair: Cauchy interlacing), and
/// the lower of the pair rises to ω_n as the bed stiffens: the fixed-base limit, θ held by
/// k_θ ∝ ω_v², so the error falls as (p/ω_v)², order 2. ω_n is the fixed-base kernels'
/// (`Structure::derived`, an independent eigenproblem in u alone). On the softest bed the
/// lower mode is the rocking one and u dominates the upper; from ω_v/p = 80 u dominates the
/// lower.
#[test]
fn flexible_structure_modes_on_the_bed() {
    let s = structure(0.5);
    let omega_n = s.derived().omega_n;
    let mut errors = Vec::new();
    for ratio in [20.0, 80.0, 320.0, 1280.0, 5120.0] {
        let g = bed(&s, GroundKind::Winkler, ratio);
        let modes = small_vibrations(&s, &Effects::default(), &g).unwrap();
        assert_eq!(modes.omega.len(), 3);
        let omega_v = ratio * s.derived().p;
        let vertical = modes
            .dominant
            .iter()
            .position(|&d| d == Coordinate::Settlement)
            .unwrap();
        let pair: Vec<usize> = (0..3).filter(|&i| i != vertical).collect();
        let (low, high) = (modes.omega[pair[0]], modes.omega[pair[1]]);
        println!(
            "ω_v/p = {ratio}: ω/p = {:?} ({:?}); lower of the pair / ω_n = {:.9}; K error {:.1e}",
            modes
                .omega
                .iter()
                .map(|w| w / s.derived().p)
                .collect::<Vec<_>>(),
            modes.dominant,
            low / omega_n,
            modes.stiffness_error
        );
        assert!(rel(modes.omega[vertical], omega_v) <= 1e-10);
        assert!(low <= omega_n && omega_n <= high, "{low} {omega_n} {high}");
        if ratio >= 80.0 {
            assert_eq!(modes.dominant[pair[0]], Coordinate::Deformation(0));
        }
        errors.push(1.0 - low / omega_n);
    }
    let orders: Vec<f64> = errors.windows(2).map(|e| (e[0] / e[1]).log(4.0)).collect();
    println!("1 − (lower of the pair) / ω_n: {errors:?}; observed orders in ω_v/p: {orders:.4?}");
    assert!(errors.windows(2).all(|e| e[1] < e[0]), "{errors:?}");
    for q in &orders[2..] {
        assert!((q - 2.0).abs() <= 0.1, "{orders:?}");
    }
    assert!(errors[4] <= 2e-4, "{errors:?}");
}
