//! docs/reference/accuracy-study.md and the work-precision diagrams, from the JSON results of the
//! study and the peers: every case (`cases.rs`), the presets and the classes of runs
//! (`presets.rs`), the peers (`peers.rs`) and the matched points against heyoka (`heyoka.rs`). The
//! one-page summary, docs/accuracy.md, is `summary.rs`.

mod cases;
mod heyoka;
mod peers;
mod presets;
mod summary;

pub(crate) use heyoka::paired_table;
pub use heyoka::pairs;
pub(crate) use presets::{class_of, point_of, presets_measured};

use std::fmt::Write as _;
use std::path::Path;

use serde_json::Value;

use crate::Result;

fn f(v: &Value) -> f64 {
    v.as_f64().unwrap_or(f64::NAN)
}

pub(crate) fn sci(x: f64) -> String {
    if x.is_nan() {
        "–".into()
    } else if x == 0.0 {
        "0".into()
    } else {
        format!("{x:.1e}")
    }
}

fn ms(x: f64) -> String {
    if x.is_nan() {
        "–".into()
    } else if x < 1e-3 {
        format!("{:.1} µs", x * 1e6)
    } else if x < 1.0 {
        format!("{:.2} ms", x * 1e3)
    } else {
        format!("{x:.2} s")
    }
}

fn err(p: &Value, key: &str) -> f64 {
    f(&p["errors"][key])
}

/// Whether the reference resolves measure `k` to a tenth of `target` (its difference to the
/// check is no larger; a NaN, no check, counts as resolved).
pub(crate) fn resolves(check: &Value, k: &str, target: f64) -> bool {
    f(&check["errors"][k]).partial_cmp(&(0.1 * target)) != Some(std::cmp::Ordering::Greater)
}

/// The error a preset is judged by: the worse of max θ/α (absolute) and impact τ (relative), leaving out a measure
/// that the reference itself does not resolve to a tenth of `target` (its difference to the
/// check, `check`, is larger).
pub(crate) fn combined(p: &Value, check: &Value, target: f64) -> f64 {
    if p["failed"].is_string() {
        return f64::INFINITY;
    }
    let resolved = |k: &str| resolves(check, k, target);
    let a = if resolved("max_theta") {
        err(p, "max_theta")
    } else {
        0.0
    };
    let b = if resolved("impact_time_rel") {
        err(p, "impact_time_rel")
    } else {
        0.0
    };
    let mut e = a.max(b);
    if err(p, "overturn_mismatch") > 0.0 {
        e = f64::INFINITY;
    }
    e
}

/// The study's results and the peers' as read from the study's directory (a peer that did not
/// run is `None`), the Python peers' answers judged against the Rust reference.
struct Results {
    rust: Value,
    cases: Vec<Value>,
    scipy: Option<Value>,
    heyoka: Option<Value>,
    paired: Option<Value>,
    opensees: Option<Value>,
}

impl Results {
    fn read(dir: &Path) -> Result<Self> {
        let rust: Value = serde_json::from_str(&std::fs::read_to_string(dir.join("rust.json"))?)?;
        let optional = |name: &str| -> Option<Value> {
            std::fs::read_to_string(dir.join(name))
                .ok()
                .and_then(|s| serde_json::from_str(&s).ok())
        };
        let (mut scipy, mut heyoka) = (optional("scipy.json"), optional("heyoka.json"));
        let cases = rust["cases"].as_array().cloned().unwrap_or_default();
        for peer in [scipy.as_mut(), heyoka.as_mut()].into_iter().flatten() {
            judge(peer, &cases);
        }
        Ok(Results {
            rust,
            cases,
            scipy,
            heyoka,
            paired: optional("paired.json"),
            opensees: optional("opensees.json"),
        })
    }

    /// A peer's entry for the case named `name`.
    fn peer_case(peer: &Option<Value>, name: &Value) -> Option<Value> {
        peer.as_ref().and_then(|s| {
            s["cases"]
                .as_array()
                .and_then(|l| l.iter().find(|c| c["name"] == *name).cloned())
        })
    }
}

