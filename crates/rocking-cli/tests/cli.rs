//! The `rocking` binary end to end: example scenes, overrides, bad input, outputs.

mod common;

use common::{rocking, scenes, stderr, tmp};
use std::path::{Path, PathBuf};
use std::process::Output;

use serde_json::Value;

/// `rocking run SCENE --json --out DIR [extra]`: the parsed summary.
fn run_json(scene: &Path, out: &Path, extra: &[&str]) -> Value {
    let mut args = vec![
        "run",
        scene.to_str().unwrap(),
        "--json",
        "--out",
        out.to_str().unwrap(),
    ];
    args.extend_from_slice(extra);
    let o = rocking(&args);
    assert!(
        o.status.success(),
        "{}: exit {:?}: {}",
        scene.display(),
        o.status.code(),
        stderr(&o)
    );
    let text = String::from_utf8(o.stdout).unwrap();
    assert_eq!(text.trim().lines().count(), 1, "one JSON object: {text}");
    serde_json::from_str(&text).unwrap()
}

const KEYS: &[&str] = &[
    "max_theta_over_alpha",
    "max_u_over_ucr",
    "overturned",
    "overturn_time",
    "impacts",
    "significant_impacts",
    "first_uplift_time",
    "first_impact_time",
    "energy_balance_residual",
    "kernel_variant",
    "solver_stats",
];

#[test]
fn every_example_scene_runs() {
    let mut names: Vec<PathBuf> = std::fs::read_dir(scenes())
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    names.sort();
    assert!(names.len() >= 8, "{names:?}");
    for scene in &names {
        let stem = scene.file_stem().unwrap().to_str().unwrap();
        // Plots are checked in `outputs_are_written`; skip them here to keep the suite fast.
        let s = run_json(scene, &tmp(stem), &["--set", "output.plots=false"]);
        for k in KEYS {
            assert!(s.get(k).is_some(), "{stem}: missing `{k}` in {s}");
        }
        let max = s["max_theta_over_alpha"].as_f64().unwrap();
        assert!(max.is_finite() && max >= 0.0, "{stem}: {max}");
        assert!(s["max_u_over_ucr"].as_f64().unwrap().is_finite());
        assert!(s["solver_stats"]["steps"].as_u64().unwrap() > 0);
        if let Some(r) = s["energy_balance_residual"].as_f64() {
            assert!(r.abs() < 1e-4, "{stem}: energy residual {r}");
        }
        let overturned = s["overturned"].as_bool().unwrap();
        assert_eq!(overturned, s["overturn_time"].is_number(), "{stem}");
        match stem {
            "fig3-vvel" | "fig3-adjex" => {
                let t = s["first_impact_time"].as_f64().unwrap();
                assert!((t - 0.9).abs() < 0.05, "{stem}: first impact τ = {t}");
                assert!(!overturned);
                assert_eq!(s["kernel_variant"], "point_mass");
            }
            "fig10-overturns" => assert!(overturned),
            "fig10-survives" | "fig5-flexible" | "fig5-stiff" | "wind-turbine-elcentro" => {
                assert!(!overturned, "{stem}");
                assert!(s["impacts"].as_u64().unwrap() >= 1, "{stem} rocks");
            }
            "housner-free" => {
                assert_eq!(s["kernel_variant"], "rigid");
                assert!((max - 0.5).abs() < 1e-9);
                assert!(s["first_impact_time_s"].is_number(), "R given: seconds");
            }
            _ => {}
        }
    }
}

