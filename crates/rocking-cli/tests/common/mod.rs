//! What every test of the command line needs: the repository's paths, fresh scratch directories
//! and the `rocking` binary. Each test file includes it (`mod common;`) and uses a part of it.

#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// The repository's root (scenes, records and docs are found from there).
pub fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// The example scenes.
pub fn scenes() -> PathBuf {
    repo().join("scenes")
}

/// A path for `name` under this test binary's scratch directory, with nothing there (for an
/// output directory the command must create itself).
pub fn tmp_path(name: &str) -> PathBuf {
    let path = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(env!("CARGO_CRATE_NAME"))
        .join(name);
    let _ = std::fs::remove_dir_all(&path);
    path
}

/// An empty directory for `name` under this test binary's scratch directory.
pub fn tmp(name: &str) -> PathBuf {
    let dir = tmp_path(name);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The `rocking` binary, to be given arguments, run in the repository's root.
pub fn bin() -> Command {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_rocking"));
    cmd.current_dir(repo());
    cmd
}

/// Runs `rocking` with `args` in the repository's root.
pub fn rocking(args: &[&str]) -> Output {
    bin().args(args).output().expect("run rocking")
}

/// What the command wrote to standard error.
pub fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// The exit code and everything the command wrote, for assertion messages.
pub fn text(o: &Output) -> String {
    format!(
        "exit {:?}\n{}{}",
        o.status.code(),
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    )
}

/// `rocking run SCENE --json` with `--set` overrides (plots off), in a scratch folder: the
/// summary it prints (the test fails on a non-zero exit).
pub fn summary(scene: &str, sets: &[&str]) -> serde_json::Value {
    let out = tmp_path("summary-run");
    let mut args = vec![
        "run",
        scene,
        "--json",
        "--out",
        out.to_str().unwrap(),
        "--set",
        "output.plots=false",
    ];
    for s in sets {
        args.extend(["--set", s]);
    }
    let o = rocking(&args);
    assert!(o.status.success(), "{}", text(&o));
    let stdout = String::from_utf8(o.stdout).unwrap();
    serde_json::from_str(stdout.trim().lines().last().unwrap()).unwrap()
}

/// Figs 6-8, each as two figure files (α = 0.1 and 0.2, 3 + 2 panels, so that a panel prints
/// at least 35 mm wide).
pub const FIGS_6_TO_8: [&str; 6] = [
    "fig6-alpha01",
    "fig6-alpha02",
    "fig7-alpha01",
    "fig7-alpha02",
    "fig8-alpha01",
    "fig8-alpha02",
];