pub fn run(dir: &Path, docs: &Path) -> Result<()> {
    let r = Results::read(dir)?;
    let img = docs.join("img");
    std::fs::create_dir_all(&img)?;
    let mut md = String::new();
    let w = &mut md;
    cases::header(w, &r.rust)?;
    cases::tables(w, &r, &img)?;
    let standard = presets::chosen(w, &r.cases)?;
    presets::by_class(w, &r.cases)?;
    peers::scipy(w, &r, dir)?;
    peers::heyoka(w, &r, dir)?;
    peers::opensees(w, &r, dir)?;
    cases::overhead(w, &r)?;
    writeln!(w, "\nStudy wall time: {:.0} s.", f(&r.rust["study_wall_s"]))?;
    let page = summary::page(&r.rust, &r.cases, &standard, r.paired.as_ref())?;
    let reference = docs.join("reference");
    std::fs::create_dir_all(&reference)?;
    std::fs::write(reference.join("accuracy-study.md"), md)?;
    std::fs::write(docs.join("accuracy.md"), page)?;
    eprintln!(
        "wrote {}, {} and {}/accuracy-*.{{json,svg,png}}",
        docs.join("accuracy.md").display(),
        reference.join("accuracy-study.md").display(),
        img.display()
    );
    Ok(())
}

/// A Python peer's answers judged against the Rust reference of each case it ran.
fn judge(peer: &mut Value, cases: &[Value]) {
    if let Some(list) = peer["cases"].as_array_mut() {
        for c in list {
            if let Some(rc) = cases.iter().find(|r| r["name"] == c["name"]) {
                add_scipy_errors(rc, c);
            }
        }
    }
}

/// A Python peer's answers (SciPy, heyoka) against the Rust reference and the Rust DOP853 run at
/// the same tolerance.
fn add_scipy_errors(rust_case: &Value, sp: &mut Value) {
    let reference = &rust_case["reference"]["answers"];
    let cells: Vec<usize> = sp["cells"]
        .as_array()
        .into_iter()
        .flatten()
        .filter_map(|c| c.as_u64())
        .map(|c| c as usize)
        .collect();
    let pick =
        |answers: &Value| -> Vec<Value> { cells.iter().map(|&i| answers[i].clone()).collect() };
    let ref_cells = pick(reference);
    let amps: Option<Vec<f64>> = rust_case["amplitudes"]
        .as_array()
        .map(|a| cells.iter().map(|&i| f(&a[i])).collect());
    let to_answers = |v: &[Value]| -> Vec<crate::study::Answer> {
        v.iter()
            .map(|a| serde_json::from_value(fill(a)).expect("answer"))
            .collect()
    };
    let r = to_answers(&ref_cells);
    if let Some(points) = sp["points"].as_array_mut() {
        for p in points {
            let Some(ans) = p["answers"].as_array() else {
                continue;
            };
            let a = to_answers(ans);
            let e = crate::study::errors(&a, &r, amps.as_deref());
            p["errors"] = serde_json::to_value(e).unwrap();
            // agreement with the Rust DOP853 run at the same tolerance
            let tol = f(&p["tol"]);
            if let Some(rp) = rust_case["points"]
                .as_array()
                .into_iter()
                .flatten()
                .find(|q| q["method"] == "dop853" && (f(&q["tol"]) / tol - 1.0).abs() < 1e-9)
            {
                if let Some(ra) = rp["answers"].as_array() {
                    let rr = to_answers(&pick(&Value::Array(ra.clone())));
                    p["agreement"] =
                        serde_json::to_value(crate::study::errors(&a, &rr, amps.as_deref()))
                            .unwrap();
                    p["rust_cpu_s"] = rp["cpu_s"].clone();
                }
            }
        }
    }
}

/// Fills fields the Python answers do not have (energy) so they deserialize as `Answer`.
fn fill(a: &Value) -> Value {
    let mut a = a.clone();
    if a.get("energy_residual").is_none() {
        a["energy_residual"] = Value::from(f64::NAN);
    }
    if a["energy_residual"].is_null() {
        a["energy_residual"] = Value::from(0.0);
    }
    a
}
