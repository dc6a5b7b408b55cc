//! `rocking spectrum` and `rocking batch` end to end: outputs, a real interruption (the process
//! is killed mid-sweep) that resumes to the uninterrupted result, a changed scene refused, and
//! the same cells with 1 and 2 threads.

mod common;

use common::{bin, repo, tmp_path};
use std::path::{Path, PathBuf};
use std::process::Stdio;
use std::time::{Duration, Instant};

fn spectrum(out: &Path, axes: &[&str], extra: &[&str]) -> std::process::Output {
    let mut c = bin();
    c.arg("spectrum")
        .arg(repo().join("scenes/spectra/fig8.toml"))
        .arg("--quiet")
        .arg("--out")
        .arg(out);
    for a in axes {
        c.arg("--axis").arg(a);
    }
    c.args(extra).output().unwrap()
}

const AXES: [&str; 2] = [
    "excitation.omega_p_over_p=1:10:24",
    "excitation.amplitude=1:20:24",
];

#[test]
fn spectrum_writes_classified_cells_and_plots() {
    let out = tmp_path("outputs");
    let o = spectrum(&out, &AXES, &[]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let csv = std::fs::read_to_string(out.join("cells.csv")).unwrap();
    let mut lines = csv.lines();
    assert_eq!(
        lines.next().unwrap(),
        "excitation.omega_p_over_p,excitation.amplitude,class,max_theta_over_alpha,impacts"
    );
    let rows: Vec<Vec<String>> = lines
        .map(|l| l.split(',').map(String::from).collect())
        .collect();
    assert_eq!(rows.len(), 24 * 24);
    let classes: std::collections::BTreeSet<&str> = rows.iter().map(|r| r[2].as_str()).collect();
    // The paper's regions all appear on the Fig-8 structure: no uplift at small amplitudes,
    // survivors, overturning without impact at small ω_p/p, and after one and more impacts.
    for c in [
        "no-uplift",
        "survived",
        "overturned-no-impact",
        "overturned-one-impact",
        "overturned-impacts",
    ] {
        assert!(classes.contains(c), "class {c} missing: {classes:?}");
    }
    for r in &rows {
        let theta: f64 = r[3].parse().unwrap();
        assert!(theta.is_finite() && theta >= 0.0);
        if r[2] == "no-uplift" {
            assert_eq!(theta, 0.0);
        }
    }
    let meta: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("meta.json")).unwrap()).unwrap();
    assert_eq!(meta["cells"], 576);
    // What the run took is in timing.json (meta.json is a function of the study alone).
    let timing: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("timing.json")).unwrap()).unwrap();
    assert!(timing["seconds"].as_f64().unwrap() > 0.0);
    assert_eq!(timing["computed_now"], 576);
    for f in ["spectrum.png", "spectrum.svg"] {
        assert!(std::fs::metadata(out.join(f)).unwrap().len() > 1000, "{f}");
    }
}

