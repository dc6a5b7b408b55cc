//! The defects of an adversarial pass (issue 11): huge values, closed or full stdout, sizes that
//! would exhaust memory, hangs, output directories, messages. Each test asserts the property that
//! failed before the fix.

mod common;

use common::{repo, rocking, stderr, tmp};
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};

/// Exit 2 with one message that contains every needle, no panic (101) and no abort (134).
fn assert_input_error(o: &Output, needles: &[&str], label: &str) {
    let err = stderr(o);
    eprintln!("{label}: exit {:?}: {}", o.status.code(), err.trim());
    assert_eq!(o.status.code(), Some(2), "{label}: {err}");
    assert_eq!(err.trim().lines().count(), 1, "{label}: one message: {err}");
    assert!(!err.contains("panicked"), "{label}: {err}");
    for n in needles {
        assert!(err.contains(n), "{label}: `{n}` not in: {err}");
    }
}

const PHYSICAL: &str = "[structure]\nh = 30.0\nb = 3.0\nei = 2.0e10\nm = 1.0e5\nm_c = 5.0e4\n\
    m_b = 1.0e5\nzeta = 0.01\ng = 9.81\n\n[excitation]\nkind = \"sine-pulse\"\nomega_p = 3.0\n\
    amplitude_g = 0.3\n";

/// Products of accepted values that overflow are refused naming the key the user wrote (they
/// panicked with exit 101), and the number is printed in short exponent form.
#[test]
fn huge_values_are_input_errors_naming_the_key() {
    let dir = tmp("huge");
    let scene = dir.join("physical.toml");
    std::fs::write(&scene, PHYSICAL).unwrap();
    let s = scene.to_str().unwrap();
    let record = dir.join("rec.AT2");
    std::fs::write(
        &record,
        "T\nE\nACCELERATION IN UNITS OF G\nNPTS= 3, DT= .01\n0 0.3 0\n",
    )
    .unwrap();
    let cases: [(&[&str], &[&str]); 4] = [
        (
            &["check", s, "--set", "structure.h=1e308"],
            &["`h`", "1e308"],
        ),
        (
            &["check", s, "--set", "excitation.amplitude_g=1e308"],
            &["amplitude_g", "1e308"],
        ),
        (
            &[
                "check",
                s,
                "--set",
                "excitation={ kind = \"record\", path = \"rec.AT2\", scale = 1e308 }",
            ],
            &["scale", "1e308"],
        ),
        (
            &["check", s, "--set", "structure.ei=1e308"],
            &["`ei`", "1e308"],
        ),
    ];
    for (args, needles) in cases {
        let o = rocking(args);
        assert_input_error(&o, needles, args[3]);
        assert!(
            !stderr(&o).contains("00000000000000000000"),
            "short numbers: {}",
            stderr(&o)
        );
    }
}

/// A closed (`| true`) or full (`> /dev/full`) standard output is an error (exit 1 with a
/// message), not a panic (exit 101).
#[test]
fn closed_or_full_stdout_is_an_error_not_a_panic() {
    let dir = tmp("stdout");
    let scene = repo().join("scenes/fig5-stiff.toml");
    // EPIPE: the reader is gone before rocking writes.
    let mut child = Command::new(env!("CARGO_BIN_EXE_rocking"))
        .args(["check", scene.to_str().unwrap(), "--json"])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    drop(child.stdout.take());
    let o = child.wait_with_output().unwrap();
    let err = stderr(&o);
    assert_ne!(o.status.code(), Some(101), "{err}");
    assert!(!err.contains("panicked"), "{err}");
    if !o.status.success() {
        assert!(err.contains("standard output"), "{err}");
    }
    if Path::new("/dev/full").exists() {
        let full = std::fs::OpenOptions::new()
            .write(true)
            .open("/dev/full")
            .unwrap();
        let o = Command::new(env!("CARGO_BIN_EXE_rocking"))
            .args(["run", scene.to_str().unwrap(), "--json", "--out"])
            .arg(dir.join("out"))
            .stdout(full)
            .output()
            .unwrap();
        let err = stderr(&o);
        eprintln!("/dev/full: exit {:?}: {}", o.status.code(), err.trim());
        assert_eq!(o.status.code(), Some(1), "{err}");
        assert!(
            err.contains("standard output") && !err.contains("panicked"),
            "{err}"
        );
    }
}

