//! Text values on sweep axes (`--axis structure.model=cubic,cantilever_modes2`): each cell is the
//! scene run with those texts set, cells.csv holds the texts, and shards of such a sweep merge to
//! the same bytes as one run; a resume recomputes nothing.

mod common;

use common::{repo, rocking, summary, text, tmp, tmp_path};
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

/// The rows of a CSV file written by the command (no quoted fields in these tests).
fn rows(path: &Path) -> Vec<Vec<String>> {
    std::fs::read_to_string(path)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
        .lines()
        .map(|l| l.split(',').map(String::from).collect())
        .collect()
}

/// The same table without its column `k`.
fn without(rows: &[Vec<String>], k: usize) -> Vec<Vec<String>> {
    rows.iter()
        .map(|r| {
            let mut r = r.clone();
            r.remove(k);
            r
        })
        .collect()
}

/// A sweep's outputs whose bytes must not depend on how it was run (whole, resumed, sharded).
const SPECTRUM_FILES: [&str; 2] = ["cells.csv", "meta.json"];
const BATCH_FILES: [&str; 3] = ["runs.csv", "fragility.csv", "meta.json"];

fn assert_same_files(a: &Path, b: &Path, files: &[&str], what: &str) {
    for f in files {
        assert_eq!(
            std::fs::read(a.join(f)).unwrap_or_else(|e| panic!("{what}: {f}: {e}")),
            std::fs::read(b.join(f)).unwrap(),
            "{what}: {f} differs"
        );
    }
}

/// Runs `rocking ARGS` and fails the test on a non-zero exit.
fn ok(args: &[&str]) {
    let o = rocking(args);
    assert!(o.status.success(), "{args:?}: {}", text(&o));
}

/// Resumes a sweep from an interrupted journal: `whole`'s journal cut after its header and
/// `keep` cells, plus a torn line (a kill mid-write), alone in `dir`; then `run(dir)` must write
/// the bytes of the uninterrupted run and compute only the missing cells.
fn resume_from_a_cut_journal(
    whole: &Path,
    dir: &Path,
    keep: usize,
    files: &[&str],
    run: impl Fn(&Path) -> std::process::Output,
) {
    let journal = std::fs::read_to_string(whole.join("cells.journal")).unwrap();
    let lines: Vec<&str> = journal.lines().collect();
    let total = lines.len() - 1;
    assert!(keep < total, "{keep} of {total} cells");
    let torn = &lines[keep + 1][..lines[keep + 1].len() / 2];
    std::fs::create_dir_all(dir).unwrap();
    std::fs::write(
        dir.join("cells.journal"),
        format!("{}\n{torn}", lines[..=keep].join("\n")),
    )
    .unwrap();
    let o = run(dir);
    assert!(o.status.success(), "{}", text(&o));
    let timing: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("timing.json")).unwrap()).unwrap();
    assert_eq!(
        timing["computed_now"],
        total - keep,
        "only the lost cells run"
    );
    assert_same_files(whole, dir, files, "resumed");
}

