//! `cargo xtask bench [--quick]`: the accuracy/cost study and its peers, into docs/accuracy.md.
//!
//! 1. the project venv (`.venv`, derive/requirements.txt, see `venv.rs`) plus the peers' pins of
//!    `bench/requirements.txt` (SciPy, openseespy, heyoka), re-installed when their hash changes (own stamp);
//! 2. `rocking-bench run` (release build): both integrators × tolerances on every case, errors
//!    against the reference, CPU times → `target/bench/{rust,cases}.json`;
//! 3. the SciPy peer `bench/scipy_peer.py` → `target/bench/scipy.json`;
//! 4. the heyoka peer `bench/heyoka_peer.py` → `target/bench/heyoka.json`, then the targets'
//!    matched points timed again in alternated rounds, `bench/paired.py` → `paired.json`;
//! 5. the OpenSees peer `bench/opensees_rocking.py` → `target/bench/opensees.json`;
//! 6. `rocking-bench report` → `docs/accuracy.md`, `docs/reference/accuracy-study.md`,
//!    `docs/img/accuracy-*.{json,svg,png}` (with
//!    `--quick`: `target/bench-quick/docs/`, so the full study's doc is never replaced).
//!
//! A peer that fails is reported in the doc; the Rust study failing fails the command.

use crate::venv::{fnv1a64, run};
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Instant;

use crate::Result;

const STAMP: &str = ".rocking-bench-requirements.stamp";

/// Command-line options of `bench`.
#[derive(Debug, Default, Clone, Copy, PartialEq, Eq)]
pub struct Options {
    /// Fewer tolerances and cases (a minute or two).
    pub quick: bool,
    /// Skip the Python peers (Rust study and report only).
    pub no_peers: bool,
}

impl Options {
    /// Parses the arguments following `bench`.
    pub fn parse(args: &[String]) -> Result<Options, String> {
        let mut opts = Options::default();
        for arg in args {
            match arg.as_str() {
                "--quick" => opts.quick = true,
                "--no-peers" => opts.no_peers = true,
                other => return Err(format!("unknown argument {other:?} for bench")),
            }
        }
        Ok(opts)
    }
}

/// Installs the peers' pins into the project venv when `bench/requirements.txt` changed.
fn ensure_peers(root: &Path, python: &Path) -> Result<()> {
    let req = root.join("bench").join("requirements.txt");
    let mut pins = std::fs::read(&req).map_err(|e| format!("{}: {e}", req.display()))?;
    pins.extend(std::fs::read(root.join("derive").join("requirements.txt")).unwrap_or_default());
    let venv = root.join(".venv");
    let stamp = venv.join(STAMP);
    let want = format!("fnv1a64 {:016x} bench/requirements.txt\n", fnv1a64(&pins));
    if std::fs::read_to_string(&stamp).unwrap_or_default() == want {
        println!(
            "xtask: {} is up to date with bench/requirements.txt",
            venv.display()
        );
        return Ok(());
    }
    println!("xtask: installing the pinned peer packages of bench/requirements.txt");
    run(Command::new(python)
        .args(["-m", "pip", "install", "--disable-pip-version-check", "-r"])
        .arg(&req))?;
    std::fs::write(&stamp, want).map_err(|e| format!("{}: {e}", stamp.display()))?;
    Ok(())
}

fn target_dir(root: &Path) -> PathBuf {
    std::env::var_os("CARGO_TARGET_DIR").map_or_else(|| root.join("target"), PathBuf::from)
}

/// Runs the whole study.
pub fn run_bench(root: &Path, opts: &Options) -> Result<()> {
    let start = Instant::now();
    // --quick keeps its results and its doc under target/bench-quick, so that it never replaces
    // the full study's docs/accuracy.md.
    let out = target_dir(root).join(if opts.quick { "bench-quick" } else { "bench" });
    let docs = if opts.quick {
        out.join("docs")
    } else {
        root.join("docs")
    };
    std::fs::create_dir_all(&out).map_err(|e| format!("{}: {e}", out.display()))?;
    let python = if opts.no_peers {
        None
    } else {
        let py = crate::venv::ensure(root)?;
        ensure_peers(root, &py)?;
        Some(py)
    };
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".to_string());
    run(Command::new(&cargo)
        .args(["build", "--release", "-p", "rocking-bench"])
        .current_dir(root))?;
    let bin = target_dir(root).join("release").join("rocking-bench");
    let mut study = Command::new(&bin);
    study.arg("run").arg("--out").arg(&out).current_dir(root);
    if opts.quick {
        study.arg("--quick");
    }
    run(&mut study)?;
    for f in ["scipy.json", "heyoka.json", "paired.json", "opensees.json"] {
        let _ = std::fs::remove_file(out.join(f));
    }
    if let Some(py) = &python {
        let mut scipy = Command::new(py);
        scipy
            .arg(root.join("bench").join("scipy_peer.py"))
            .arg(out.join("cases.json"))
            .arg(out.join("scipy.json"))
            .env("PYTHONPATH", root.join("derive"))
            .current_dir(root);
        if opts.quick {
            scipy.arg("--quick");
        }
        if let Err(e) = run(&mut scipy) {
            eprintln!("xtask: warning: the SciPy peer failed ({e}); the report leaves it out");
        }
        let mut hy = Command::new(py);
        hy.arg(root.join("bench").join("heyoka_peer.py"))
            .arg(out.join("cases.json"))
            .arg(out.join("heyoka.json"))
            .env("PYTHONPATH", root.join("derive"))
            .current_dir(root);
        if opts.quick {
            hy.arg("--quick");
        }
        match run(&mut hy) {
            Err(e) => {
                eprintln!("xtask: warning: the heyoka peer failed ({e}); the report leaves it out")
            }
            Ok(()) => {
                // The targets' matched points again, both tools timed in the same minutes.
                let mut paired = Command::new(py);
                paired
                    .arg(root.join("bench").join("paired.py"))
                    .arg("--dir")
                    .arg(&out)
                    .arg("--bin")
                    .arg(&bin)
                    .env("PYTHONPATH", root.join("derive"))
                    .current_dir(root);
                if opts.quick {
                    paired.args(["--rounds", "3"]);
                }
                if let Err(e) = run(&mut paired) {
                    eprintln!("xtask: warning: the paired rounds failed ({e}); the report leaves them out");
                }
            }
        }
        let mut os = Command::new(py);
        os.arg(root.join("bench").join("opensees_rocking.py"))
            .arg(out.join("rust.json"))
            .arg(out.join("opensees.json"))
            .current_dir(root);
        if opts.quick {
            os.arg("--quick");
        }
        if let Err(e) = run(&mut os) {
            eprintln!("xtask: warning: the OpenSees peer failed ({e}); the report leaves it out");
        }
    }
    run(Command::new(&bin)
        .arg("report")
        .arg("--dir")
        .arg(&out)
        .arg("--docs")
        .arg(&docs)
        .current_dir(root))?;
    println!(
        "xtask: bench done in {:.0} s: {}/accuracy.md, {}/img/accuracy-*.{{json,svg,png}} (raw results in {})",
        start.elapsed().as_secs_f64(),
        docs.display(),
        docs.display(),
        out.display()
    );
    Ok(())
}
