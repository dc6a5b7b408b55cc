//! `rocking spectrum` and `rocking batch` end to end: outputs, a real interruption (the process
//! is killed mid-sweep) that resumes to the uninterrupted result, a changed scene refused, and
//! the same cells with 1 and 2 threads.

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

fn bin() -> Command {
    Command::new(env!("CARGO_BIN_EXE_rocking"))
}

fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn tmp(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!(
        "rocking-spectrum-test-{}-{name}",
        std::process::id()
    ));
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

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
    let out = tmp("outputs");
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
    assert!(meta["seconds"].as_f64().unwrap() > 0.0);
    for f in ["spectrum.png", "spectrum.svg"] {
        assert!(std::fs::metadata(out.join(f)).unwrap().len() > 1000, "{f}");
    }
}

#[test]
fn killed_spectrum_resumes_to_the_uninterrupted_result() {
    let whole = tmp("whole");
    assert!(spectrum(&whole, &AXES, &["--threads", "2"])
        .status
        .success());
    let reference = std::fs::read_to_string(whole.join("cells.csv")).unwrap();

    let out = tmp("killed");
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
    let (a, b) = (tmp("t1"), tmp("t2"));
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
        let o = spectrum(&tmp("bad"), &[axis], &[]);
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
    let out = tmp("batch");
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
