//! The accuracy/cost study of the rocking solver (`cargo xtask bench`).
//!
//! `rocking-bench run [--quick] --out DIR` runs every case with each integrator (dopri5, dop853, taylor) over a range of
//! tolerances, measures the error of each answer against a reference solution (DOP853 at 1e-14,
//! itself checked against 1e-15), the CPU time and the RHS evaluations, and writes
//! `DIR/rust.json` (results) and `DIR/cases.json` (the cases, for the SciPy peer).
//!
//! `rocking-bench report --dir DIR --docs DOCS` reads `rust.json` and, when present, `scipy.json`
//! and `opensees.json`, and writes `DOCS/accuracy.md` (one page, `report/summary.rs`),
//! `DOCS/reference/accuracy-study.md` (every case, `report.rs`) and the work-precision diagrams
//! `DOCS/img/accuracy-*.{json,svg,png}` (each diagram's data and its images).
//!
//! `rocking-bench redraw --docs DOCS` draws the diagrams again from their data.

mod diagram;
mod report;
mod study;

use std::path::PathBuf;
use std::process::ExitCode;

const USAGE: &str = "\
usage: rocking-bench run [--quick] [--out DIR]
       rocking-bench report [--dir DIR] [--docs DOCS]
       rocking-bench redraw [--docs DOCS]
       rocking-bench probe CASE METHOD TOL [SECONDS]
       rocking-bench pairs [--dir DIR]

run     the accuracy/cost study (dopri5, dop853, taylor; tolerances 1e-3, 3e-4, 1e-4, ..., 3e-12,
        1e-12, taylor also 1e-13 and 1e-14, dop853 also 1e-13; reference DOP853 1e-14);
        writes DIR/rust.json and DIR/cases.json (default DIR: target/bench)
        --quick  fewer tolerances and cases (a minute or two)
report  writes DOCS/accuracy.md, DOCS/reference/accuracy-study.md and
        DOCS/img/accuracy-*.{json,svg,png} from
        DIR/{rust,scipy,heyoka,opensees}.json (default DOCS: docs)
redraw  draws DOCS/img/accuracy-*.{svg,png} again from DOCS/img/accuracy-*.json
probe   one case of the study at one method and tolerance: CPU per simulation (median over
        SECONDS, default 1), steps, evaluations and the errors against the reference
pairs   prints, as JSON, the study's matched points at the heyoka targets' error levels
        (per case and level: heyoka's tolerance, the cheapest Rust configuration and preset),
        from DIR/{rust,heyoka}.json; `bench/paired.py` times them in alternated rounds
";

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let mut quick = false;
    let mut dir = PathBuf::from("target/bench");
    let mut docs = PathBuf::from("docs");
    let Some((cmd, rest)) = args.split_first() else {
        eprint!("{USAGE}");
        return ExitCode::from(2);
    };
    if cmd == "probe" {
        let (case, method) = (rest.first(), rest.get(1));
        let tol = rest.get(2).and_then(|t| t.parse::<f64>().ok());
        let seconds = rest.get(3).map_or(Some(1.0), |s| s.parse::<f64>().ok());
        let (Some(case), Some(method), Some(tol), Some(seconds)) = (case, method, tol, seconds)
        else {
            eprint!("probe needs CASE METHOD TOL [SECONDS]\n{USAGE}");
            return ExitCode::from(2);
        };
        return match study::probe(case, method, tol, seconds) {
            Ok(()) => ExitCode::SUCCESS,
            Err(e) => {
                eprintln!("rocking-bench: error: {e}");
                ExitCode::from(2)
            }
        };
    }
    let mut it = rest.iter();
    while let Some(a) = it.next() {
        match a.as_str() {
            "--quick" => quick = true,
            "--out" | "--dir" => match it.next() {
                Some(v) => dir = PathBuf::from(v),
                None => {
                    eprint!("{a} needs a value\n{USAGE}");
                    return ExitCode::from(2);
                }
            },
            "--docs" => match it.next() {
                Some(v) => docs = PathBuf::from(v),
                None => {
                    eprint!("--docs needs a value\n{USAGE}");
                    return ExitCode::from(2);
                }
            },
            other => {
                eprint!("unknown argument {other:?}\n{USAGE}");
                return ExitCode::from(2);
            }
        }
    }
    let result = match cmd.as_str() {
        "run" => study::run(quick, &dir),
        "report" => report::run(&dir, &docs),
        "pairs" => report::pairs(&dir).map(|rows| {
            println!(
                "{}",
                serde_json::to_string_pretty(&rows).expect("JSON values serialize")
            );
        }),
        "redraw" => diagram::redraw(&docs).map(|files| {
            eprintln!(
                "redrew {} files in {}",
                files.len(),
                docs.join("img").display()
            );
        }),
        "help" | "--help" | "-h" => {
            print!("{USAGE}");
            return ExitCode::SUCCESS;
        }
        other => Err(format!("unknown command {other:?}").into()),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("rocking-bench: error: {e}");
            ExitCode::FAILURE
        }
    }
}

/// Error type of the bench.
pub type Result<T, E = Box<dyn std::error::Error>> = std::result::Result<T, E>;
