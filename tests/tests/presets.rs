//! The accuracy presets deliver the accuracy docs/accuracy.md and `rocking --help` state for them:
//! the error in max θ/α and in the impact times, against DOP853 at 1e-14 (the study's reference,
//! a decade below `reference`'s own DOP853 1e-13), within the preset's
//! target (fast 1e-3, default 1e-6, accurate 1e-9 with a factor 10 of margin, reference 1e-11).

use rocking::{
    simulate, Accuracy, DampingConvention, Dimensionless, Effects, ImpactModel, Method, Options,
    Preset, Run, Structure,
};
use rocking_motion::{GroundMotion, Ricker, SinePulse};

fn case(name: &str) -> (Structure, SinePulse, Options) {
    let (d, amp, wp, t_end) = match name {
        "fig3" => ((11.9, 0.2, 0.0, 0.0), 1.3, 5.1, 8.0),
        _ => (
            (5.0, 0.1, 1.0, 2.0),
            3.0,
            4.0,
            2.0 * std::f64::consts::PI / 4.0 + 20.0,
        ),
    };
    let dl = Dimensionless {
        omega_n_over_p: d.0,
        alpha: d.1,
        gamma_mc: d.2,
        gamma_mb: d.3,
        gamma_ib: 1.0,
        zeta: 0.005,
        damping: DampingConvention::FixedBase,
    };
    let s = Structure::from_dimensionless(&dl, None).unwrap();
    let o = Options {
        t_end,
        event_log: true,
        impact: ImpactModel::Vvel,
        ..Options::default()
    };
    (s, SinePulse::new(amp * d.1.tan(), wp), o)
}

fn run(name: &str, accuracy: Accuracy) -> Run {
    let (s, pulse, o) = case(name);
    simulate(&s, &pulse, &Effects::default(), &Options { accuracy, ..o }).unwrap()
}

/// The worse of the max θ/α error and the relative error of the impact times.
fn error(run: &Run, reference: &Run) -> f64 {
    let theta = (run.summary.max_theta_over_alpha - reference.summary.max_theta_over_alpha).abs();
    let times = |r: &Run| -> Vec<f64> {
        r.events
            .iter()
            .filter(|e| e.kind == rocking::EventKind::Impact)
            .map(|e| e.time.tau)
            .collect()
    };
    let (a, b) = (times(run), times(reference));
    assert_eq!(a.len(), b.len(), "the same impact sequence");
    let t = a
        .iter()
        .zip(&b)
        .map(|(x, y)| ((x - y) / y).abs())
        .fold(0.0, f64::max);
    theta.max(t)
}

#[test]
fn presets_meet_their_stated_accuracy() {
    for name in ["fig3", "fig5-flexible"] {
        let reference = run(
            name,
            Accuracy {
                method: Method::Dop853,
                tol: 1e-14,
            },
        );
        for (preset, bound) in [
            (Preset::Fast, 1e-3),
            (Preset::Default, 1e-6),
            (Preset::Accurate, 1e-8),
            (Preset::Reference, 1e-11),
        ] {
            let e = error(&run(name, preset.accuracy()), &reference);
            eprintln!("{name} {preset:?}: error {e:.1e} (bound {bound:.0e})");
            assert!(e <= bound, "{name} {preset:?}: error {e:e} > {bound:e}");
        }
    }
}

/// A Ricker pulse that hides its Taylor series, as a motion without one would (a smooth motion
/// of finite resolution that does not implement `accel_series`).
struct WithoutSeries(Ricker);

impl GroundMotion for WithoutSeries {
    fn accel(&self, t: f64) -> f64 {
        self.0.accel(t)
    }
    fn end(&self) -> f64 {
        self.0.end()
    }
    fn next_kink(&self, t: f64) -> Option<f64> {
        self.0.next_kink(t)
    }
    fn accel_left(&self, t: f64) -> f64 {
        self.0.accel_left(t)
    }
    fn accel_right(&self, t: f64) -> f64 {
        self.0.accel_right(t)
    }
    fn resolution(&self) -> f64 {
        self.0.resolution()
    }
}

