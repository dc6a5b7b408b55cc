//! `--shard K/N` and `rocking merge` end to end: a spectrum split into N = 1, 3, 4, 7 shards and
//! a record suite split into 3 merge to the same bytes as one unsharded run (cells.csv / runs.csv,
//! meta.json and the plots); shards of another study, a duplicate, a missing shard, a killed
//! shard and bad K/N are refused with exit status 2; a killed shard resumes to the same merge.

mod common;

use common::{bin, repo, text, tmp};
use std::path::{Path, PathBuf};
use std::process::Output;

const AXES: [&str; 4] = [
    "--axis",
    "excitation.omega_p_over_p=1:10:7",
    "--axis",
    "excitation.amplitude=1:20:9",
];

fn spectrum(out: &Path, extra: &[&str]) -> Output {
    bin()
        .arg("spectrum")
        .arg(repo().join("scenes/spectra/fig8.toml"))
        .args(AXES)
        .args(["--quiet", "--threads", "1", "--out"])
        .arg(out)
        .args(extra)
        .output()
        .unwrap()
}

fn shards(root: &Path, n: usize, run: impl Fn(&Path, &str) -> Output) -> Vec<PathBuf> {
    (0..n)
        .map(|k| {
            let dir = root.join(format!("shard-{n}-{k}"));
            let o = run(&dir, &format!("{k}/{n}"));
            assert!(o.status.success(), "{}", text(&o));
            assert!(
                !dir.join("cells.csv").exists(),
                "a shard writes no partial outputs"
            );
            dir
        })
        .collect()
}

fn merge(out: &Path, dirs: &[PathBuf]) -> Output {
    bin().arg("merge").arg(out).args(dirs).output().unwrap()
}

fn assert_same_files(a: &Path, b: &Path, files: &[&str]) {
    for f in files {
        let (x, y) = (
            std::fs::read(a.join(f)).unwrap(),
            std::fs::read(b.join(f)).unwrap(),
        );
        assert!(!x.is_empty(), "{f} is written");
        assert!(x == y, "{f}: {} and {} differ", a.display(), b.display());
    }
}

const SPECTRUM_FILES: [&str; 5] = [
    "cells.csv",
    "meta.json",
    "spectrum.png",
    "spectrum.svg",
    "spectrum.pdf",
];

#[test]
fn sharded_spectra_merge_to_the_bytes_of_an_unsharded_run() {
    let root = tmp("spectrum");
    let whole = root.join("whole");
    let o = spectrum(&whole, &[]);
    assert!(o.status.success(), "{}", text(&o));
    // meta.json is a function of the study alone: a second run (resumed from the journal, so
    // computing nothing) writes the same bytes, and the timings are in timing.json.
    let meta = std::fs::read(whole.join("meta.json")).unwrap();
    let o = spectrum(&whole, &[]);
    assert!(o.status.success(), "{}", text(&o));
    assert_eq!(std::fs::read(whole.join("meta.json")).unwrap(), meta);
    let timing: serde_json::Value =
        serde_json::from_slice(&std::fs::read(whole.join("timing.json")).unwrap()).unwrap();
    assert_eq!(timing["computed_now"], 0);
    assert_eq!(timing["cells"], 63);
    let m: serde_json::Value = serde_json::from_slice(&meta).unwrap();
    for key in ["seconds", "threads", "computed_now"] {
        assert!(m.get(key).is_none(), "meta.json holds no {key}");
    }
    for n in [1, 3, 4, 7] {
        let dirs = shards(&root, n, |dir, shard| spectrum(dir, &["--shard", shard]));
        let merged = root.join(format!("merged-{n}"));
        let o = merge(&merged, &dirs);
        assert!(o.status.success(), "N = {n}: {}", text(&o));
        assert_same_files(&whole, &merged, &SPECTRUM_FILES);
        // The merge may be run again into the same OUT (replaced whole).
        let reversed: Vec<PathBuf> = dirs.iter().rev().cloned().collect();
        let o = merge(&merged, &reversed);
        assert!(o.status.success(), "N = {n} again: {}", text(&o));
        assert_same_files(&whole, &merged, &SPECTRUM_FILES);
    }
    let _ = std::fs::remove_dir_all(&root);
}

