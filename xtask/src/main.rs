//! Project automation: `cargo xtask regen [--check] [--skip-derive | --only NAME[,NAME...]]`,
//! `cargo xtask bench [--quick]`, `cargo xtask try-model`.
//!
//! `regen` re-derives the kernel IR with the pinned Python environment
//! (`derive/requirements.txt`, installed into `<repo>/.venv`), renders it with
//! `rocking-codegen`, and updates the generated files that are checked in:
//!
//! - `generated/ir/*.json` (copied byte-for-byte from the derivation),
//! - `generated/src/kernels/*.rs` (rendered),
//! - `docs/errata.md` (copied from the derivation).
//!
//! With `--check` nothing is written: every difference is printed as a unified diff
//! and the command fails. With `--skip-derive` the checked-in `generated/ir/` is
//! rendered instead of a fresh derivation (no Python needed). With `--only a,b` only the
//! variants `a` and `b` are derived, and every file is rendered from their fresh IR and the
//! checked-in IR of all others (kept as it is, as is `docs/errata.md`).

use std::path::{Path, PathBuf};
use std::process::ExitCode;

/// Every task's result: an error is printed and the task exits 1.
pub type Result<T, E = Box<dyn std::error::Error>> = std::result::Result<T, E>;

mod bench;
mod regen;
mod try_model;
mod venv;

const USAGE: &str = "\
usage: cargo xtask <command>

commands:
  regen [--check] [--skip-derive | --only NAME[,NAME...]]
      Re-derive the kernels (Python/CasADi in .venv), render them and update
      generated/ir, generated/src/kernels and docs/errata.md.
      --check        write nothing; print diffs and fail if anything is stale
      --skip-derive  render the checked-in generated/ir (no Python needed)
      --only NAMES   derive only these variants of derive/rocking_derive/models.py
                     (`ground`: the ground's IR) and render everything from them and
                     the checked-in IR of the others; docs/errata.md is kept
  bench [--quick] [--no-peers]
      The accuracy/cost study: both integrators x tolerances on every case against
      a reference, the SciPy, heyoka and OpenSees peers (installed into .venv from
      bench/requirements.txt), written to docs/accuracy.md (one page),
      docs/reference/accuracy-study.md (every case) and docs/img/.
      --quick     fewer tolerances and cases (about two minutes); writes
                  target/bench-quick/docs/ instead of docs/
      --no-peers  Rust study and report only (no Python)
  try-model
      The model developer's path in a temporary copy (target/try-model/): append
      a new model to derive/rocking_derive/models.py, regenerate, and run the
      tests of the generated and codegen crates there.
  help
      Print this message.
";

/// The repository root: the nearest directory at or above the current one that holds the
/// workspace's Cargo.toml and this xtask (where cargo found the `xtask` alias). Not the path the
/// binary was compiled in: a checkout copied or moved with its `target/` works on itself.
pub fn repo_root() -> Result<PathBuf> {
    let cwd = std::env::current_dir()?;
    workspace_root(&cwd).ok_or_else(|| {
        format!(
            "no repository at or above {}: run `cargo xtask` inside the repository (a directory \
             whose Cargo.toml has [workspace] and which holds xtask/)",
            cwd.display()
        )
        .into()
    })
}

/// The nearest ancestor of `start` (itself included) that is a workspace root holding xtask/.
fn workspace_root(start: &Path) -> Option<PathBuf> {
    let is_root = |dir: &Path| {
        dir.join("xtask/Cargo.toml").is_file()
            && std::fs::read_to_string(dir.join("Cargo.toml"))
                .is_ok_and(|t| t.lines().any(|l| l.trim() == "[workspace]"))
    };
    start
        .ancestors()
        .find(|d| is_root(d))
        .map(Path::to_path_buf)
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let Some((command, rest)) = args.split_first() else {
        eprint!("{USAGE}");
        return ExitCode::from(2);
    };
    if matches!(command.as_str(), "help" | "--help" | "-h") {
        print!("{USAGE}");
        return ExitCode::SUCCESS;
    }
    let root = match repo_root() {
        Ok(r) => r,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::from(2);
        }
    };
    let result = match command.as_str() {
        "regen" => match regen::Options::parse(rest) {
            Ok(opts) => regen::run(&root, &opts),
            Err(msg) => {
                eprintln!("error: {msg}\n\n{USAGE}");
                return ExitCode::from(2);
            }
        },
        "bench" => match bench::Options::parse(rest) {
            Ok(opts) => bench::run_bench(&root, &opts),
            Err(msg) => {
                eprintln!("error: {msg}\n\n{USAGE}");
                return ExitCode::from(2);
            }
        },
        "try-model" if rest.is_empty() => try_model::run(&root),
        other => {
            eprintln!("error: unknown command {other:?}\n\n{USAGE}");
            return ExitCode::from(2);
        }
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}

#[cfg(test)]
mod tidy;

#[cfg(test)]
mod tests {
    use super::workspace_root;

    /// The root is found from where xtask runs, in any copy of the tree: from the root itself,
    /// from a folder below it and from a member crate with its own Cargo.toml, and nowhere
    /// outside a workspace (the compile-time path is never the answer).
    #[test]
    fn the_repository_is_found_from_the_current_directory() {
        let tmp = tempfile::tempdir().unwrap();
        let copy = tmp.path().join("moved-checkout");
        for dir in ["xtask", "crates/member/src"] {
            std::fs::create_dir_all(copy.join(dir)).unwrap();
        }
        std::fs::write(
            copy.join("Cargo.toml"),
            "[workspace]\nmembers = [\"crates/*\"]\n",
        )
        .unwrap();
        std::fs::write(
            copy.join("xtask/Cargo.toml"),
            "[package]\nname = \"xtask\"\n",
        )
        .unwrap();
        std::fs::write(
            copy.join("crates/member/Cargo.toml"),
            "[package]\nname = \"m\"\n",
        )
        .unwrap();
        for start in ["", "crates/member", "crates/member/src"] {
            assert_eq!(
                workspace_root(&copy.join(start)),
                Some(copy.clone()),
                "{start}"
            );
        }
        assert_eq!(workspace_root(tmp.path()), None);
        // The compile-time checkout is not where this copy's root is.
        assert_ne!(
            workspace_root(&copy),
            std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
                .parent()
                .map(|p| p.to_path_buf())
        );
    }
}