/// A Fig-8 spectrum with its design forces (`[sweep] report`) over the model as a text axis and
/// a 2 x 3 pulse grid equals, value for value (the same decimal text, so the same f64 bits), the
/// two spectra run apart with `--set structure.model=...`; two shards merge to its bytes and a
/// cut journal resumes to them.
#[test]
fn a_text_axis_spectrum_equals_the_separate_spectra_to_the_last_bit() {
    let scene = repo()
        .join("scenes/spectra/fig8-forces.toml")
        .display()
        .to_string();
    let grid = [
        "--axis",
        "excitation.omega_p_over_p=2,6",
        "--axis",
        "excitation.amplitude=1.5,3,6",
    ];
    let run = |out: &Path, first: &[&str], extra: &[&str]| {
        let mut args = vec![
            "spectrum",
            &scene,
            "--quiet",
            "--out",
            out.to_str().unwrap(),
        ];
        args.extend_from_slice(first);
        args.extend_from_slice(&grid);
        args.extend_from_slice(extra);
        rocking(&args)
    };
    let model_axis = ["--axis", "structure.model=cubic,cantilever_modes2"];
    let whole = tmp_path("spec-model-axis");
    let o = run(&whole, &model_axis, &[]);
    assert!(o.status.success(), "{}", text(&o));
    let swept = rows(&whole.join("cells.csv"));
    assert_eq!(swept.len(), 1 + 2 * 6);
    assert_eq!(swept[0][0], "structure.model");
    for (m, model) in ["cubic", "cantilever_modes2"].into_iter().enumerate() {
        let apart = tmp_path(&format!("spec-apart-{model}"));
        let set = format!("structure.model={model}");
        let o = run(&apart, &[], &["--set", &set]);
        assert!(o.status.success(), "{}", text(&o));
        let alone = rows(&apart.join("cells.csv"));
        let mine: Vec<Vec<String>> = swept[1 + 6 * m..1 + 6 * (m + 1)].to_vec();
        assert!(mine.iter().all(|r| r[0] == model), "{mine:?}");
        assert_eq!(without(&swept[..1], 0), alone[..1], "the header");
        assert_eq!(without(&mine, 0), alone[1..], "{model}: cell for cell");
    }
    // The axis is not ignored: the two models give different base moments somewhere.
    let k = swept[0]
        .iter()
        .position(|c| c == "max_base_moment_over_wb")
        .unwrap();
    assert!(
        (0..6).any(|i| swept[1 + i][k] != swept[7 + i][k]),
        "{swept:?}"
    );
    let (s0, s1, merged) = (
        tmp_path("spec-model-s0"),
        tmp_path("spec-model-s1"),
        tmp_path("spec-model-merged"),
    );
    for (dir, shard) in [(&s0, "0/2"), (&s1, "1/2")] {
        let o = run(dir, &model_axis, &["--shard", shard]);
        assert!(o.status.success(), "{}", text(&o));
    }
    ok(&[
        "merge",
        merged.to_str().unwrap(),
        s0.to_str().unwrap(),
        s1.to_str().unwrap(),
    ]);
    assert_same_files(&whole, &merged, &SPECTRUM_FILES, "merged");
    resume_from_a_cut_journal(
        &whole,
        &tmp_path("spec-model-resumed"),
        5,
        &SPECTRUM_FILES,
        |dir| run(dir, &model_axis, &["--threads", "1"]),
    );
}

/// A one-sine record of amplitude `a` g and period 2 s (header units g).
fn sine_record(a: f64) -> String {
    let s: Vec<String> = (0..=40)
        .map(|i| {
            format!(
                "{:.10e}",
                a * (2.0 * std::f64::consts::PI * i as f64 / 40.0).sin()
            )
        })
        .collect();
    format!(
        "T\nE\nACCELERATION TIME HISTORY IN UNITS OF G\nNPTS= 41, DT= .05 SEC\n{}\n",
        s.join("\n")
    )
}

/// A record scene reporting its base moment, so that the forces are compared too.
const RECORD_SCENE: &str = "[structure]\nomega_n_over_p = 8.0\nalpha = 0.2\ngamma_mb = 1.0\n\
    gamma_mc = 1.0\nr = 2.0\n\n[excitation]\nkind = \"record\"\npath = \"a.AT2\"\n\n\
    [solver]\nafter_excitation = 5.0\n\n[sweep]\nreport = [\"max_base_moment_over_wb\"]\n";