#[test]
fn a_sharded_record_suite_merges_to_the_bytes_of_an_unsharded_run() {
    let records = repo().join("../shared/data/ground-motions");
    let records = if records.is_dir() {
        records
    } else {
        repo().join("scenes/records")
    };
    let mut files: Vec<PathBuf> = std::fs::read_dir(&records)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x.eq_ignore_ascii_case("at2")))
        .collect();
    files.sort();
    files.truncate(3);
    let root = tmp("batch");
    let batch = |out: &Path, extra: &[&str]| {
        bin()
            .arg("batch")
            .arg(repo().join("scenes/wind-turbine-elcentro.toml"))
            .arg("--records")
            .args(&files)
            .args(["--scales", "2,9", "--quiet", "--threads", "1", "--out"])
            .arg(out)
            .args(extra)
            .output()
            .unwrap()
    };
    let whole = root.join("whole");
    let o = batch(&whole, &[]);
    assert!(o.status.success(), "{}", text(&o));
    let runs = std::fs::read_to_string(whole.join("runs.csv")).unwrap();
    assert_eq!(runs.lines().count(), 1 + 3 * 2, "{runs}");
    let dirs = shards(&root, 4, |dir, shard| batch(dir, &["--shard", shard]));
    let merged = root.join("merged");
    let o = merge(&merged, &dirs);
    assert!(o.status.success(), "{}", text(&o));
    assert_same_files(
        &whole,
        &merged,
        &[
            "runs.csv",
            "fragility.csv",
            "meta.json",
            "fragility.png",
            "fragility.svg",
        ],
    );
    // A shard of the spectrum is not a shard of this suite.
    let spec = shards(&root.join("spectrum"), 4, |dir, shard| {
        spectrum(dir, &["--shard", shard])
    });
    let o = merge(&root.join("mixed"), &[dirs[0].clone(), spec[1].clone()]);
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    assert!(
        text(&o).contains("the command (spectrum or batch) differ"),
        "{}",
        text(&o)
    );
    assert!(!root.join("mixed").exists(), "nothing written");
    let _ = std::fs::remove_dir_all(&root);
}

/// Edits a field of a shard's `shard.json`.
fn edit_manifest(dir: &Path, edit: impl Fn(&mut serde_json::Value)) {
    let path = dir.join("shard.json");
    let mut v: serde_json::Value = serde_json::from_slice(&std::fs::read(&path).unwrap()).unwrap();
    edit(&mut v);
    std::fs::write(&path, serde_json::to_string_pretty(&v).unwrap()).unwrap();
}

