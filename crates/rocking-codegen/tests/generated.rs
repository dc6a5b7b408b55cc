//! Tests over the real IR checked in at `generated/ir/` (skipped while it does not exist).

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use rocking_codegen::{load_dir, render_all, render_mod, render_variant, IR_DIR, KERNELS_DIR};

fn repo_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .ancestors()
        .nth(2)
        .unwrap()
        .to_path_buf()
}

fn ir_dir() -> Option<PathBuf> {
    let dir = repo_root().join(IR_DIR);
    if dir.is_dir() {
        Some(dir)
    } else {
        eprintln!("skipped: {} does not exist yet", dir.display());
        None
    }
}

/// Snapshots of every real variant: a template change shows up as a reviewable diff.
#[test]
fn snapshots_of_real_ir() {
    let Some(dir) = ir_dir() else { return };
    let irs = load_dir(&dir).unwrap();
    for ir in &irs {
        insta::assert_snapshot!(format!("real_{}", ir.variant), render_variant(ir).unwrap());
    }
    insta::assert_snapshot!("real_mod", render_mod(&irs).unwrap());
}

/// The checked-in `generated/src/kernels/` is exactly what the checked-in IR renders to:
/// catches a hand edit of a generated file, a template change without `cargo xtask regen`,
/// and a stale module. (`cargo xtask regen --check` does the same, plus a fresh derivation.)
#[test]
fn checked_in_kernels_are_fresh() {
    let Some(dir) = ir_dir() else { return };
    let root = repo_root();
    let want = render_all(&dir).unwrap();
    let mut have = BTreeMap::new();
    for entry in std::fs::read_dir(root.join(KERNELS_DIR)).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "rs") {
            let name = path.file_name().unwrap().to_string_lossy().into_owned();
            let text = std::fs::read_to_string(&path).unwrap();
            have.insert(format!("{KERNELS_DIR}/{name}"), text);
        }
    }
    let mut problems = Vec::new();
    for (path, text) in &want {
        match have.get(path) {
            None => problems.push(format!("missing: {path}")),
            Some(old) if old != text => {
                let line = old
                    .lines()
                    .zip(text.lines())
                    .position(|(a, b)| a != b)
                    .unwrap_or_else(|| old.lines().count().min(text.lines().count()));
                problems.push(format!("differs: {path} (first at line {})", line + 1));
            }
            Some(_) => {}
        }
    }
    for path in have.keys().filter(|p| !want.contains_key(*p)) {
        problems.push(format!("stale: {path}"));
    }
    assert!(
        problems.is_empty(),
        "{}\ngenerated code is stale: run `cargo xtask regen` and commit the result \
         (`cargo xtask regen --check --skip-derive` shows the diffs)",
        problems.join("\n")
    );
}
