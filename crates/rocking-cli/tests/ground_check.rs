//! `rocking check` on compliant ground (issue 44, docs/ground.md): the statics and the
//! small-amplitude frequencies it prints are the library's (`rocking::ground_statics`,
//! `rocking::ground_modes`, computed here from the same scene, not re-typed) and meet the closed
//! forms v0 = W / K_v and k_θ = (2/3) k B³ of the Winkler bed.

mod common;

use common::{rocking, text};
use rocking::ground_modes::small_vibrations;
use rocking::ground_statics::statics;
use serde_json::Value;

const SCENE: &str = "scenes/ground-winkler.toml";

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

/// `rocking check SCENE --json`: the `derived.ground` object.
fn printed_ground() -> Value {
    let o = rocking(&["check", SCENE, "--json"]);
    assert!(o.status.success(), "{}", text(&o));
    let v: Value = serde_json::from_slice(&o.stdout).expect("check --json prints JSON");
    v["derived"]["ground"].clone()
}

#[test]
fn check_prints_the_ground_statics_and_frequencies_of_the_library() {
    let g = printed_ground();
    let n = |key: &str| {
        g[key]
            .as_f64()
            .unwrap_or_else(|| panic!("no number {key} in {g}"))
    };
    let path = common::repo().join(SCENE);
    let scene = rocking_scene::scene::load(&path, &[]).unwrap();
    let m = rocking_scene::setup::build(&scene).unwrap();
    let ground = m.ground.expect("the scene has a compliant ground");
    let w = m.structure.static_uplift().weight;
    let wb = m.structure.static_uplift().moment;
    let p = m.structure.derived().p;
    let st = statics(&ground, w);
    let modes = small_vibrations(&m.structure, &m.effects, &ground).unwrap();

    // The library's numbers, as printed (serde_json's parser may differ from Rust's by one
    // unit in the last place: 4 ulp relative).
    let ulp = 4.0 * f64::EPSILON;
    for (key, lib) in [
        ("k_v", st.k_v),
        ("settlement", st.settlement),
        ("rotational_stiffness", st.k_rot),
        ("rotational_stiffness_over_wb", st.k_rot / wb),
        ("lift_off_theta", st.lift_off.theta),
        ("lift_off_moment", st.lift_off.moment),
        ("lift_off_moment_over_wb", st.lift_off.moment / wb),
        ("mean_pressure", st.mean_pressure),
    ] {
        assert!(
            rel(n(key), lib) <= ulp,
            "{key}: printed {} library {lib}",
            n(key)
        );
    }
    let printed: Vec<f64> = g["frequencies_over_p"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect();
    assert_eq!(printed.len(), modes.omega.len());
    for (a, b) in printed.iter().zip(&modes.omega) {
        assert!(rel(*a, b / p) <= ulp, "ω/p printed {a} library {}", b / p);
    }
    let names: Vec<&str> = g["frequency_modes"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_str().unwrap())
        .collect();
    let lib_names: Vec<String> = modes.dominant.iter().map(|c| c.name()).collect();
    assert_eq!(names, lib_names);
    assert!(names.contains(&"rocking") && names.contains(&"vertical") && names.contains(&"u1"));
    let largest = modes.omega.iter().copied().fold(f64::MIN, f64::max);
    assert!(rel(n("omega_max_over_p"), largest / p) <= ulp);
    assert!(n("stiffness_error") <= 1e-9, "{}", n("stiffness_error"));

    // The closed forms: v0 = W / K_v, K_v = 2 k B, k_θ = (2/3) k B³; ω_v/p as the scene gives
    // it (the ground's k is the scene's ω_v/p turned into a bed stiffness by the library).
    let (k, b) = (ground.k, ground.b);
    let e_v0 = rel(n("settlement"), w / (2.0 * k * b));
    let e_k = rel(n("rotational_stiffness"), 2.0 / 3.0 * k * b.powi(3));
    let text = std::fs::read_to_string(&path).unwrap();
    let spec: toml::Table = text.parse().unwrap();
    let given = spec["ground"]["omega_v_over_p"].as_float().unwrap();
    let e_w = rel(n("omega_v_over_p"), given);
    println!(
        "check: v0 {:.6e} (closed form error {e_v0:.1e}), k_θ {:.6e} = {:.4} W B/rad (error \
         {e_k:.1e}), ω_v/p {:.6} (scene {given}, error {e_w:.1e}), ω/p {printed:?} {names:?}",
        n("settlement"),
        n("rotational_stiffness"),
        n("rotational_stiffness_over_wb"),
        n("omega_v_over_p"),
    );
    assert!(e_v0 <= 1e-14, "{e_v0:e}");
    assert!(e_k <= 1e-14, "{e_k:e}");
    assert!(e_w <= 1e-14, "{e_w:e}");
}

/// The text form names the same quantities (one line each).
#[test]
fn check_prints_the_ground_in_text() {
    let o = rocking(&["check", SCENE]);
    assert!(o.status.success(), "{}", text(&o));
    let out = String::from_utf8_lossy(&o.stdout);
    for line in [
        "compliant ground (winkler",
        "K_v ",
        "v0 ",
        "k_θ ",
        "lift-off ",
        "small-amplitude frequencies on the ground, ω/p: rocking ",
        "stiffness ratio ω_max/p = ",
    ] {
        assert!(out.contains(line), "no `{line}` in\n{out}");
    }
    assert!(!out.contains("NaN"), "{out}");
}