#[test]
fn outputs_are_written() {
    let out = tmp("outputs");
    let o = rocking(&[
        "run",
        scenes().join("fig3-vvel.toml").to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let human = String::from_utf8_lossy(&o.stdout);
    assert!(
        human.contains("max θ/α") && human.contains("summary.json"),
        "{human}"
    );
    let s: Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(s["kernel_variant"], "point_mass");
    let h = std::fs::read_to_string(out.join("history.csv")).unwrap();
    assert!(
        h.starts_with("tau,t_s,theta_over_alpha,u_over_ucr,"),
        "{}",
        &h[..80]
    );
    assert!(h.lines().count() > 1000);
    // No NaN anywhere; "inf" only as the required friction where the vertical reaction is not
    // positive (no friction holds there: the lift-off warning).
    assert!(!h.contains("NaN"));
    let header: Vec<&str> = h.lines().next().unwrap().split(',').collect();
    let col = |name: &str| header.iter().position(|c| *c == name).unwrap();
    let (friction, vertical) = (col("required_friction"), col("vertical_reaction_over_w"));
    for line in h.lines().skip(1) {
        let cells: Vec<&str> = line.split(',').collect();
        for (i, c) in cells.iter().enumerate() {
            if c.contains("inf") {
                let v: f64 = cells[vertical].parse().unwrap();
                assert!(i == friction && *c == "inf" && v <= 0.0, "{line}");
            }
        }
    }
    let e = std::fs::read_to_string(out.join("events.csv")).unwrap();
    assert!(e.starts_with("tau,t_s,kind,branch,"));
    assert!(e.contains(",impact,") && e.contains(",uplift,"));
    for f in ["plot.png", "plot.svg"] {
        let len = std::fs::metadata(out.join(f)).unwrap().len();
        assert!(len > 10_000, "{f}: {len} bytes");
    }
    let png = std::fs::read(out.join("plot.png")).unwrap();
    assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n");
    let svg = std::fs::read_to_string(out.join("plot.svg")).unwrap();
    assert!(svg.contains("<svg") && svg.contains("θ/α"));
    // No temporary files left behind.
    let leftovers: Vec<_> = std::fs::read_dir(&out)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.contains(".tmp"))
        .collect();
    assert!(leftovers.is_empty(), "{leftovers:?}");
}

#[test]
fn summary_only_runs_write_only_the_summary() {
    let out = tmp("summary-only");
    let scene = scenes().join("fig5-stiff.toml");
    let s = run_json(
        &scene,
        &out,
        &[
            "--set",
            "output.plots=false",
            "--set",
            "output.events=false",
            "--set",
            "output.history=none",
            "--set",
            "effects.energy=false",
        ],
    );
    assert!(s["energy_balance_residual"].is_null());
    let files: Vec<_> = std::fs::read_dir(&out).unwrap().collect();
    assert_eq!(files.len(), 1, "{files:?}");
    assert!(out.join("summary.json").exists());
}

#[test]
fn overrides_change_the_result() {
    let scene = scenes().join("fig3-vvel.toml");
    let off = ["--set", "output.plots=false"];
    let base = run_json(&scene, &tmp("set-base"), &off);
    let stronger = run_json(
        &scene,
        &tmp("set-strong"),
        &[
            "--set",
            "output.plots=false",
            "--set",
            "excitation.amplitude=1.6",
        ],
    );
    let (a, b) = (
        base["max_theta_over_alpha"].as_f64().unwrap(),
        stronger["max_theta_over_alpha"].as_f64().unwrap(),
    );
    assert!(b > a, "{a} -> {b}");
    let rigid = run_json(
        &scene,
        &tmp("set-rigid"),
        &[
            "--set",
            "output.plots=false",
            "--set",
            "effects.flexibility=false",
            "--set",
            "effects.impact={ restitution = 0.9 }",
        ],
    );
    assert_eq!(rigid["kernel_variant"], "rigid");
    // Other pulse kinds through --set.
    for kind in ["cosine-pulse", "ricker"] {
        let s = run_json(
            &scene,
            &tmp(kind),
            &[
                "--set",
                "output.plots=false",
                "--set",
                &format!("excitation.kind={kind}"),
            ],
        );
        assert!(s["excitation"].as_str().unwrap().starts_with(kind));
    }
    // Bad overrides: exit 2 with the key named.
    for (arg, needle) in [
        ("structure.alpha=2.0", "alpha"),
        ("structure.alhpa=0.1", "did you mean `alpha`"),
        ("structure.alpha=nan", "alpha"),
        ("structure.zeta=-0.1", "zeta"),
        ("excitation.amplitude=big", "amplitude"),
        ("excitation.kind=sine", "did you mean \"sine-pulse\""),
        ("effects.impact=bounce", "impact"),
        ("solver.accuracy=fastest", "accuracy"),
        ("noequals", "KEY.PATH=VALUE"),
        ("structure.alpha.x=1", "not a table"),
    ] {
        let o = rocking(&["run", scene.to_str().unwrap(), "--json", "--set", arg]);
        assert_eq!(o.status.code(), Some(2), "--set {arg}: {}", stderr(&o));
        let err = stderr(&o);
        assert!(err.contains(needle), "--set {arg}: {err}");
        assert!(o.stdout.is_empty());
    }
}

const GOOD: &str = r#"
[structure]
omega_n_over_p = 11.9
alpha = 0.2
zeta = 0.005

[excitation]
kind = "sine-pulse"
omega_p_over_p = 5.1
amplitude = 1.3
"#;

/// Writes a scene made from GOOD by replacing `from` with `to`, runs `check`, returns the output.
fn check_variant(dir: &Path, name: &str, text: &str) -> Output {
    let path = dir.join(format!("{name}.toml"));
    std::fs::write(&path, text).unwrap();
    rocking(&["check", path.to_str().unwrap()])
}

#[test]
fn bad_scenes_exit_2_naming_file_line_and_key() {
    let dir = tmp("bad");
    std::fs::write(
        dir.join("malformed.AT2"),
        "title\nevent\nunits\nNPTS= 3, DT= .01\n0.1 x 0.3\n",
    )
    .unwrap();
    std::fs::write(
        dir.join("good.AT2"),
        "title\nevent\nunits\nNPTS= 3, DT= .01\n0.1 0.2 0.3\n",
    )
    .unwrap();
    let cases: &[(&str, &str, &str, &[&str])] = &[
        (
            "typo",
            "omega_n_over_p = 11.9",
            "omega_n_ovr_p = 11.9",
            &[
                "typo.toml:3:",
                "unknown key `omega_n_ovr_p` in [structure]",
                "did you mean `omega_n_over_p`?",
            ],
        ),
        (
            "wrongtype",
            "alpha = 0.2",
            "alpha = \"steep\"",
            &["wrongtype.toml:4:", "alpha", "string"],
        ),
        (
            "zerofreq",
            "omega_p_over_p = 5.1",
            "omega_p_over_p = 0",
            &["zerofreq.toml:9:", "omega_p_over_p", "> 0"],
        ),
        (
            "negzeta",
            "zeta = 0.005",
            "zeta = -0.1",
            &["negzeta.toml:5:", "zeta", "0 <= zeta < 1"],
        ),
        (
            "steep",
            "alpha = 0.2",
            "alpha = 1.6",
            &["steep.toml:4:", "alpha", "pi/2"],
        ),
        (
            "nan",
            "alpha = 0.2",
            "alpha = nan",
            &["nan.toml:4:", "alpha", "NaN"],
        ),
        (
            "inf",
            "amplitude = 1.3",
            "amplitude = inf",
            &["inf.toml:10:", "amplitude"],
        ),
        (
            "missing",
            "alpha = 0.2\n",
            "",
            &["missing.toml:2:", "missing key `alpha`"],
        ),
        (
            "syntax",
            "alpha = 0.2",
            "alpha = ",
            &["syntax.toml:4:", "invalid TOML"],
        ),
        (
            "badkind",
            "kind = \"sine-pulse\"",
            "kind = \"ricker\"\nshape = \"round\"",
            &["badkind.toml:9:", "shape"],
        ),
        (
            "norecord",
            "kind = \"sine-pulse\"\nomega_p_over_p = 5.1\namplitude = 1.3",
            "kind = \"record\"\npath = \"nowhere.AT2\"",
            &["norecord.toml:", "nowhere.AT2", "cannot read"],
        ),
        (
            "noscale",
            "kind = \"sine-pulse\"\nomega_p_over_p = 5.1\namplitude = 1.3",
            "kind = \"record\"\npath = \"good.AT2\"",
            &["noscale.toml:", "`r` (m) or `p` (1/s)"],
        ),
    ];
    for (name, from, to, needles) in cases {
        assert!(GOOD.contains(from), "{name}");
        let o = check_variant(&dir, name, &GOOD.replacen(from, to, 1));
        assert_eq!(o.status.code(), Some(2), "{name}: {}", stderr(&o));
        let err = stderr(&o);
        for n in *needles {
            assert!(err.contains(n), "{name}: `{n}` not in: {err}");
        }
    }
    // A malformed record: the record's file and line, and the scene's.
    let text = GOOD
        .replace("zeta = 0.005", "zeta = 0.005\nr = 2.0")
        .replace(
            "kind = \"sine-pulse\"\nomega_p_over_p = 5.1\namplitude = 1.3",
            "kind = \"record\"\npath = \"malformed.AT2\"",
        );
    let o = check_variant(&dir, "malformed", &text);
    assert_eq!(o.status.code(), Some(2));
    let err = stderr(&o);
    assert!(
        err.contains("malformed.toml:10:") && err.contains("malformed.AT2:5"),
        "{err}"
    );
    // Missing scene file and clap usage errors.
    let o = rocking(&["run", dir.join("absent.toml").to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("absent.toml"));
    assert_eq!(rocking(&["run"]).status.code(), Some(2));
    assert_eq!(rocking(&["frobnicate"]).status.code(), Some(2));
}

#[test]
fn check_prints_variant_reasons_and_derived_quantities() {
    let o = rocking(&[
        "check",
        scenes().join("fig5-flexible.toml").to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let out = String::from_utf8_lossy(&o.stdout);
    for needle in [
        "kernel variant: full",
        "because all masses present",
        "ω_n",
        "ω_up",
        "u_cr",
        "θ_cr",
        "E_ref",
        "static uplift threshold",
        // The Fig. 5 flexible column's weight and uplift moment (R = g = m = 1: W = 1 + γ_mc +
        // γ_mb = 4, B = R sin α), and its elastic moment at static uplift (docs/design-forces.md).
        "W          = 4.000000e0, W B = 3.993337e-1",
        "M_el       = 0.880",
    ] {
        assert!(out.contains(needle), "`{needle}` not in:\n{out}");
    }
    let o = rocking(&[
        "check",
        scenes().join("fig5-flexible.toml").to_str().unwrap(),
        "--set",
        "effects.column_mass=false",
        "--set",
        "effects.base_mass=false",
        "--json",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let v: Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(v["kernel_variant"], "point_mass");
    let reasons = v["variant_reasons"].as_array().unwrap();
    assert!(reasons
        .iter()
        .any(|r| r.as_str().unwrap().contains("m_c = false")));
    let thr = v["derived"]["static_uplift_over_g_tan_alpha"]
        .as_f64()
        .unwrap();
    assert!(thr > 0.5 && thr < 1.5, "{thr}");
    // One coordinate: the frequency lists are [omega_n] and [omega_up] of eq (18), by the
    // generic eigenproblem of rocking_kernels::modes, and the uplifted ratio is eq (19)'s.
    let d = &v["derived"];
    for (list, one) in [
        ("fixed_base_frequencies", "omega_n"),
        ("uplifted_frequencies", "omega_up"),
        ("uplifted_damping_ratios", "zeta_uplifted"),
        ("fixed_base_damping_ratios", "zeta_fixed_base"),
    ] {
        let w = d[list].as_array().unwrap();
        assert_eq!(w.len(), 1, "{list}: {w:?}");
        let (w, one) = (w[0].as_f64().unwrap(), d[one].as_f64().unwrap());
        assert!((w / one - 1.0).abs() < 1e-12, "{list}: {w} vs {one}");
    }
}

/// `zeta = [..]`, one fixed-base damping ratio per mode: `check --json` reads each mode's ratio
/// back from the damping matrix the kernels run with, a run's summary lists them, the run differs
/// from one with the first ratio for every mode, and `--set structure.zeta=` with one ratio
/// replaces the list (as a sweep over `structure.zeta` does).
#[test]
fn damping_ratios_per_mode_from_the_scene() {
    let dir = tmp("zeta-per-mode");
    let scene = scenes().join("wind-turbine-elcentro.toml");
    let scene = scene.to_str().unwrap();
    let model = "structure.model=\"cantilever_modes3\"";
    let list = "structure.zeta=[0.01, 0.03, 0.06]";
    let o = rocking(&["check", scene, "--json", "--set", model, "--set", list]);
    assert!(o.status.success(), "{}", stderr(&o));
    let v: Value = serde_json::from_slice(&o.stdout).unwrap();
    let d = &v["derived"];
    let read: Vec<f64> = serde_json::from_value(d["fixed_base_damping_ratios"].clone()).unwrap();
    for (r, z) in read.iter().zip([0.01, 0.03, 0.06]) {
        assert!((r / z - 1.0).abs() < 1e-12, "{read:?}");
    }
    assert_eq!(read.len(), 3);
    assert_eq!(d["zeta_fixed_base"], 0.01);
    assert_eq!(
        d["zeta_fixed_base_per_mode"],
        serde_json::json!([0.01, 0.03, 0.06])
    );
    let run = |name: &str, zeta: &str| {
        let set = [
            "--set",
            model,
            "--set",
            zeta,
            "--set",
            "solver.after_excitation=0",
        ];
        run_json(Path::new(scene), &dir.join(name), &set)
    };
    let graded = run("graded", list);
    let first = run("first", "structure.zeta=0.01");
    assert_eq!(
        graded["derived"]["zeta_fixed_base_per_mode"],
        d["zeta_fixed_base_per_mode"]
    );
    assert!(first["derived"].get("zeta_fixed_base_per_mode").is_none());
    assert_ne!(graded["max_u_over_ucr"], first["max_u_over_ucr"]);
}

#[test]
fn mp_pulse_and_physical_si_pulse() {
    let dir = tmp("kinds");
    let mp = r#"
[structure]
omega_n_over_p = 11.9
alpha = 0.2
[excitation]
kind = "mp-pulse"
omega_p_over_p = 4.0
velocity_amplitude = 0.8
gamma = 2.0
"#;
    std::fs::write(dir.join("mp.toml"), mp).unwrap();
    let s = run_json(&dir.join("mp.toml"), &dir.join("mp"), &[]);
    assert!(s["excitation"].as_str().unwrap().starts_with("mp-pulse"));
    let si = r#"
[structure]
h = 10.0
b = 1.0
ei = 1e9
m = 1e4
zeta = 0.02
[excitation]
kind = "sine-pulse"
omega_p = 6.0
amplitude_g = 0.3
"#;
    std::fs::write(dir.join("si.toml"), si).unwrap();
    let s = run_json(&dir.join("si.toml"), &dir.join("si"), &[]);
    assert!(s["first_uplift_time_s"].is_number(), "{s}");
}

/// A one-sine record of 0.3 g written in g, in cm/s² and in m/s² (header units), and an
/// unlabelled one with `units` stated in the scene, give the same run; before units were read,
/// the cm/s² file reported a PGA of 294 g and overturned.
#[test]
fn record_units_are_read_and_converted() {
    let dir = tmp("record-units");
    let samples = |k: f64| -> String {
        (0..=40)
            .map(|i| {
                format!(
                    "{:.12e}",
                    k * 0.3 * (2.0 * std::f64::consts::PI * i as f64 / 40.0).sin()
                )
            })
            .collect::<Vec<_>>()
            .join("\n")
    };
    let g0 = 9.80665;
    let files = [
        (
            "g.AT2",
            "ACCELERATION TIME HISTORY IN UNITS OF G",
            1.0,
            None,
        ),
        (
            "cm.AT2",
            "ACCELERATION TIME HISTORY IN UNITS OF CM/SEC/SEC",
            100.0 * g0,
            None,
        ),
        (
            "m.AT2",
            "ACCELERATION TIME HISTORY IN UNITS OF M/S/S",
            g0,
            None,
        ),
        ("bare.AT2", "no units here", 100.0 * g0, Some("cm/s2")),
    ];
    let mut results = Vec::new();
    for (name, units, k, stated) in files {
        std::fs::write(
            dir.join(name),
            format!("T\nE\n{units}\nNPTS= 41, DT= .01 SEC\n{}\n", samples(k)),
        )
        .unwrap();
        let units_line = stated
            .map(|u| format!("units = \"{u}\"\n"))
            .unwrap_or_default();
        let scene = dir.join(format!("{name}.toml"));
        std::fs::write(
            &scene,
            format!(
                "[structure]\nomega_n_over_p = 8.0\nalpha = 0.2\ngamma_mb = 1.0\nr = 2.0\n\n\
                 [excitation]\nkind = \"record\"\npath = \"{name}\"\n{units_line}\n\
                 [solver]\nafter_excitation = 5.0\n"
            ),
        )
        .unwrap();
        let o = rocking(&["check", scene.to_str().unwrap(), "--json"]);
        assert!(o.status.success(), "{name}: {}", stderr(&o));
        let check: Value = serde_json::from_slice(&o.stdout).unwrap();
        let desc = check["excitation"].as_str().unwrap().to_string();
        assert!(desc.contains("PGA = 0.3000 g"), "{name}: {desc}");
        let v = run_json(&scene, &dir.join(format!("out-{name}")), &[]);
        eprintln!(
            "{name}: {desc}; max θ/α = {}, overturned = {}",
            v["max_theta_over_alpha"], v["overturned"]
        );
        results.push((name, v));
    }
    let reference = results[0].1["max_theta_over_alpha"].as_f64().unwrap();
    assert!(reference > 0.0 && results[0].1["overturned"] == false);
    for (name, v) in &results[1..] {
        let x = v["max_theta_over_alpha"].as_f64().unwrap();
        assert!(
            (x - reference).abs() <= 1e-6 * reference,
            "{name}: max θ/α {x}, in g {reference}"
        );
        assert_eq!(v["overturned"], results[0].1["overturned"], "{name}");
    }
}

/// PEER velocity and displacement histories are refused with exit 2 naming the file.
#[test]
fn velocity_and_displacement_records_are_refused() {
    let dir = tmp("record-velocity");
    let body = "T\nE\nVELOCITY TIME HISTORY IN UNITS OF CM/SEC\nNPTS= 3, DT= .01 SEC\n0 1 0\n";
    let accel = "T\nE\nACCELERATION TIME HISTORY IN UNITS OF G\nNPTS= 3, DT= .01 SEC\n0 1 0\n";
    for (name, text) in [("v.AT2", body), ("rec.VT2", accel), ("rec.DT2", accel)] {
        std::fs::write(dir.join(name), text).unwrap();
        let scene = dir.join(format!("{name}.toml"));
        std::fs::write(
            &scene,
            format!(
                "[structure]\nomega_n_over_p = 8.0\nalpha = 0.2\nr = 2.0\n\n\
                 [excitation]\nkind = \"record\"\npath = \"{name}\"\n"
            ),
        )
        .unwrap();
        let o = rocking(&[
            "run",
            scene.to_str().unwrap(),
            "--out",
            dir.join("out").to_str().unwrap(),
        ]);
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{name}: {err}");
        assert!(
            err.contains(name) && err.contains("acceleration"),
            "{name}: {err}"
        );
        assert!(!dir.join("out").exists(), "{name}: nothing written");
    }
}

/// The example models: `rocking check` reports the scene's model, its own parameters and its own
/// derived quantities; `rocking models` lists every model; a key of another model is refused with
/// a pointer to that model (exit 2).
#[test]
fn example_models_check_and_models_listing() {
    let o = rocking(&[
        "check",
        scenes().join("added-mass.toml").to_str().unwrap(),
        "--json",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let v: Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(v["model"], "cubic_platform");
    assert_eq!(v["kernel_variant"], "added_mass");
    assert_eq!(v["params"]["m_a"], 0.5);
    assert_eq!(v["params"]["eta_a"], 0.25);
    // EI is set so that this model's own ω_n/p is the scene's.
    let wn = v["derived"]["omega_n_over_p"].as_f64().unwrap();
    assert!((wn - 5.0).abs() < 1e-12, "{wn}");
    let o = rocking(&[
        "check",
        scenes().join("cosine-shape.toml").to_str().unwrap(),
        "--json",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let v: Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(v["model"], "cosine");
    assert_eq!(v["kernel_variant"], "cosine_shape");
    let wn = v["derived"]["omega_n_over_p"].as_f64().unwrap();
    assert!((wn - 5.0).abs() < 1e-12, "{wn}");

    let o = rocking(&["models"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let out = String::from_utf8_lossy(&o.stdout);
    for needle in [
        "model \"cubic\"",
        "model \"cosine\"",
        "model \"cubic_platform\"",
        "m_a",
        "eta_a",
        "point_mass",
    ] {
        assert!(out.contains(needle), "`{needle}` not in:\n{out}");
    }

    let o = rocking(&[
        "check",
        scenes().join("fig3-vvel.toml").to_str().unwrap(),
        "--set",
        "structure.m_a=0.5",
    ]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("belongs to model `cubic_platform`"),
        "{}",
        stderr(&o)
    );
    let o = rocking(&[
        "check",
        scenes().join("fig3-vvel.toml").to_str().unwrap(),
        "--set",
        "structure.model=cosin",
    ]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("did you mean \"cosine\""),
        "{}",
        stderr(&o)
    );
    // A model of several deformation coordinates runs (its column's first mode sets ω_n) where
    // the column has a mass; without one (Fig. 3's point mass) its mass matrix is singular.
    let s = run_json(
        &scenes().join("fig5-flexible.toml"),
        &tmp("polynomial2"),
        &[
            "--set",
            "structure.model=polynomial2",
            "--set",
            "output.plots=false",
        ],
    );
    assert_eq!(s["kernel_variant"], "polynomial2");
    let o = rocking(&[
        "check",
        scenes().join("fig3-vvel.toml").to_str().unwrap(),
        "--set",
        "structure.model=polynomial2",
    ]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("gamma_mc"), "{}", stderr(&o));
    let o = rocking(&[
        "check",
        scenes().join("cosine-shape.toml").to_str().unwrap(),
        "--set",
        "effects.flexibility=false",
    ]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("has no rigid variant"),
        "{}",
        stderr(&o)
    );
}

/// A result says what produced it (issue 30, item 17): summary.json names the model, its
/// parameters and the `--set` overrides, as `rocking check --json` does (the old summary named
/// none of them).
#[test]
fn the_summary_names_the_model_its_parameters_and_the_overrides() {
    let scene = scenes().join("fig5-flexible.toml");
    let s = scene.to_str().unwrap();
    let sets = [
        "--set",
        "structure.alpha=0.15",
        "--set",
        "solver.after_excitation=2.0",
    ];
    let out = tmp("summary-provenance");
    let mut args = vec!["run", s, "--out", out.to_str().unwrap()];
    args.extend(sets);
    let o = rocking(&args);
    assert!(o.status.success(), "{}", stderr(&o));
    let summary: Value =
        serde_json::from_slice(&std::fs::read(out.join("summary.json")).unwrap()).unwrap();
    let mut args = vec!["check", s, "--json"];
    args.extend(sets);
    let o = rocking(&args);
    assert!(o.status.success(), "{}", stderr(&o));
    let checked: Value = serde_json::from_slice(&o.stdout).unwrap();
    for key in ["model", "params", "overrides"] {
        assert!(!summary[key].is_null(), "summary.json has no `{key}`");
        assert_eq!(summary[key], checked[key], "`{key}`: run and check agree");
    }
    assert_eq!(
        summary["overrides"],
        serde_json::json!(["structure.alpha=0.15", "solver.after_excitation=2.0"])
    );
    assert_eq!(summary["model"], "cubic");
}

/// The fixed-base twin of a tilted start is the structure held upright from t = 0 (issue 47):
/// the free-rocking block's twin carries its weight and nothing else, where it used to rock
/// with the run (ratios of 1).
#[test]
fn the_twin_of_a_tilted_start_starts_upright() {
    let s = run_json(
        &scenes().join("housner-free.toml"),
        &tmp("twin-tilted"),
        &[
            "--set",
            "output.fixed_base_reference=true",
            "--set",
            "output.plots=false",
        ],
    );
    assert!(s["impacts"].as_u64().unwrap() > 100, "{s}");
    let fb = &s["fixed_base"];
    assert_eq!(fb["max_base_moment_over_wb"], 0.0, "{fb}");
    assert_eq!(fb["max_base_shear_over_w"], 0.0, "{fb}");
    assert_eq!(fb["min_vertical_reaction_over_w"], 1.0, "{fb}");
}

/// `[output] forces = false` drops the force columns from history.csv as it drops the force
/// keys from the summary (issue 47: the history kept them, with values).
#[test]
fn without_forces_history_and_summary_agree() {
    let scene = scenes().join("fig3-vvel.toml");
    for (forces, present) in [("true", true), ("false", false)] {
        let out = tmp(&format!("forces-{forces}"));
        let set = format!("output.forces={forces}");
        let s = run_json(
            &scene,
            &out,
            &["--set", &set, "--set", "output.plots=false"],
        );
        let header = std::fs::read_to_string(out.join("history.csv"))
            .unwrap()
            .lines()
            .next()
            .unwrap()
            .to_string();
        for (column, key) in [
            ("base_moment_over_wb", "max_base_moment_over_wb"),
            ("base_shear_over_w", "max_base_shear_over_w"),
            ("required_friction", "max_required_friction"),
            ("vertical_reaction_over_w", "min_vertical_reaction_over_w"),
        ] {
            assert_eq!(
                header.split(',').any(|c| c == column),
                present,
                "forces = {forces}: {header}"
            );
            assert_eq!(s.get(key).is_some(), present, "forces = {forces}: {key}");
        }
    }
}

/// The rows of a CSV file as fields (no quoted commas in these tables).
fn csv_table(path: &Path) -> Vec<Vec<String>> {
    std::fs::read_to_string(path)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
        .lines()
        .map(|l| l.split(',').map(str::to_string).collect())
        .collect()
}

/// The column `name` of a CSV table with a header row.
fn column<'a>(rows: &'a [Vec<String>], name: &str) -> Vec<&'a str> {
    let k = rows[0]
        .iter()
        .position(|c| c == name)
        .unwrap_or_else(|| panic!("no column `{name}`: {:?}", rows[0]));
    rows[1..].iter().map(|r| r[k].as_str()).collect()
}

/// Issue 47 item 5: once R_v falls below zero the friction the base needs is unbounded. Fig. 3
/// (VVEL) falls to R_v/W = −0.38: its summary holds `"inf"` (JSON has no infinity; the history
/// writes `inf` alike) with the time of the first lift-off, the warning says unbounded, and a
/// sweep that reports the quantity writes `inf` in cells.csv, never an empty field or NaN.
#[test]
fn an_unbounded_required_friction_is_inf_in_the_summary_and_in_cells_csv() {
    let fig3 = scenes().join("fig3-vvel.toml");
    let s = common::summary(fig3.to_str().unwrap(), &[]);
    assert_eq!(s["max_required_friction"], "inf", "{s}");
    assert!(s["min_vertical_reaction_over_w"].as_f64().unwrap() < 0.0);
    assert!(s["first_lift_off_time"].as_f64().unwrap() > 0.0);
    let warnings = s["warnings"].to_string();
    assert!(
        warnings.contains("max required friction unbounded"),
        "{warnings}"
    );
    // A one-axis spectrum over the amplitude: the paper's 1.30 lifts off, 0.3 never uplifts.
    let out = tmp("friction-spectrum");
    let o = rocking(&[
        "spectrum",
        fig3.to_str().unwrap(),
        "--quiet",
        "--axis",
        "excitation.amplitude=0.3,1.3",
        "--set",
        "sweep.report=[\"max_required_friction\"]",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let rows = csv_table(&out.join("cells.csv"));
    let friction = column(&rows, "max_required_friction");
    let small: f64 = friction[0].parse().unwrap();
    assert!(small.is_finite() && small > 0.0, "{rows:?}");
    assert_eq!(friction[1], "inf", "{rows:?}");
}

/// A physical scene reports its force maxima in SI to a sweep, its own and its fixed-base
/// twin's (issue 47 item 13), with the values of the single run's summary.json (and the
/// required friction, finite here, as the summary has it).
#[test]
fn a_physical_batch_reports_the_si_maxima_of_the_run_and_of_its_twin() {
    let turbine = scenes().join("wind-turbine-elcentro.toml");
    let s = common::summary(
        turbine.to_str().unwrap(),
        &["output.fixed_base_reference=true"],
    );
    let fb = &s["fixed_base"];
    for key in ["max_base_moment_nm", "max_base_shear_n"] {
        let (run, twin) = (s[key].as_f64().unwrap(), fb[key].as_f64().unwrap());
        assert!(run > 1e6 && twin > 1e6, "{key}: {run}, {twin}");
    }
    let wb =
        s["max_base_moment_nm"].as_f64().unwrap() / s["max_base_moment_over_wb"].as_f64().unwrap();
    let fixed = fb["max_base_moment_nm"].as_f64().unwrap()
        / fb["max_base_moment_over_wb"].as_f64().unwrap();
    assert!(
        (wb / fixed - 1.0).abs() < 1e-12,
        "the same W B: {wb}, {fixed}"
    );
    let out = tmp("si-batch");
    let o = rocking(&[
        "batch",
        turbine.to_str().unwrap(),
        "--quiet",
        "--records",
        scenes().join("records/elCentro.AT2").to_str().unwrap(),
        "--scales",
        "3",
        "--set",
        "sweep.report=[\"max_base_moment_nm\", \"fixed_base.max_base_moment_nm\", \
         \"max_required_friction\"]",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let rows = csv_table(&out.join("runs.csv"));
    let value = |name: &str| -> f64 { column(&rows, name)[0].parse().unwrap() };
    assert_eq!(
        value("max_base_moment_nm"),
        s["max_base_moment_nm"].as_f64().unwrap()
    );
    assert_eq!(
        value("fixed_base.max_base_moment_nm"),
        fb["max_base_moment_nm"].as_f64().unwrap()
    );
    assert_eq!(
        value("max_required_friction"),
        s["max_required_friction"].as_f64().unwrap()
    );
}

/// A dimensionless scene has no SI maxima: `report` naming one is refused before anything runs
/// (exit 2, naming `report`), as any quantity a run does not report.
#[test]
fn a_dimensionless_sweep_refuses_the_si_maxima() {
    let scene = scenes().join("spectra/fig8-forces.toml");
    for key in ["max_base_moment_nm", "fixed_base.max_base_shear_n"] {
        let out = tmp("si-refused");
        let set = format!("sweep.report=[\"{key}\"]");
        let o = rocking(&[
            "spectrum",
            scene.to_str().unwrap(),
            "--quiet",
            "--axis",
            "excitation.omega_p_over_p=2,4",
            "--axis",
            "excitation.amplitude=3,6",
            "--set",
            &set,
            "--out",
            out.to_str().unwrap(),
        ]);
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{key}: {err}");
        assert!(
            err.contains(&format!("`report` in [sweep] names `{key}`")),
            "{key}: {err}"
        );
        assert!(
            err.contains(&format!("; `{key}` needs physical units")),
            "{key}: {err}"
        );
        assert!(!out.join("cells.csv").exists(), "{key}: nothing run");
    }
}

/// A chattering run (restitution 1 on the flexible Fig. 5 column, 200 τ after the pulse: about
/// 450,000 impacts) draws its plot: one impact marker per pixel. It used to fail after the whole
/// run with exit 1, "SVG data parsing failed cause nodes limit reached".
#[test]
fn a_chattering_run_draws_its_plot() {
    let out = tmp("chatter");
    let o = rocking(&[
        "run",
        scenes().join("fig5-flexible.toml").to_str().unwrap(),
        "--set",
        "effects.impact={restitution=1.0}",
        "--set",
        "solver.after_excitation=200",
        "--set",
        "output.events=false",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let s: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert!(s["impacts"].as_u64().unwrap() > 100_000, "{}", s["impacts"]);
    let svg = std::fs::read_to_string(out.join("plot.svg")).unwrap();
    // Markers are drawn per pixel, not per impact: far fewer elements than impacts.
    let elements = svg.matches('<').count();
    assert!(elements < 100_000, "{elements} SVG elements");
    assert!(out.join("plot.png").is_file());
}
