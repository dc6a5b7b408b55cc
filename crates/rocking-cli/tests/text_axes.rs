//! Text values on sweep axes (`--axis structure.model=cubic,cantilever_modes2`): each cell is the
//! scene run with those texts set, cells.csv holds the texts, and shards of such a sweep merge to
//! the same bytes as one run; a resume recomputes nothing.

mod common;

use common::{repo, rocking, summary, text, tmp_path};
use std::path::Path;

const AXES: [&str; 4] = [
    "--axis",
    "structure.model=cubic,cantilever_modes2",
    "--axis",
    "effects.impact=vvel,adjex,housner",
];

fn scene() -> String {
    repo()
        .join("scenes/fig5-flexible.toml")
        .display()
        .to_string()
}

fn spectrum(out: &Path, extra: &[&str]) -> std::process::Output {
    let scene = scene();
    let mut args = vec![
        "spectrum",
        &scene,
        "--quiet",
        "--out",
        out.to_str().unwrap(),
    ];
    args.extend_from_slice(&AXES);
    args.extend_from_slice(extra);
    rocking(&args)
}

#[test]
fn a_text_axis_sweep_equals_the_separate_runs_cell_for_cell() {
    let out = tmp_path("text-axes");
    let o = spectrum(&out, &[]);
    assert!(o.status.success(), "{}", text(&o));
    let csv = std::fs::read_to_string(out.join("cells.csv")).unwrap();
    let rows: Vec<Vec<&str>> = csv.lines().map(|l| l.split(',').collect()).collect();
    assert_eq!(
        rows[0],
        [
            "structure.model",
            "effects.impact",
            "class",
            "max_theta_over_alpha",
            "impacts"
        ]
    );
    assert_eq!(rows.len(), 7, "{csv}");
    let scene = scene();
    for r in &rows[1..] {
        let (model, impact) = (
            format!("structure.model={}", r[0]),
            format!("effects.impact={}", r[1]),
        );
        let s = summary(&scene, &[&model, &impact]);
        assert_eq!(s["model"], r[0], "{r:?}");
        let max: f64 = r[3].parse().unwrap();
        assert_eq!(max, s["max_theta_over_alpha"].as_f64().unwrap(), "{r:?}");
        assert_eq!(r[4], s["impacts"].to_string(), "{r:?}");
    }
    // The three impact models give three answers on one model: the axis is not ignored.
    let cubic: std::collections::BTreeSet<&str> = rows[1..4].iter().map(|r| r[3]).collect();
    assert_eq!(cubic.len(), 3, "{csv}");
    let meta: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("meta.json")).unwrap()).unwrap();
    assert_eq!(
        meta["axes"][0]["values"],
        serde_json::json!(["cubic", "cantilever_modes2"])
    );

    // A resume recomputes nothing; shards merge to the same bytes.
    let again = spectrum(&out, &[]);
    assert!(again.status.success(), "{}", text(&again));
    let timing: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("timing.json")).unwrap()).unwrap();
    assert_eq!(timing["computed_now"], 0);
    let (s0, s1, merged) = (
        tmp_path("text-s0"),
        tmp_path("text-s1"),
        tmp_path("text-merged"),
    );
    for (dir, shard) in [(&s0, "0/2"), (&s1, "1/2")] {
        let o = spectrum(dir, &["--shard", shard]);
        assert!(o.status.success(), "{}", text(&o));
    }
    let m = rocking(&[
        "merge",
        merged.to_str().unwrap(),
        s0.to_str().unwrap(),
        s1.to_str().unwrap(),
    ]);
    assert!(m.status.success(), "{}", text(&m));
    for f in ["cells.csv", "meta.json"] {
        assert_eq!(
            std::fs::read(merged.join(f)).unwrap(),
            std::fs::read(out.join(f)).unwrap(),
            "{f}"
        );
    }
}

#[test]
fn a_text_the_key_does_not_take_is_refused_before_any_cell_runs() {
    let out = tmp_path("text-axes-bad");
    let scene = scene();
    let o = rocking(&[
        "spectrum",
        &scene,
        "--quiet",
        "--out",
        out.to_str().unwrap(),
        "--axis",
        "structure.model=cubic,no_such_model",
    ]);
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    assert!(text(&o).contains("no_such_model"), "{}", text(&o));
    assert!(!out.join("cells.csv").exists());
}
