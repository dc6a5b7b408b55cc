//! Project automation: `cargo xtask regen [--check] [--skip-derive]`, `cargo xtask bench [--quick]`,
//! `cargo xtask try-model`.
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
//! rendered instead of a fresh derivation (no Python needed).

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
  regen [--check] [--skip-derive]
      Re-derive the kernels (Python/CasADi in .venv), render them and update
      generated/ir, generated/src/kernels and docs/errata.md.
      --check        write nothing; print diffs and fail if anything is stale
      --skip-derive  render the checked-in generated/ir (no Python needed)
  bench [--quick] [--no-peers]
      The accuracy/cost study: both integrators x tolerances on every case against
      a reference, the SciPy, heyoka and OpenSees peers (installed into .venv from
      bench/requirements.txt), written to docs/accuracy.md and docs/img/.
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

/// The repository root (the parent of this crate's directory).
pub fn repo_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("xtask lives one level below the repository root")
        .to_path_buf()
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let Some((command, rest)) = args.split_first() else {
        eprint!("{USAGE}");
        return ExitCode::from(2);
    };
    let result = match command.as_str() {
        "regen" => match regen::Options::parse(rest) {
            Ok(opts) => regen::run(&repo_root(), &opts),
            Err(msg) => {
                eprintln!("error: {msg}\n\n{USAGE}");
                return ExitCode::from(2);
            }
        },
        "bench" => match bench::Options::parse(rest) {
            Ok(opts) => bench::run_bench(&repo_root(), &opts),
            Err(msg) => {
                eprintln!("error: {msg}\n\n{USAGE}");
                return ExitCode::from(2);
            }
        },
        "try-model" if rest.is_empty() => try_model::run(&repo_root()),
        "help" | "--help" | "-h" => {
            print!("{USAGE}");
            return ExitCode::SUCCESS;
        }
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