const SCENE: &str = "[structure]\nomega_n_over_p = 11.9\nalpha = 0.2\nr = 2.0\n\n\
    [excitation]\nkind = \"sine-pulse\"\nomega_p_over_p = 5.1\namplitude = 1.3\n\n\
    [solver]\nafter_excitation = 5.0\n";

fn scene_file(dir: &Path, text: &str) -> PathBuf {
    let p = dir.join("scene.toml");
    std::fs::write(&p, text).unwrap();
    p
}

/// Sizes that aborted with exit 134 (memory) are bounded and refused up front, with the limit in
/// the message.
#[test]
fn sizes_are_bounded_up_front() {
    let dir = tmp("sizes");
    let scene = scene_file(&dir, SCENE);
    let s = scene.to_str().unwrap();
    let out = dir.join("out");
    let o = out.to_str().unwrap();
    let o1 = rocking(&[
        "run",
        s,
        "--out",
        o,
        "--set",
        "output.plots=true",
        "--set",
        "solver.after_excitation=1e6",
    ]);
    assert_input_error(&o1, &["plots", "at most 5e6"], "plots over 1e6 τ");
    let o2 = rocking(&[
        "spectrum",
        s,
        "--quiet",
        "--out",
        o,
        "--axis",
        "excitation.amplitude=1:2:1e11",
    ]);
    assert_input_error(&o2, &["at most 100000"], "axis of 1e11 values");
    let o3 = rocking(&[
        "spectrum",
        s,
        "--quiet",
        "--out",
        o,
        "--axis",
        "excitation.amplitude=1:2:100000000000",
    ]);
    assert_input_error(&o3, &["at most 100000"], "axis count 1e11");
    let mut five = vec!["spectrum", s, "--quiet", "--out", o];
    let axes = [
        "excitation.amplitude=1:2:10000",
        "excitation.omega_p_over_p=1:2:10000",
        "structure.alpha=0.1:0.2:10000",
        "structure.zeta=0:0.1:10000",
        "structure.omega_n_over_p=5:10:10000",
    ];
    for a in &axes {
        five.extend(["--axis", a]);
    }
    let o4 = rocking(&five);
    assert_input_error(&o4, &["at most 1000000 cells"], "five axes of 1e4 values");
    assert!(!out.join("cells.journal").exists(), "nothing written");
}

/// `--threads 100000` is refused with its limit. The spectrum with an axis
/// `excitation.amplitude=1,1e308` wrote its cells and then spun in the plot forever: the
/// amplitude is now refused up front (a peak ground acceleration above 1e4 g); and an axis whose
/// values a plot cannot show (here `structure.r` up to 1e20) gives its cells and a note instead of
/// the plot.
#[test]
fn no_hangs_on_huge_axes_or_thread_counts() {
    let dir = tmp("hangs");
    let scene = scene_file(&dir, SCENE);
    let s = scene.to_str().unwrap();
    let out = dir.join("out");
    let o = out.to_str().unwrap();
    let t = rocking(&["spectrum", s, "--quiet", "--out", o, "--threads", "100000"]);
    assert_input_error(&t, &["--threads", "1024"], "--threads 100000");
    let huge = rocking(&[
        "spectrum",
        s,
        "--quiet",
        "--out",
        o,
        "--axis",
        "structure.zeta=0,0.1",
        "--axis",
        "excitation.amplitude=1,1e308",
    ]);
    assert_input_error(
        &huge,
        &["amplitude", "1e308", "at most 10000 g"],
        "amplitude axis to 1e308",
    );
    let sp = rocking(&[
        "spectrum",
        s,
        "--quiet",
        "--out",
        o,
        "--axis",
        "structure.zeta=0,0.1",
        "--axis",
        "structure.r=1,1e20",
    ]);
    let err = stderr(&sp);
    eprintln!("axis to 1e20: exit {:?}: {err}", sp.status.code());
    assert!(sp.status.success(), "{err}");
    let cells = std::fs::read_to_string(out.join("cells.csv")).unwrap();
    assert_eq!(cells.lines().count(), 1 + 4, "{cells}");
    assert!(err.contains("plot"), "the skipped plot is said: {err}");
}