/// `rocking batch --axis structure.model=cubic,cantilever_modes2` over two records at two scales
/// equals, value for value, the two batches run apart with `--set structure.model=...`: runs.csv
/// row for row and fragility.csv (per model and scale) row for row, the model's column removed;
/// shards merge to its bytes, a cut journal resumes to them, and the Python-free outputs name the
/// axis (meta.json). Without --axis the tables have no axis column.
#[test]
fn a_text_axis_batch_equals_the_separate_batches_to_the_last_bit() {
    let dir = tmp("batch-model-axis");
    let scene = dir.join("scene.toml");
    std::fs::write(&scene, RECORD_SCENE).unwrap();
    // 0.3 g rocks and survives at scale 1, 0.6 g overturns at scale 2: the classes differ.
    std::fs::write(dir.join("a.AT2"), sine_record(0.3)).unwrap();
    std::fs::write(dir.join("b.AT2"), sine_record(0.6)).unwrap();
    let (scene, a, b) = (
        scene.display().to_string(),
        dir.join("a.AT2").display().to_string(),
        dir.join("b.AT2").display().to_string(),
    );
    let run = |out: &Path, extra: &[&str]| {
        let mut args = vec![
            "batch",
            &scene,
            "--records",
            &a,
            &b,
            "--scales",
            "1,2",
            "--quiet",
            "--out",
            out.to_str().unwrap(),
        ];
        args.extend_from_slice(extra);
        rocking(&args)
    };
    let model_axis = ["--axis", "structure.model=cubic,cantilever_modes2"];
    let whole = dir.join("whole");
    let o = run(&whole, &model_axis);
    assert!(o.status.success(), "{}", text(&o));
    let runs = rows(&whole.join("runs.csv"));
    let frag = rows(&whole.join("fragility.csv"));
    assert_eq!(
        runs[0][..4],
        ["record", "scale", "structure.model", "class"],
        "{runs:?}"
    );
    assert_eq!(frag[0][..2], ["structure.model", "scale"], "{frag:?}");
    assert_eq!((runs.len(), frag.len()), (1 + 2 * 2 * 2, 1 + 2 * 2));
    for model in ["cubic", "cantilever_modes2"] {
        let apart = dir.join(format!("apart-{model}"));
        let set = format!("structure.model={model}");
        let o = run(&apart, &["--set", &set]);
        assert!(o.status.success(), "{}", text(&o));
        let alone = rows(&apart.join("runs.csv"));
        assert_eq!(alone[0][2], "class", "no axis column without --axis");
        let mine: Vec<Vec<String>> = runs[1..]
            .iter()
            .filter(|r| r[2] == model)
            .cloned()
            .collect();
        assert_eq!(mine.len(), 4);
        assert_eq!(without(&runs[..1], 2), alone[..1], "runs.csv header");
        assert_eq!(
            without(&mine, 2),
            alone[1..],
            "{model}: runs.csv row for row"
        );
        let alone = rows(&apart.join("fragility.csv"));
        let mine: Vec<Vec<String>> = frag[1..]
            .iter()
            .filter(|r| r[0] == model)
            .cloned()
            .collect();
        assert_eq!(without(&frag[..1], 0), alone[..1], "fragility.csv header");
        assert_eq!(without(&mine, 0), alone[1..], "{model}: fragility.csv");
    }
    let k = runs[0]
        .iter()
        .position(|c| c == "max_base_moment_over_wb")
        .unwrap();
    assert!(
        runs[1..].iter().any(|r| !r[k].is_empty()),
        "some run has a base moment: {runs:?}"
    );
    let meta: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(whole.join("meta.json")).unwrap()).unwrap();
    assert_eq!(
        meta["axes"],
        serde_json::json!([{"key": "structure.model", "values": ["cubic", "cantilever_modes2"]}])
    );
    let (s0, s1, s2, merged) = (
        dir.join("s0"),
        dir.join("s1"),
        dir.join("s2"),
        dir.join("merged"),
    );
    for (d, shard) in [(&s0, "0/3"), (&s1, "1/3"), (&s2, "2/3")] {
        let mut extra = model_axis.to_vec();
        extra.extend(["--shard", shard]);
        let o = run(d, &extra);
        assert!(o.status.success(), "{}", text(&o));
    }
    ok(&[
        "merge",
        merged.to_str().unwrap(),
        s0.to_str().unwrap(),
        s1.to_str().unwrap(),
        s2.to_str().unwrap(),
    ]);
    assert_same_files(&whole, &merged, &BATCH_FILES, "merged");
    resume_from_a_cut_journal(&whole, &dir.join("resumed"), 3, &BATCH_FILES, |d| {
        let mut extra = model_axis.to_vec();
        extra.extend(["--threads", "1"]);
        run(d, &extra)
    });
}
