//! `cargo xtask try-model`: the model developer's path, end to end, in a temporary copy.
//!
//! A model developer edits `derive/rocking_derive/models.py`, runs `cargo xtask regen` and
//! expects everything downstream to keep working. This command does exactly that to a copy of
//! the workspace (the files git knows, committed or not): it appends a new model to `models.py`
//! ([`NEW_MODEL`]: another shape function and another added mass, with its own parameter),
//! regenerates, and runs the tests of the generated crate, the codegen crate and the freshness
//! check there. The working tree is never touched.

use std::path::{Path, PathBuf};
use std::process::Command;

use crate::regen::Result;
use crate::venv;

/// The change a model developer makes: a model that is neither of the kept examples (shape
/// ψ = η², a lumped tank mass `m_t` at 3/4 H with its own parameter), and its kernel variant.
pub const NEW_MODEL: &str = r#"

# --- appended by `cargo xtask try-model` in a temporary copy: a model developer's change ---
TRY_MODEL = Model(
    name="parabolic_tank",
    description="Top mass, a tank m_t at 3/4 H and a base, on a column deflecting as psi = eta^2",
    shape=Polynomial("psi = eta^2", {2: Fraction(1)}),
    masses=(LumpedMass("m"), LumpedMass("m_t", Fraction(3, 4)), BaseMass("m_b", "i_bc")),
    extra_params=(Param("m_t", "mass of the tank at 3/4 H", default=0.0),),
)
VARIANTS = VARIANTS + (
    Variant("parabolic_tank", "Try-model: top mass and a tank on a parabolic column", "", TRY_MODEL),
)
"#;

/// The file the change is appended to.
const MODELS_PY: &str = "derive/rocking_derive/models.py";

/// Runs the whole path; the copy stays in `target/try-model/workspace` for inspection.
pub fn run(root: &Path) -> Result<()> {
    let python = venv::ensure(root)?;
    let base = root.join("target").join("try-model");
    let copy = base.join("workspace");
    if copy.exists() {
        std::fs::remove_dir_all(&copy).map_err(|e| format!("{}: {e}", copy.display()))?;
    }
    let n = copy_workspace(root, &copy)?;
    println!("xtask: try-model: copied {n} files to {}", copy.display());
    // The copy derives with the pinned environment of the working tree.
    let venv_dir = python
        .parent()
        .and_then(Path::parent)
        .ok_or("the virtual environment has no root")?;
    std::os::unix::fs::symlink(venv_dir, copy.join(".venv"))?;
    // Scenes may name records in ../shared, as beside the working tree.
    let shared = root.join("..").join("shared");
    let link = base.join("shared");
    if shared.is_dir() && std::fs::symlink_metadata(&link).is_err() {
        std::os::unix::fs::symlink(shared.canonicalize()?, &link)?;
    }

    let models = copy.join(MODELS_PY);
    let mut text =
        std::fs::read_to_string(&models).map_err(|e| format!("{}: {e}", models.display()))?;
    text.push_str(NEW_MODEL);
    std::fs::write(&models, text)?;
    println!("xtask: try-model: appended the model `parabolic_tank` to {MODELS_PY}");

    let target = base.join("target");
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".to_string());
    let cargo_in_copy = |args: &[&str]| {
        let mut cmd = Command::new(&cargo);
        // Unoptimised, without debug info: these tests are about correctness, and the copy's
        // dev and test builds then share their dependencies (one compile of each crate).
        cmd.args(args)
            .current_dir(&copy)
            .env("CARGO_TARGET_DIR", &target)
            .env("CARGO_PROFILE_TEST_OPT_LEVEL", "0")
            .env("CARGO_PROFILE_TEST_DEBUG", "0")
            .env("CARGO_PROFILE_DEV_DEBUG", "0");
        cmd
    };
    venv::run(&mut cargo_in_copy(&["xtask", "regen"]))?;
    for generated in [
        "generated/ir/parabolic_tank.json",
        "generated/src/kernels/parabolic_tank.rs",
    ] {
        if !copy.join(generated).is_file() {
            return Err(format!("regen did not write {generated}").into());
        }
    }
    venv::run(&mut cargo_in_copy(&[
        "test",
        "-p",
        "rocking-kernels",
        "-p",
        "rocking-codegen",
        "-p",
        "xtask",
    ]))?;
    println!(
        "xtask: try-model: a new model regenerated and the generated crate's, the codegen \
         crate's and the freshness tests passed in the copy"
    );
    Ok(())
}

/// Copies every file git knows (tracked, or untracked and not ignored) from `root` to `dest`.
fn copy_workspace(root: &Path, dest: &Path) -> Result<usize> {
    let out = Command::new("git")
        .args([
            "ls-files",
            "-z",
            "--cached",
            "--others",
            "--exclude-standard",
        ])
        .current_dir(root)
        .output()
        .map_err(|e| format!("cannot run git ls-files: {e}"))?;
    if !out.status.success() {
        return Err(format!(
            "git ls-files failed: {}",
            String::from_utf8_lossy(&out.stderr)
        )
        .into());
    }
    let mut n = 0;
    for name in out.stdout.split(|b| *b == 0).filter(|s| !s.is_empty()) {
        let rel = PathBuf::from(String::from_utf8_lossy(name).into_owned());
        let from = root.join(&rel);
        if !from.is_file() {
            continue; // deleted in the working tree
        }
        let to = dest.join(&rel);
        if let Some(dir) = to.parent() {
            std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
        }
        std::fs::copy(&from, &to).map_err(|e| format!("{}: {e}", from.display()))?;
        n += 1;
    }
    Ok(n)
}