#[test]
fn merges_of_inconsistent_or_incomplete_shards_are_refused() {
    let root = tmp("refusals");
    let whole = root.join("whole");
    assert!(spectrum(&whole, &[]).status.success());
    let dirs = shards(&root, 3, |dir, shard| spectrum(dir, &["--shard", shard]));
    let out = root.join("merged");
    let refused = |dirs: &[PathBuf], says: &[&str]| {
        let o = merge(&out, dirs);
        let t = text(&o);
        assert_eq!(o.status.code(), Some(2), "{t}");
        for s in says {
            assert!(t.contains(s), "expected `{s}` in: {t}");
        }
        assert!(!out.exists(), "nothing written: {t}");
    };
    // Another scene (an override), other axes: shards of another study, named.
    let other = root.join("other");
    assert!(
        spectrum(&other, &["--shard", "1/3", "--set", "structure.alpha=0.15"])
            .status
            .success()
    );
    let d = other.display().to_string();
    refused(
        &[dirs[0].clone(), other.clone(), dirs[2].clone()],
        &[&d, "the --set overrides differ"],
    );
    let axes = root.join("axes");
    let o = bin()
        .arg("spectrum")
        .arg(repo().join("scenes/spectra/fig8.toml"))
        .args([
            "--axis",
            "excitation.omega_p_over_p=1:10:7",
            "--axis",
            "excitation.amplitude=1:20:8",
        ])
        .args(["--quiet", "--shard", "1/3", "--out"])
        .arg(&axes)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", text(&o));
    refused(
        &[dirs[0].clone(), axes, dirs[2].clone()],
        &["the axes differ"],
    );
    // Another scene text (the shard's copy of the scene edited).
    let edited = root.join("edited");
    std::fs::create_dir_all(&edited).unwrap();
    for f in ["shard.json", "cells.journal"] {
        std::fs::copy(dirs[1].join(f), edited.join(f)).unwrap();
    }
    edit_manifest(&edited, |v| {
        v["scene_text"] = format!("{}\n# edited", v["scene_text"].as_str().unwrap()).into()
    });
    refused(
        &[dirs[0].clone(), edited.clone(), dirs[2].clone()],
        &["the scene text differ"],
    );
    // Another program build: every shard written by it is refused by this merge.
    let mut builds = Vec::new();
    for (k, dir) in dirs.iter().enumerate() {
        let copy = root.join(format!("build-{k}"));
        std::fs::create_dir_all(&copy).unwrap();
        for f in ["shard.json", "cells.journal"] {
            std::fs::copy(dir.join(f), copy.join(f)).unwrap();
        }
        edit_manifest(&copy, |v| v["program"] = "0.0.1 0123456789abcdef".into());
        builds.push(copy);
    }
    refused(
        &[dirs[0].clone(), builds[1].clone(), dirs[2].clone()],
        &["the program build differ"],
    );
    refused(
        &builds,
        &["another build of rocking (0.0.1 0123456789abcdef)"],
    );
    // A duplicate shard, a missing shard (its cells listed with their owner).
    refused(
        &[dirs[0].clone(), dirs[1].clone(), dirs[1].clone()],
        &["shard 1/3 is given twice"],
    );
    refused(
        &[dirs[0].clone(), dirs[2].clone()],
        &["shard 1/3 (not given): 21 of its 21 cells missing: 1 (excitation.omega_p_over_p=1, excitation.amplitude=3.375)"],
    );
    // Not a shard directory.
    refused(
        &[dirs[0].clone(), whole.clone(), dirs[2].clone()],
        &["not a shard directory", "shard.json"],
    );

    // A killed shard (its journal cut after 5 cells): refused, listing what it lacks; resumed,
    // it computes only those and the merge equals the unsharded run.
    let journal = dirs[1].join("cells.journal");
    let full = std::fs::read_to_string(&journal).unwrap();
    let cut: String = full.lines().take(6).map(|l| format!("{l}\n")).collect();
    std::fs::write(&journal, cut + "4,surv").unwrap();
    let owner = format!(
        "shard 1/3 ({}): 16 of its 21 cells missing",
        dirs[1].display()
    );
    refused(&dirs, &[&owner, "and 6 more"]);
    let o = spectrum(&dirs[1], &["--shard", "1/3"]);
    assert!(o.status.success(), "{}", text(&o));
    assert!(
        text(&o).contains("16 computed now, 5 resumed"),
        "{}",
        text(&o)
    );
    let o = merge(&out, &dirs);
    assert!(o.status.success(), "{}", text(&o));
    assert_same_files(&whole, &out, &SPECTRUM_FILES);

    // A shard directory is not resumed as another shard, and the refused run changes nothing:
    // its shard.json used to be rewritten to 2/3, so the finished shard no longer merged.
    let before: Vec<Vec<u8>> = ["shard.json", "cells.journal"]
        .iter()
        .map(|f| std::fs::read(dirs[1].join(f)).unwrap())
        .collect();
    for (other, says) in [
        (&["--shard", "2/3"][..], "different sweep"),
        (
            &["--shard", "1/3", "--set", "structure.alpha=0.15"][..],
            "different sweep",
        ),
    ] {
        let o = spectrum(&dirs[1], other);
        assert_eq!(o.status.code(), Some(2), "{}", text(&o));
        assert!(text(&o).contains(says), "{}", text(&o));
        let after: Vec<Vec<u8>> = ["shard.json", "cells.journal"]
            .iter()
            .map(|f| std::fs::read(dirs[1].join(f)).unwrap())
            .collect();
        assert!(
            after == before,
            "{other:?}: the refused run changed the shard"
        );
    }
    let o = merge(&out, &dirs);
    assert!(o.status.success(), "the shard still merges: {}", text(&o));
    assert_same_files(&whole, &out, &SPECTRUM_FILES);
    let _ = std::fs::remove_dir_all(&root);
}

#[test]
fn bad_shard_arguments_are_input_errors() {
    let root = tmp("bad-args");
    for (bad, says) in [
        ("3/3", "0 ≤ K < N = 3"),
        ("0/0", "1 ≤ N ≤ 100000"),
        ("0/1000000", "1 ≤ N ≤ 100000"),
        ("1of3", "expected K/N"),
        ("x/3", "K `x` is not a whole number"),
    ] {
        let o = spectrum(&root.join("out"), &["--shard", bad]);
        assert_eq!(o.status.code(), Some(2), "{bad}: {}", text(&o));
        assert!(text(&o).contains(says), "{bad}: {}", text(&o));
        assert!(!root.join("out").exists(), "{bad}: nothing written");
    }
    let o = bin().arg("merge").arg(root.join("m")).output().unwrap();
    assert_eq!(
        o.status.code(),
        Some(2),
        "merge without shards: {}",
        text(&o)
    );
    let _ = std::fs::remove_dir_all(&root);
}
