//! The Fig. 6 panel α = 0.2, ω_n/p = 2.5 (mass only on top) has cells where the deflection
//! carries the top mass over the pivot and the mass matrix becomes singular. A spectrum has no
//! holes there: those cells are the class `beyond-model`, counted, listed with their messages
//! and drawn, and the command succeeds; a single run of such a cell still reports the error.

mod common;

use common::{repo, rocking, stderr, text, tmp_path};

const SETS: [&str; 4] = [
    "--set",
    "structure.omega_n_over_p=2.5",
    "--set",
    "structure.alpha=0.2",
];

#[test]
fn singular_cells_of_fig6_are_beyond_the_model_not_failures() {
    let out = tmp_path("fig6-beyond");
    let scene = repo().join("scenes/spectra/fig6.toml");
    let mut args = vec![
        "spectrum",
        scene.to_str().unwrap(),
        "--quiet",
        "--out",
        out.to_str().unwrap(),
        "--axis",
        "excitation.omega_p_over_p=3.5:4.3:9",
        "--axis",
        "excitation.amplitude=17:21:9",
    ];
    args.extend_from_slice(&SETS);
    let o = rocking(&args);
    assert!(o.status.success(), "{}", text(&o));
    let stdout = String::from_utf8_lossy(&o.stdout);
    let csv = std::fs::read_to_string(out.join("cells.csv")).unwrap();
    let beyond: Vec<&str> = csv
        .lines()
        .filter(|l| l.contains(",beyond-model,"))
        .collect();
    assert!(beyond.len() >= 10, "{csv}");
    assert!(!csv.contains(",failed,"), "{csv}");
    assert!(
        stdout.contains(&format!("beyond-model: {}", beyond.len())),
        "{stdout}"
    );
    for l in &beyond {
        assert!(l.ends_with(",beyond-model,,"), "no values: {l}");
    }
    let meta: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("meta.json")).unwrap()).unwrap();
    assert_eq!(meta["failures"].as_array().unwrap().len(), 0);
    let listed = meta["beyond_model"].as_array().unwrap();
    assert_eq!(listed.len(), beyond.len());
    for b in listed {
        let m = b["message"].as_str().unwrap();
        assert!(
            m.contains("beyond the model: the mass matrix became singular"),
            "{m}"
        );
        // The stated criterion: the top mass over the pivot, a deflection of several u_cr.
        let u: f64 = m
            .split("u/u_cr = ")
            .nth(1)
            .and_then(|r| r.split(')').next())
            .and_then(|v| v.parse().ok())
            .unwrap_or_else(|| panic!("{m}"));
        assert!(u.abs() > 3.0, "{m}");
    }
    let svg = std::fs::read_to_string(out.join("spectrum.svg")).unwrap();
    assert!(
        svg.contains("beyond the model"),
        "the legend names the class"
    );
    assert!(
        svg.contains("url(#hatch-101010)"),
        "the cells are drawn hatched"
    );

    // The same cell as a single run: the error, exit 1 (a run has no class to fall back on).
    let v = &listed[0]["values"];
    let (wp, a) = (v[0].as_f64().unwrap(), v[1].as_f64().unwrap());
    let (wp, a) = (
        format!("excitation.omega_p_over_p={wp}"),
        format!("excitation.amplitude={a}"),
    );
    let run_out = tmp_path("fig6-beyond-run");
    let mut args = vec![
        "run",
        scene.to_str().unwrap(),
        "--out",
        run_out.to_str().unwrap(),
        "--set",
        &wp,
        "--set",
        &a,
    ];
    args.extend_from_slice(&SETS);
    let r = rocking(&args);
    assert_eq!(r.status.code(), Some(1), "{}", text(&r));
    assert!(
        stderr(&r).contains("the mass matrix became singular"),
        "{}",
        text(&r)
    );
}