#[test]
fn killed_spectrum_resumes_to_the_uninterrupted_result() {
    let whole = tmp_path("whole");
    assert!(spectrum(&whole, &AXES, &["--threads", "2"])
        .status
        .success());
    let reference = std::fs::read_to_string(whole.join("cells.csv")).unwrap();

    let out = tmp_path("killed");
    let mut child = bin()
        .arg("spectrum")
        .arg(repo().join("scenes/spectra/fig8.toml"))
        .args(["--quiet", "--threads", "1", "--out"])
        .arg(&out)
        .args(["--axis", AXES[0], "--axis", AXES[1]])
        .stdout(Stdio::null())
        .spawn()
        .unwrap();
    // Kill it (SIGKILL: no chance to clean up) once some cells are journaled.
    let journal = out.join("cells.journal");
    let start = Instant::now();
    loop {
        let n = std::fs::read_to_string(&journal)
            .map(|t| t.lines().count())
            .unwrap_or(0);
        if n > 40 || start.elapsed() > Duration::from_secs(60) {
            break;
        }
        std::thread::sleep(Duration::from_millis(2));
    }
    child.kill().unwrap();
    child.wait().unwrap();
    let done = std::fs::read_to_string(&journal).unwrap().lines().count() - 1;
    assert!(done > 0 && done < 576, "killed after {done} cells");
    assert!(
        !out.join("cells.csv").exists(),
        "no final output from the killed run"
    );

    let o = spectrum(&out, &AXES, &["--threads", "2"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(
        stdout.contains(&format!("{} computed now", 576 - done)) || stdout.contains("resumed"),
        "{stdout}"
    );
    assert_eq!(
        std::fs::read_to_string(out.join("cells.csv")).unwrap(),
        reference
    );

    // The same directory with a changed scene is refused (exit 2), not mixed.
    let o = spectrum(&out, &AXES, &["--set", "structure.alpha=0.2"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("different sweep"));
}

#[test]
fn one_and_two_threads_give_identical_cells() {
    let (a, b) = (tmp_path("t1"), tmp_path("t2"));
    let axes = [
        "excitation.omega_p_over_p=2:8:10",
        "excitation.amplitude=2:16:10",
    ];
    assert!(spectrum(&a, &axes, &["--threads", "1"]).status.success());
    assert!(spectrum(&b, &axes, &["--threads", "2"]).status.success());
    assert_eq!(
        std::fs::read_to_string(a.join("cells.csv")).unwrap(),
        std::fs::read_to_string(b.join("cells.csv")).unwrap()
    );
}

#[test]
fn bad_axes_are_input_errors() {
    for axis in [
        "excitation.amplitude=1:2",
        "excitation.amplitud=1:2:3",
        "structure.alpha=0.1:2:3",
    ] {
        let o = spectrum(&tmp_path("bad"), &[axis], &[]);
        assert_eq!(
            o.status.code(),
            Some(2),
            "{axis}: {}",
            String::from_utf8_lossy(&o.stderr)
        );
    }
}

#[test]
fn batch_over_records_gives_the_fraction_overturned_per_scale() {
    let out = tmp_path("batch");
    let records = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared/data/ground-motions");
    let records = if records.is_dir() {
        records
    } else {
        repo().join("scenes/records")
    };
    let files: Vec<PathBuf> = std::fs::read_dir(&records)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x.eq_ignore_ascii_case("at2")))
        .take(6)
        .collect();
    let o = bin()
        .arg("batch")
        .arg(repo().join("scenes/wind-turbine-elcentro.toml"))
        .arg("--records")
        .args(&files)
        .args(["--scales", "0.5,4,12", "--quiet", "--out"])
        .arg(&out)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let frag = std::fs::read_to_string(out.join("fragility.csv")).unwrap();
    let fractions: Vec<f64> = frag
        .lines()
        .skip(1)
        .map(|l| l.rsplit(',').next().unwrap().parse().unwrap())
        .collect();
    assert_eq!(fractions.len(), 3);
    assert!(
        fractions.windows(2).all(|w| w[0] <= w[1]),
        "fraction grows with the scale: {fractions:?}"
    );
    let runs = std::fs::read_to_string(out.join("runs.csv")).unwrap();
    assert_eq!(runs.lines().count(), 1 + 3 * files.len());
    assert!(out.join("fragility.png").exists() && out.join("fragility.svg").exists());
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

const RECORD_SCENE: &str =
    "[structure]\nomega_n_over_p = 8.0\nalpha = 0.2\ngamma_mb = 1.0\nr = 2.0\n\n\
    [excitation]\nkind = \"record\"\npath = \"rec.AT2\"\n\n[solver]\nafter_excitation = 5.0\n";

/// A batch resumed after a record file was replaced by a 10× weaker one must not reuse the old
/// results (it reused the journal: "0 runs computed now", still 100 % overturned): the record's
/// contents are in the fingerprint, so the directory is refused as a different sweep, and a fresh
/// run gives the weaker record's answer. The same holds for a spectrum of a record scene.
#[test]
fn a_changed_record_is_not_resumed() {
    let dir = tmp_path("changed-record");
    std::fs::create_dir_all(&dir).unwrap();
    let scene = dir.join("scene.toml");
    std::fs::write(&scene, RECORD_SCENE).unwrap();
    let rec = dir.join("rec.AT2");
    let batch = |out: &str| {
        bin()
            .arg("batch")
            .arg(&scene)
            .arg("--records")
            .arg(&rec)
            .args(["--scales", "1", "--quiet", "--out"])
            .arg(dir.join(out))
            .output()
            .unwrap()
    };
    let fraction = |out: &str| {
        let f = std::fs::read_to_string(dir.join(out).join("fragility.csv")).unwrap();
        f.lines()
            .nth(1)
            .unwrap()
            .rsplit(',')
            .next()
            .unwrap()
            .to_string()
    };
    std::fs::write(&rec, sine_record(1.5)).unwrap();
    let o = batch("out");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert_eq!(fraction("out"), "1", "1.5 g overturns");
    std::fs::write(&rec, sine_record(0.15)).unwrap();
    let o = batch("out");
    let err = String::from_utf8_lossy(&o.stderr);
    eprintln!("resume after the change: exit {:?}: {err}", o.status.code());
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(err.contains("different sweep"), "{err}");
    let o = batch("fresh");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert_eq!(fraction("fresh"), "0", "0.15 g does not overturn");

    // spectrum of the record scene over a scale axis
    let spectrum = |out: &str| {
        bin()
            .arg("spectrum")
            .arg(&scene)
            .args(["--axis", "excitation.scale=1,2", "--quiet", "--out"])
            .arg(dir.join(out))
            .output()
            .unwrap()
    };
    let o = spectrum("spec");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    std::fs::write(&rec, sine_record(1.5)).unwrap();
    let o = spectrum("spec");
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(err.contains("different sweep"), "{err}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// Runs that fail (a singular mass matrix: ω_n/p = 0.3, top mass only, under the shared records
/// at scales 2, 8, 16) are reported as failed everywhere, on the first run and on a resume: in
/// runs.csv (no "overturned = false"), in fragility.csv (counted apart; the fraction is of the runs
/// that finished), in meta.json, and in the exit status. They used to count as survivors, and a
/// resume dropped the warnings.
#[test]
fn failed_runs_are_reported_as_failed_on_first_runs_and_resumes() {
    let records = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared/data/ground-motions");
    if !records.is_dir() {
        eprintln!("SKIPPED: {} is absent", records.display());
        return;
    }
    let dir = tmp_path("failed-runs");
    std::fs::create_dir_all(&dir).unwrap();
    let scene = dir.join("scene.toml");
    std::fs::write(
        &scene,
        "[structure]\nomega_n_over_p = 0.3\nalpha = 0.2\ngamma_mc = 0.0\ngamma_mb = 0.0\nr = 1.0\n\n\
         [excitation]\nkind = \"record\"\npath = \"x.AT2\"\n\n[solver]\nafter_excitation = 5.0\n\
         max_events = 8\n",
    )
    .unwrap();
    std::fs::write(dir.join("x.AT2"), sine_record(0.1)).unwrap();
    let out = dir.join("out");
    let batch = || {
        bin()
            .arg("batch")
            .arg(&scene)
            .arg("--records")
            .arg(&records)
            .args(["--scales", "2,8,16", "--quiet", "--out"])
            .arg(&out)
            .output()
            .unwrap()
    };
    let mut previous: Option<(String, String, serde_json::Value)> = None;
    for pass in ["first run", "resume"] {
        let o = batch();
        let err = String::from_utf8_lossy(&o.stderr);
        let stdout = String::from_utf8_lossy(&o.stdout);
        eprintln!(
            "{pass}: exit {:?}: {}\n{stdout}",
            o.status.code(),
            err.trim()
        );
        assert_eq!(
            o.status.code(),
            Some(1),
            "{pass}: failures give a non-zero exit: {err}"
        );
        assert!(err.contains("runs failed"), "{err}");
        let runs = std::fs::read_to_string(out.join("runs.csv")).unwrap();
        let mut rdr = csv_rows(&runs);
        let header = rdr.remove(0);
        assert_eq!(header[2], "class");
        // Runs stopped by the event guard fail; runs whose mass matrix becomes singular (the
        // massless column's top mass over the pivot) are beyond the model, not failures.
        let failed: Vec<&Vec<String>> = rdr.iter().filter(|r| r[2] == "failed").collect();
        let beyond: Vec<&Vec<String>> = rdr.iter().filter(|r| r[2] == "beyond-model").collect();
        assert!(!failed.is_empty(), "{pass}: this case has failing runs");
        assert!(!beyond.is_empty(), "{pass}: and runs beyond the model");
        for (rows, why) in [(&failed, "events"), (&beyond, "singular")] {
            for r in rows {
                assert!(
                    r[3].is_empty() && r[4].is_empty(),
                    "{pass}: a run without a result has no values: {r:?}"
                );
                assert!(r[6].contains(why), "{pass}: the message is kept: {r:?}");
            }
        }
        let frag = std::fs::read_to_string(out.join("fragility.csv")).unwrap();
        assert_eq!(
            frag.lines().next().unwrap(),
            "scale,runs,failed,beyond_model,completed,overturned,fraction_overturned"
        );
        let (mut total_failed, mut total_beyond) = (0, 0);
        for line in frag.lines().skip(1) {
            let f: Vec<usize> = line
                .split(',')
                .skip(1)
                .take(5)
                .map(|v| v.parse().unwrap())
                .collect();
            let [runs_n, failed_n, beyond_n, completed, over] = f[..] else {
                panic!("{line}")
            };
            assert_eq!(runs_n, 61);
            assert_eq!(completed, runs_n - failed_n - beyond_n, "{line}");
            let frac: f64 = line.rsplit(',').next().unwrap().parse().unwrap();
            assert!(
                (frac - over as f64 / completed as f64).abs() < 1e-12,
                "{line}"
            );
            total_failed += failed_n;
            total_beyond += beyond_n;
        }
        assert_eq!(total_failed, failed.len(), "{pass}: {frag}");
        assert_eq!(total_beyond, beyond.len(), "{pass}: {frag}");
        let meta: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(out.join("meta.json")).unwrap()).unwrap();
        assert_eq!(meta["failed"], failed.len(), "{pass}");
        assert_eq!(
            meta["failures"].as_array().unwrap().len(),
            failed.len(),
            "{pass}"
        );
        assert_eq!(
            meta["beyond_model"].as_array().unwrap().len(),
            beyond.len(),
            "{pass}"
        );
        if let Some((r0, f0, m0)) = &previous {
            let timing: serde_json::Value =
                serde_json::from_str(&std::fs::read_to_string(out.join("timing.json")).unwrap())
                    .unwrap();
            assert_eq!(timing["computed_now"], 0, "the resume computes nothing");
            assert_eq!(&runs, r0, "runs.csv the same on resume");
            assert_eq!(&frag, f0, "fragility.csv the same on resume");
            assert_eq!(meta["failures"], m0["failures"], "failures kept on resume");
            assert_eq!(meta["beyond_model"], m0["beyond_model"], "kept on resume");
        }
        previous = Some((runs, frag, meta));
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// Rows of a CSV text (quoted fields allowed).
fn csv_rows(text: &str) -> Vec<Vec<String>> {
    let mut rows = Vec::new();
    for line in text.lines() {
        let mut row = Vec::new();
        let (mut field, mut quoted, mut chars) = (String::new(), false, line.chars().peekable());
        while let Some(c) = chars.next() {
            match (c, quoted) {
                ('"', true) if chars.peek() == Some(&'"') => {
                    field.push('"');
                    chars.next();
                }
                ('"', _) => quoted = !quoted,
                (',', false) => row.push(std::mem::take(&mut field)),
                _ => field.push(c),
            }
        }
        row.push(field);
        rows.push(row);
    }
    rows
}

/// runs.csv is written by a CSV library: a record named `a,b.AT2` is one quoted field (it shifted
/// the columns).
#[test]
fn runs_csv_quotes_record_names() {
    let dir = tmp_path("quoted");
    std::fs::create_dir_all(&dir).unwrap();
    let scene = dir.join("scene.toml");
    std::fs::write(&scene, RECORD_SCENE).unwrap();
    std::fs::write(dir.join("rec.AT2"), sine_record(0.15)).unwrap();
    let odd = dir.join("a,b \"x\".AT2");
    std::fs::write(&odd, sine_record(0.15)).unwrap();
    let o = bin()
        .arg("batch")
        .arg(&scene)
        .arg("--records")
        .arg(&odd)
        .args(["--scales", "1,2", "--quiet", "--out"])
        .arg(dir.join("out"))
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let runs = std::fs::read_to_string(dir.join("out/runs.csv")).unwrap();
    let rows = csv_rows(&runs);
    assert_eq!(rows.len(), 3, "{runs}");
    for r in &rows {
        assert_eq!(r.len(), rows[0].len(), "same columns in every row: {runs}");
    }
    assert_eq!(rows[1][0], "a,b \"x\".AT2", "{runs}");
    assert_eq!(rows[1][2], "no-uplift", "{runs}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// A sweep validates a ratio to the fixed-base twin as `run` validates `fixed_base_reference`
/// (the same words), and a quantity named twice; it used to run them (ratio 1 in every cell with
/// `uplift = false`, two identical columns).
#[test]
fn a_sweep_refuses_what_run_refuses_of_a_twin_and_a_quantity_twice() {
    let scene = repo().join("scenes/spectra/fig8-forces.toml");
    let axes = ["excitation.omega_p_over_p=2,4", "excitation.amplitude=3,6"];
    for (set, says) in [
        (
            "effects.uplift=false",
            "`base_moment_ratio` in [sweep] report compares the run with its fixed-base twin: it \
             needs the run itself to uplift",
        ),
        (
            "output.forces=false",
            "`base_moment_ratio` in [sweep] report compares the forces of the run and of its \
             fixed-base twin: it needs `forces = true` in [output]",
        ),
        (
            "sweep.report=[\"impacts\", \"base_moment_ratio\", \"base_moment_ratio\"]",
            "names `base_moment_ratio` twice",
        ),
        // The time of the first slip needs a friction coefficient to compare with.
        (
            "sweep.report=[\"first_slip_time\"]",
            "`report` in [sweep] names `first_slip_time`, which a run of this scene does not \
             report (allowed: ",
        ),
        (
            "sweep.report=[\"first_slip_time\"]",
            "; `first_slip_time` needs a friction coefficient ([effects] friction)",
        ),
    ] {
        let out = tmp_path("twin-refused");
        let mut c = bin();
        c.arg("spectrum")
            .arg(&scene)
            .args(["--quiet", "--set", set, "--out"])
            .arg(&out);
        for a in axes {
            c.arg("--axis").arg(a);
        }
        let o = c.output().unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{set}: {err}");
        assert!(err.contains(says), "{set}: {err}");
        assert!(!out.join("cells.csv").exists(), "{set}: nothing run");
    }
}