/// Two axes on one key were accepted and the first silently ignored.
#[test]
fn two_axes_on_one_key_are_refused() {
    let dir = tmp("two-axes");
    let scene = scene_file(&dir, SCENE);
    let o = rocking(&[
        "spectrum",
        scene.to_str().unwrap(),
        "--quiet",
        "--out",
        dir.join("out").to_str().unwrap(),
        "--axis",
        "excitation.amplitude=1,2",
        "--axis",
        "excitation.amplitude=3,4",
    ]);
    assert_input_error(&o, &["two axes", "excitation.amplitude"], "two axes");
}

fn names(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

/// One output directory holds exactly one run's files: a re-run with fewer outputs leaves none
/// of the previous run's files; what a killed run left beside it is removed by the next run;
/// parallel runs into one --out leave the files of one of them, never a mix; a folder holding
/// other files is not replaced.
#[test]
fn an_output_directory_holds_one_runs_files() {
    let dir = tmp("outdir");
    let scene = scene_file(&dir, SCENE);
    let s = scene.to_str().unwrap();
    let out = dir.join("out");
    let o = out.to_str().unwrap();
    let full = rocking(&[
        "run",
        s,
        "--out",
        o,
        "--set",
        "output.history_dt=0.01",
        "--set",
        "output.events=true",
    ]);
    assert!(full.status.success(), "{}", stderr(&full));
    assert_eq!(names(&out), ["events.csv", "history.csv", "summary.json"]);
    // A killed run's leftovers beside the directory.
    std::fs::create_dir_all(dir.join(".out.rocking-killed")).unwrap();
    std::fs::write(
        dir.join(".out.rocking-killed/history.csv"),
        vec![b'x'; 1 << 20],
    )
    .unwrap();
    let fewer = rocking(&["run", s, "--out", o]);
    assert!(fewer.status.success(), "{}", stderr(&fewer));
    assert_eq!(names(&out), ["summary.json"], "no stale history or events");
    let beside: Vec<String> = names(&dir)
        .into_iter()
        .filter(|n| n.starts_with(".out.rocking"))
        .collect();
    assert!(beside.is_empty(), "leftovers removed: {beside:?}");

    // Four parallel runs with different outputs and amplitudes.
    let variants: [(&str, &[&str]); 4] = [
        ("1.3", &[]),
        ("1.4", &["--set", "output.events=true"]),
        ("1.5", &["--set", "output.history_dt=0.01"]),
        (
            "1.6",
            &[
                "--set",
                "output.history_dt=0.01",
                "--set",
                "output.events=true",
            ],
        ),
    ];
    let expected = |amp: &str| -> Vec<String> {
        let mut v = vec!["summary.json".to_string()];
        if amp == "1.4" || amp == "1.6" {
            v.push("events.csv".into());
        }
        if amp == "1.5" || amp == "1.6" {
            v.push("history.csv".into());
        }
        v.sort();
        v
    };
    for round in 0..3 {
        let children: Vec<_> = variants
            .iter()
            .map(|(amp, extra)| {
                let set = format!("excitation.amplitude={amp}");
                Command::new(env!("CARGO_BIN_EXE_rocking"))
                    .args(["run", s, "--out", o, "--set", &set])
                    .args(*extra)
                    .stdout(Stdio::null())
                    .stderr(Stdio::piped())
                    .spawn()
                    .unwrap()
            })
            .collect();
        for c in children {
            let r = c.wait_with_output().unwrap();
            assert!(r.status.success(), "{}", String::from_utf8_lossy(&r.stderr));
        }
        let summary: serde_json::Value =
            serde_json::from_slice(&std::fs::read(out.join("summary.json")).unwrap()).unwrap();
        let desc = summary["excitation"].as_str().unwrap();
        let amp = variants
            .iter()
            .map(|v| v.0)
            .find(|a| desc.contains(&format!("= {a}000")))
            .unwrap_or_else(|| panic!("{desc}"));
        assert_eq!(
            names(&out),
            expected(amp),
            "round {round}: one run's files ({desc})"
        );
    }

    // A folder with other files is not replaced.
    let mine = dir.join("mine");
    std::fs::create_dir_all(&mine).unwrap();
    std::fs::write(mine.join("notes.txt"), "keep").unwrap();
    let r = rocking(&["run", s, "--out", mine.to_str().unwrap()]);
    assert_input_error(&r, &["notes.txt"], "--out with other files");
    assert_eq!(names(&mine), ["notes.txt"]);
}

/// The guards of a run that would not end are scene settings named in the message (the message
/// advised raising `max_steps`, which no scene could set); raising them lets the run finish.
#[test]
fn run_guards_are_scene_settings() {
    let dir = tmp("guards");
    let scene = scene_file(&dir, SCENE);
    let s = scene.to_str().unwrap();
    let o = dir.join("out");
    let low = rocking(&[
        "run",
        s,
        "--out",
        o.to_str().unwrap(),
        "--set",
        "solver.max_steps=50",
    ]);
    let err = stderr(&low);
    eprintln!(
        "max_steps = 50: exit {:?}: {}",
        low.status.code(),
        err.trim()
    );
    assert_eq!(low.status.code(), Some(1), "{err}");
    assert!(
        err.contains("`max_steps`") && err.contains("[solver]"),
        "{err}"
    );
    let low = rocking(&[
        "run",
        s,
        "--out",
        o.to_str().unwrap(),
        "--set",
        "solver.max_events=1",
    ]);
    let err = stderr(&low);
    assert_eq!(low.status.code(), Some(1), "{err}");
    assert!(
        err.contains("`max_events`") && err.contains("[solver]"),
        "{err}"
    );
    let ok = rocking(&[
        "run",
        s,
        "--out",
        o.to_str().unwrap(),
        "--set",
        "solver.max_steps=1e8",
    ]);
    assert!(ok.status.success(), "{}", stderr(&ok));
    let bad = rocking(&[
        "run",
        s,
        "--out",
        o.to_str().unwrap(),
        "--set",
        "solver.max_steps=0.5",
    ]);
    assert_input_error(&bad, &["max_steps", "1 <= n <= 1e12"], "max_steps = 0.5");
}

/// Messages name the key the user wrote and print huge numbers shortly: `omega_n_over_p = 1e308`
/// was reported as "`ei` = inf", `alpha = 1.57` (inside the documented range) as a message about
/// `b`, and `omega_p_over_p = 1e308` ended in "step size underflow" with exit 1.
#[test]
fn messages_name_the_key_the_user_wrote() {
    let dir = tmp("messages");
    let scene = scene_file(&dir, SCENE);
    let s = scene.to_str().unwrap();
    let o = dir.join("out");
    let o = o.to_str().unwrap();
    let r = rocking(&[
        "run",
        s,
        "--out",
        o,
        "--set",
        "structure.omega_n_over_p=1e308",
    ]);
    assert_input_error(&r, &["omega_n_over_p", "1e308"], "omega_n_over_p = 1e308");
    assert!(!stderr(&r).contains("`ei`"), "{}", stderr(&r));
    let r = rocking(&["run", s, "--out", o, "--set", "structure.alpha=1.57"]);
    if !r.status.success() {
        assert_input_error(&r, &["alpha"], "alpha = 1.57");
        assert!(!stderr(&r).contains("`b`"), "{}", stderr(&r));
    }
    let r = rocking(&[
        "run",
        s,
        "--out",
        o,
        "--set",
        "excitation.omega_p_over_p=1e308",
    ]);
    assert_input_error(&r, &["omega_p_over_p", "1e308"], "omega_p_over_p = 1e308");
    assert!(!stderr(&r).contains("underflow"), "{}", stderr(&r));
    for set in ["structure.zeta=1e308", "structure.gamma_ib=-1e300"] {
        let r = rocking(&["run", s, "--out", o, "--set", set]);
        let key = &set["structure.".len()..set.find('=').unwrap()];
        assert_input_error(&r, &[key, "e30"], set);
        assert!(
            !stderr(&r).contains("0000000000"),
            "short numbers: {}",
            stderr(&r)
        );
    }
}

/// Derived quantities that would be infinite or NaN (E_ref = inf from m = 1e308, a threshold
/// from g = 1e-308) were written as JSON null with exit 0; now the input is refused naming the
/// key, and no `null` is written for a derived quantity.
#[test]
fn non_finite_derived_quantities_are_refused_not_written_as_null() {
    let dir = tmp("derived");
    let scene = dir.join("physical.toml");
    std::fs::write(&scene, PHYSICAL).unwrap();
    let s = scene.to_str().unwrap();
    for (set, key) in [
        ("structure.m=1e308", "`m`"),
        ("structure.g=1e-308", "`g`"),
        ("structure.h=1e-300", "`h`"),
        ("structure.m_b=1e308", "`m_b`"),
    ] {
        let o = rocking(&["check", s, "--json", "--set", set]);
        assert_input_error(&o, &[key], set);
        assert!(
            !String::from_utf8_lossy(&o.stdout).contains("null"),
            "{set}"
        );
    }
    let o = rocking(&["check", s, "--json"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    for (k, x) in v["derived"].as_object().unwrap() {
        assert!(!x.is_null(), "derived {k} is null");
    }
}

/// A run killed while writing its outputs leaves the previous run's directory as it was (it used
/// to leave a new summary.json beside the old history.csv, and a temporary file nothing removed);
/// what it staged is removed by the next run. The kill happens once the staging directory
/// exists (polled, not timed); if the run finished first, the kill is not exercised and that is
/// said.
#[test]
fn a_run_killed_while_writing_leaves_the_previous_run_intact() {
    let dir = tmp("killed");
    let scene = scene_file(&dir, SCENE);
    let s = scene.to_str().unwrap();
    let out = dir.join("out");
    let o = out.to_str().unwrap();
    let first = rocking(&["run", s, "--out", o, "--set", "output.events=true"]);
    assert!(first.status.success(), "{}", stderr(&first));
    let before = std::fs::read(out.join("summary.json")).unwrap();
    let staged = || {
        names(&dir)
            .into_iter()
            .any(|n| n.starts_with(".out.rocking-") && !n.contains("-old-"))
    };
    let mut child = Command::new(env!("CARGO_BIN_EXE_rocking"))
        .args(["run", s, "--out", o, "--set", "output.history_dt=0.0005"])
        .args([
            "--set",
            "solver.after_excitation=150",
            "--set",
            "excitation.amplitude=1.4",
        ])
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    let killed = loop {
        if staged() {
            child.kill().unwrap();
            child.wait().unwrap();
            break true;
        }
        if child.try_wait().unwrap().is_some() {
            break false;
        }
        std::thread::yield_now();
    };
    eprintln!("killed while writing: {killed}");
    if killed {
        assert_eq!(
            names(&out),
            ["events.csv", "summary.json"],
            "the previous run's files"
        );
        assert_eq!(std::fs::read(out.join("summary.json")).unwrap(), before);
    } else {
        assert_eq!(
            names(&out),
            ["history.csv", "summary.json"],
            "the new run's files"
        );
    }
    let next = rocking(&["run", s, "--out", o]);
    assert!(next.status.success(), "{}", stderr(&next));
    assert_eq!(names(&out), ["summary.json"]);
    assert!(!staged(), "leftovers removed: {:?}", names(&dir));
}
