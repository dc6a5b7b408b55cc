//! Output directories at their edges (issue 30, items 8-10): a swap killed at each of its steps
//! leaves the old or the new directory in place and the next run never deletes the only copy;
//! an `--out` that is a symbolic link to a run's folder is replaced through the link; a command
//! rewrites its own `--out` (`run --animate`, `ida` with stripes, a merge of a one-axis sweep with
//! a reference), or refuses it before the work.

mod common;

use common::{repo, rocking, text, tmp};
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn names(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

/// The directories a run left beside `out` (staging, set aside), by name.
fn beside(dir: &Path) -> Vec<String> {
    names(dir)
        .into_iter()
        .filter(|n| n.starts_with(".out.rocking-"))
        .collect()
}

const SCENE: &str = "[structure]\nomega_n_over_p = 11.9\nalpha = 0.2\ngamma_mc = 0.0\n\
    gamma_mb = 1.0\ngamma_ib = 1.0\nzeta = 0.005\ndamping = \"fixed-base\"\nr = 2.0\n\n\
    [excitation]\nkind = \"sine-pulse\"\nomega_p_over_p = 5.1\namplitude = 1.3\n\n\
    [solver]\nafter_excitation = 5.0\n";

fn scene_file(dir: &Path) -> PathBuf {
    let p = dir.join("scene.toml");
    std::fs::write(&p, SCENE).unwrap();
    p
}

/// The first run's files (with events.csv) and the killed run's (with history.csv).
const OLD: [&str; 2] = ["events.csv", "summary.json"];
const NEW: [&str; 2] = ["history.csv", "summary.json"];

/// A run killed at each step of the swap (a hidden hook of debug builds aborts the process there,
/// as a SIGKILL would: no destructor runs), with the atomic exchange and with the two renames
/// used where there is none. After the kill `out` holds the old run's files or the new one's; in
/// the two-rename swap, killed between the renames, the old directory is aside and the next run
/// puts it back before its own work (that run is killed too, before its swap, and `out` is the
/// old directory again: nothing deleted the only copy). The old code deleted both copies there.
#[test]
fn a_swap_killed_at_any_step_leaves_the_old_or_the_new_directory() {
    if !cfg!(debug_assertions) {
        eprintln!("skipped: the swap's test hook exists in debug builds only");
        return;
    }
    let cases: [(&str, &str, Option<[&str; 2]>); 5] = [
        ("", "staged", Some(OLD)),
        ("", "swapped", Some(NEW)),
        ("two-renames", "staged", Some(OLD)),
        ("two-renames", "old-moved", None),
        ("two-renames", "swapped", Some(NEW)),
    ];
    for (mode, point, visible) in cases {
        let label = format!("{mode} abort-at={point}");
        let dir = tmp(&format!("kill-{mode}-{point}"));
        let scene = scene_file(&dir);
        let s = scene.to_str().unwrap();
        let out = dir.join("out");
        let o = out.to_str().unwrap();
        let first = rocking(&["run", s, "--out", o, "--set", "output.events=true"]);
        assert!(first.status.success(), "{label}: {}", text(&first));
        let old_summary = std::fs::read(out.join("summary.json")).unwrap();
        let killed = Command::new(env!("CARGO_BIN_EXE_rocking"))
            .args(["run", s, "--out", o, "--set", "output.history_dt=0.01"])
            .env("ROCKING_TEST_SWAP", format!("{mode},abort-at={point}"))
            .output()
            .unwrap();
        assert!(
            killed.status.code().is_none(),
            "{label}: the run was killed: {}",
            text(&killed)
        );
        match visible {
            Some(files) => assert_eq!(names(&out), files, "{label}"),
            None => {
                assert!(!out.exists(), "{label}: between the two renames");
                let aside: Vec<String> = beside(&dir)
                    .into_iter()
                    .filter(|n| n.starts_with(".out.rocking-old-"))
                    .collect();
                assert_eq!(aside.len(), 1, "{label}: {:?}", beside(&dir));
                assert_eq!(names(&dir.join(&aside[0])), OLD, "{label}");
                // The next run puts the old directory back before its work: killed before its
                // own swap, it leaves the old directory in place.
                let again = Command::new(env!("CARGO_BIN_EXE_rocking"))
                    .args(["run", s, "--out", o])
                    .env("ROCKING_TEST_SWAP", "two-renames,abort-at=staged")
                    .output()
                    .unwrap();
                assert!(
                    String::from_utf8_lossy(&again.stderr).contains("put back the previous"),
                    "{label}: {}",
                    text(&again)
                );
                assert_eq!(names(&out), OLD, "{label}: the only copy is back");
                assert_eq!(
                    std::fs::read(out.join("summary.json")).unwrap(),
                    old_summary,
                    "{label}"
                );
            }
        }
        let next = rocking(&["run", s, "--out", o]);
        assert!(next.status.success(), "{label}: {}", text(&next));
        assert_eq!(names(&out), ["summary.json"], "{label}");
        assert!(beside(&dir).is_empty(), "{label}: {:?}", beside(&dir));
    }
}

/// The state a swap of two renames leaves when killed between them, made on disk (so this runs
/// against any build): no `out`, the previous directory aside, the new one staged. The next run
/// puts the previous one back (and says so) before its own work; the old code deleted both.
#[test]
fn a_directory_left_aside_by_a_killed_swap_is_put_back_first() {
    let dir = tmp("aside");
    let scene = scene_file(&dir);
    let s = scene.to_str().unwrap();
    let out = dir.join("out");
    let o = out.to_str().unwrap();
    let first = rocking(&["run", s, "--out", o, "--set", "output.events=true"]);
    assert!(first.status.success(), "{}", text(&first));
    std::fs::rename(&out, dir.join(".out.rocking-old-killed")).unwrap();
    std::fs::create_dir(dir.join(".out.rocking-staged")).unwrap();
    std::fs::write(dir.join(".out.rocking-staged/summary.json"), "{}").unwrap();
    // A run refused for its --out (a user's file inside) after the put-back: the old directory
    // stays in place, it is not deleted.
    std::fs::write(dir.join(".out.rocking-old-killed/notes.txt"), "mine").unwrap();
    let refused = rocking(&["run", s, "--out", o]);
    assert_eq!(refused.status.code(), Some(2), "{}", text(&refused));
    assert!(text(&refused).contains("put back"), "{}", text(&refused));
    assert!(text(&refused).contains("notes.txt"), "{}", text(&refused));
    assert_eq!(names(&out), ["events.csv", "notes.txt", "summary.json"]);
    std::fs::remove_file(out.join("notes.txt")).unwrap();
    let next = rocking(&["run", s, "--out", o]);
    assert!(next.status.success(), "{}", text(&next));
    assert_eq!(names(&out), ["summary.json"]);
    assert!(beside(&dir).is_empty(), "{:?}", beside(&dir));
}

/// `--out` as a symbolic link to a run's folder: the run replaces the folder and keeps the link
/// (it computed, then failed "cannot replace"); a link to nowhere is refused before the run.
#[cfg(unix)]
#[test]
fn an_out_that_links_to_a_run_folder_is_replaced_through_the_link() {
    let dir = tmp("symlink");
    let scene = scene_file(&dir);
    let s = scene.to_str().unwrap();
    let real = dir.join("real");
    let link = dir.join("link");
    let first = rocking(&[
        "run",
        s,
        "--out",
        real.to_str().unwrap(),
        "--set",
        "output.events=true",
    ]);
    assert!(first.status.success(), "{}", text(&first));
    std::os::unix::fs::symlink("real", &link).unwrap();
    for round in 0..2 {
        let o = rocking(&["run", s, "--out", link.to_str().unwrap()]);
        assert!(o.status.success(), "round {round}: {}", text(&o));
        assert!(text(&o).contains(&format!("{}", link.join("summary.json").display())));
        assert!(std::fs::symlink_metadata(&link)
            .unwrap()
            .file_type()
            .is_symlink());
        assert_eq!(names(&real), ["summary.json"], "round {round}");
    }
    let dangling = dir.join("dangling");
    std::os::unix::fs::symlink("nowhere", &dangling).unwrap();
    let o = rocking(&["run", s, "--out", dangling.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    assert!(text(&o).contains("symbolic link"), "{}", text(&o));
    assert!(!dir.join("nowhere").exists());
}

/// `rocking run --animate` twice into one --out: the second run refused the first one's
/// animation.gif.
#[test]
fn run_animate_rewrites_its_own_out() {
    let dir = tmp("animate");
    let scene = scene_file(&dir);
    let s = scene.to_str().unwrap();
    let o = dir.join("out");
    for round in 0..2 {
        let r = rocking(&[
            "run",
            s,
            "--out",
            o.to_str().unwrap(),
            "--animate",
            "--set",
            "output.animation_frames=2",
        ]);
        assert!(r.status.success(), "round {round}: {}", text(&r));
        assert_eq!(names(&o), ["animation.gif", "summary.json"]);
    }
}

/// Three records of the shared suite.
fn records() -> Vec<String> {
    let gm = repo().join("../shared/data/ground-motions");
    ["A-BEN360.AT2", "A-BPL160.AT2", "A-ELC180.AT2"]
        .iter()
        .map(|r| gm.join(r).canonicalize().unwrap().display().to_string())
        .collect()
}

/// `rocking ida` of the wind turbine by stripes on three records, into `out`, with `extra`.
fn ida(out: &Path, extra: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_rocking"))
        .arg("ida")
        .arg(repo().join("scenes/wind-turbine-msa.toml"))
        .args(["--set", "ida.stripes=[5.0, 13.0, 20.0, 60.0]", "--out"])
        .arg(out)
        .args(extra)
        .arg("--records")
        .args(records())
        .output()
        .unwrap()
}

/// `rocking ida` with stripes into its own --out (it refused its stripes.csv after the whole
/// study), and an --out it cannot replace is refused before the study (here a study that fails
/// with exit 1 once it runs: the refusal of the --out comes first, with exit 2).
#[test]
fn ida_with_stripes_rewrites_its_own_out_and_refuses_a_foreign_one_first() {
    let dir = tmp("ida");
    let o = dir.join("out");
    for round in 0..2 {
        let r = ida(&o, &[]);
        assert!(r.status.success(), "round {round}: {}", text(&r));
        assert!(names(&o).contains(&"stripes.csv".to_string()));
    }
    let failing = ida(&dir.join("failing"), &["--set", "solver.max_events=1"]);
    assert_eq!(failing.status.code(), Some(1), "{}", text(&failing));
    let mine = dir.join("mine");
    std::fs::create_dir_all(&mine).unwrap();
    std::fs::write(mine.join("notes.txt"), "keep").unwrap();
    let r = ida(&mine, &["--set", "solver.max_events=1"]);
    assert_eq!(r.status.code(), Some(2), "{}", text(&r));
    assert!(text(&r).contains("notes.txt"), "{}", text(&r));
    assert_eq!(names(&mine), ["notes.txt"]);
}

/// A second merge into the same OUT of a one-axis sweep with `[sweep] reference` (it refused
/// line.png and reference.csv, which the first merge wrote).
#[test]
fn a_merge_rewrites_its_own_out() {
    let dir = tmp("merge");
    let shard = |k: usize| {
        let d = dir.join(format!("s{k}"));
        let o = Command::new(env!("CARGO_BIN_EXE_rocking"))
            .arg("spectrum")
            .arg(repo().join("scenes/spectra/fig8.toml"))
            .args(["--axis", "excitation.amplitude=1:20:4", "--quiet"])
            .args(["--set", "sweep.reference=\"rigid\""])
            .args(["--shard", &format!("{k}/2"), "--out"])
            .arg(&d)
            .output()
            .unwrap();
        assert!(o.status.success(), "{}", text(&o));
        d
    };
    let shards = [shard(0), shard(1)];
    let out = dir.join("merged");
    for round in 0..2 {
        let o = Command::new(env!("CARGO_BIN_EXE_rocking"))
            .arg("merge")
            .arg(&out)
            .args(&shards)
            .output()
            .unwrap();
        assert!(o.status.success(), "round {round}: {}", text(&o));
        assert_eq!(
            names(&out),
            [
                "cells.csv",
                "line.pdf",
                "line.png",
                "line.svg",
                "meta.json",
                "reference.csv"
            ]
        );
    }
}

/// An `--out` that is a regular file is refused by every command with one line and exit 2
/// (issue 47, item 16: `spectrum` and `figure` failed with exit 1, "File exists (os error 17)").
#[test]
fn every_command_refuses_an_out_that_is_a_file_alike() {
    let dir = tmp("out-file");
    let file = dir.join("afile");
    std::fs::write(&file, "mine").unwrap();
    let f = file.to_str().unwrap();
    let scene = scene_file(&dir);
    let s = scene.to_str().unwrap();
    let commands: [&[&str]; 4] = [
        &["run", s, "--out", f],
        &[
            "spectrum",
            s,
            "--axis",
            "excitation.amplitude=1:2:2",
            "--quiet",
            "--out",
            f,
        ],
        &[
            "figure",
            "scenes/paper/fig3.toml",
            "--cells",
            "2",
            "--quiet",
            "--out",
            f,
        ],
        &[
            "batch",
            "scenes/wind-turbine-ida.toml",
            "--records",
            "scenes/records/elCentro.AT2",
            "--quiet",
            "--out",
            f,
        ],
    ];
    for args in commands {
        let o = rocking(args);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {}", text(&o));
        assert_eq!(
            common::stderr(&o).trim(),
            format!("error: {f}: --out exists and is not a directory"),
            "{args:?}"
        );
        assert_eq!(std::fs::read_to_string(&file).unwrap(), "mine");
    }
}

/// A legal `--out` name of 250 bytes (issue 47, item 17: the staging directory's name grew past
/// 255 bytes, exit 1, and `.NAME.lock` stayed): the run succeeds twice, and nothing stays beside
/// the directory, for a short name either.
#[test]
fn a_long_out_name_works_and_no_lock_stays_behind() {
    let dir = tmp("long-name");
    let scene = scene_file(&dir);
    for name in ["x".repeat(250), "out".to_string()] {
        let o = dir.join(&name);
        for round in 0..2 {
            let r = rocking(&["run", scene.to_str().unwrap(), "--out", o.to_str().unwrap()]);
            assert!(
                r.status.success(),
                "{} bytes, round {round}: {}",
                name.len(),
                text(&r)
            );
            assert_eq!(names(&o), ["summary.json"]);
            let mut expected = vec![name.clone(), "scene.toml".to_string()];
            expected.sort();
            assert_eq!(names(&dir), expected);
        }
        std::fs::remove_dir_all(&o).unwrap();
    }
}

/// `rocking figure` builds its outputs aside and swaps them in under the lock (issue 47, item 8:
/// it wrote into --out file by file, so two runs could leave one's SVG beside the other's PNG).
/// Killed before its swap, the previous figures stay whole; a figure of another file stays
/// beside the ones a run redraws.
#[test]
fn a_figure_run_swaps_its_outputs_in_whole_and_keeps_other_figures() {
    if !cfg!(debug_assertions) {
        eprintln!("skipped: the swap's test hook exists in debug builds only");
        return;
    }
    let dir = tmp("figure-swap");
    let out = dir.join("figs");
    let cache = dir.join("cache");
    let figure = |file: &str, cells: &str, env: &str| {
        Command::new(env!("CARGO_BIN_EXE_rocking"))
            .current_dir(repo())
            .env("ROCKING_TEST_SWAP", env)
            .args(["figure", file, "--quiet", "--cells", cells, "--out"])
            .arg(&out)
            .arg("--cache")
            .arg(&cache)
            .output()
            .unwrap()
    };
    let first = figure("scenes/paper/fig4.toml", "2", "");
    assert!(first.status.success(), "{}", text(&first));
    let o = figure("scenes/paper/fig3.toml", "2", "");
    assert!(o.status.success(), "{}", text(&o));
    let all = [
        "fig3.caption.md",
        "fig3.pdf",
        "fig3.png",
        "fig3.svg",
        "fig4.caption.md",
        "fig4.pdf",
        "fig4.png",
        "fig4.svg",
    ];
    assert_eq!(names(&out), all);
    let before: Vec<Vec<u8>> = all
        .iter()
        .map(|n| std::fs::read(out.join(n)).unwrap())
        .collect();
    // fig3 drawn otherwise (another title and one column), killed before its swap: nothing changed.
    let edited = dir.join("fig3.toml");
    let text3 = std::fs::read_to_string(repo().join("scenes/paper/fig3.toml")).unwrap();
    std::fs::write(
        &edited,
        text3
            .replace("../fig3", &format!("{}/scenes/fig3", repo().display()))
            .replacen("title = \"", "title = \"Edited: ", 1)
            .replacen("columns = 2", "columns = 1", 1),
    )
    .unwrap();
    let killed = figure(edited.to_str().unwrap(), "2", "abort-at=staged");
    assert!(!killed.status.success(), "{}", text(&killed));
    let after: Vec<Vec<u8>> = all
        .iter()
        .map(|n| std::fs::read(out.join(n)).unwrap())
        .collect();
    assert!(before == after, "a killed figure run changed its --out");
    // Drawn in full, all formats of fig3 and its caption change together and fig4 stays.
    let o = figure(edited.to_str().unwrap(), "2", "");
    assert!(o.status.success(), "{}", text(&o));
    assert_eq!(names(&out), all);
    for (n, b) in all.iter().zip(&before) {
        let changed = std::fs::read(out.join(n)).unwrap() != *b;
        assert_eq!(changed, n.starts_with("fig3"), "{n}");
    }
    assert!(
        names(&dir).iter().all(|n| !n.starts_with('.')),
        "{:?}",
        names(&dir)
    );
}