/// `accurate` is the Taylor method where the excitation has a Taylor series (every kind of
/// rocking-motion has one), and DOP853 at 3e-11 (the study's tolerance for the same error) where
/// it has none: on such a motion it runs and meets the preset's bound.
#[test]
fn accurate_falls_back_to_dop853_without_a_taylor_series() {
    let (s, sine, o) = case("fig3");
    let pulse = Ricker::symmetric(2.0 * 0.2f64.tan(), 4.0);
    for taylor in [
        Preset::Accurate.accuracy_for(&sine),
        Preset::Accurate.accuracy_for(&pulse),
    ] {
        assert_eq!(
            taylor,
            Accuracy {
                method: Method::Taylor,
                tol: 3e-11
            }
        );
    }
    let ricker = WithoutSeries(pulse);
    let fallback = Preset::Accurate.accuracy_for(&ricker);
    assert_eq!(
        fallback,
        Accuracy {
            method: Method::Dop853,
            tol: 3e-11
        }
    );
    // The preset's plain accuracy is refused on that motion with a message naming the way out;
    // the fallback runs, and agrees with the reference setting.
    let err = simulate(
        &s,
        &ricker,
        &Effects::default(),
        &Options {
            accuracy: Preset::Accurate.accuracy(),
            ..o
        },
    )
    .unwrap_err()
    .to_string();
    assert!(err.contains("accuracy_for"), "{err}");
    let run_at =
        |accuracy| simulate(&s, &ricker, &Effects::default(), &Options { accuracy, ..o }).unwrap();
    let (a, r) = (
        run_at(fallback),
        run_at(Accuracy {
            method: Method::Dop853,
            tol: 1e-13,
        }),
    );
    assert!(r.summary.impacts > 0, "the Ricker pulse rocks the block");
    let e = error(&a, &r);
    assert!(e <= 1e-8, "accurate on a Ricker pulse: error {e:e}");
}

/// max θ/α and the impact times of `scenes/many-impacts.toml` (ARL360 × 8, 836 impacts) at an
/// accuracy, with the record's scale moved by `ulps` units in the last place.
fn many_impacts(accuracy: Accuracy, ulps: i64) -> (f64, Vec<f64>) {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes/many-impacts.toml");
    let scale = f64::from_bits((8.0f64.to_bits() as i64 + ulps) as u64);
    let sc = rocking_scene::scene::load(&path, &[format!("excitation.scale={scale:?}")]).unwrap();
    let m = rocking_scene::setup::build(&sc).unwrap();
    let o = Options {
        accuracy,
        event_log: true,
        forces: false,
        ..m.options
    };
    let run = simulate(&m.structure, &m.excitation, &m.effects, &o).unwrap();
    let times = run
        .events
        .iter()
        .filter(|e| e.kind == rocking::EventKind::Impact)
        .map(|e| e.time.tau)
        .collect();
    (run.summary.max_theta_over_alpha, times)
}

/// On a long record with hundreds of impacts the answer is determined only as far as the input's
/// rounding allows: one ulp of the record's scale moves max θ/α by about 2e-8 here. `reference`
/// (DOP853, whose event states come from its own steps, `rocking_ode::events::refine`) agrees
/// with the converged Taylor answers within that band; it was 1.1e-5 off when its impacts
/// started from the dense output. The presets' errors on this class are those docs/accuracy.md
/// states (the study's `many-impacts` case, class `many-impacts`): `accurate` within 1e-6; `default` (1.8e-4 here) misses its target of 1e-6 on this
/// class and is held to `fast`'s, 1e-3.
#[test]
fn reference_is_converged_on_a_long_record_with_hundreds_of_impacts() {
    let taylor = |tol| Accuracy {
        method: Method::Taylor,
        tol,
    };
    // The converged answer and the band the input's rounding leaves it.
    let tight: Vec<(f64, Vec<f64>)> = [(1e-12, 0), (1e-13, 0), (1e-14, 0), (1e-14, 1), (1e-14, -1)]
        .into_iter()
        .map(|(tol, ulps)| many_impacts(taylor(tol), ulps))
        .collect();
    let thetas: Vec<f64> = tight.iter().map(|t| t.0).collect();
    let (lo, hi) = thetas
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| {
            (a.min(x), b.max(x))
        });
    let centre = 0.5 * (lo + hi);
    eprintln!("Taylor 1e-12..1e-14 and ±1 ulp of scale: max θ/α {lo:.12}..{hi:.12}");
    assert!(
        hi - lo < 2e-7,
        "the tight runs agree to the input's rounding: {thetas:?}"
    );
    let impacts = tight[2].1.len();
    assert!(impacts > 800, "{impacts} impacts");
    let error = |(theta, times): (f64, Vec<f64>)| {
        assert_eq!(times.len(), impacts, "the same impact sequence");
        let t = times
            .iter()
            .zip(&tight[2].1)
            .map(|(x, y)| ((x - y) / y).abs())
            .fold(0.0, f64::max);
        (theta - centre).abs().max(t)
    };
    for (preset, bound) in [
        (Preset::Reference, 3e-7),
        (Preset::Accurate, 1e-6),
        (Preset::Default, 1e-3),
        (Preset::Fast, 1e-3),
    ] {
        let e = error(many_impacts(preset.accuracy(), 0));
        eprintln!("many-impacts {preset:?}: error {e:.1e} (bound {bound:.0e})");
        assert!(e <= bound, "{preset:?}: error {e:e} > {bound:e}");
    }
}
