//! docs/reference/accuracy-study.md (every case, method and tolerance, the peers) and the
//! work-precision diagrams, from the JSON results of the study and peers; the one-page summary,
//! docs/accuracy.md, is `summary.rs`.

use std::fmt::Write as _;
use std::path::Path;

use serde_json::Value;

use crate::diagram::{self, Diagram};
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

/// The error levels of issue 13's and issue 31's heyoka targets (2× at ≤ 1e-9, 3× at ≤ 1e-12),
/// and ≤ 1e-6.
const LEVELS: [f64; 3] = [1e-6, 1e-9, 1e-12];

/// Which measures judge a case at a level: those the reference resolves to a tenth of it.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Judged {
    Both,
    MaxThetaOnly,
    ImpactOnly,
    Neither,
}

/// A study point (a heyoka run or a Rust configuration) and its error by [`combined`].
type Met = Option<(Value, f64)>;

/// One case at one error level: the cheapest heyoka run, Rust configuration and preset that
/// meet it, all judged by the presets' error ([`combined`]: measures the reference does not
/// resolve to a tenth of the level left out, so that rounding noise below the reference's own
/// does not decide).
struct Match {
    case: String,
    level: f64,
    judged: Judged,
    heyoka: Met,
    /// Every heyoka tolerance that meets the level (the paired rounds time them all).
    heyoka_tols: Vec<f64>,
    rust: Met,
    /// The cheapest preset's configuration.
    preset: Met,
}

/// The points of `points` whose error meets `level`, with that error; the study's reference
/// configuration is not a candidate. `keep` filters the candidates further.
fn meeting<'a>(
    points: &'a Value,
    level: f64,
    check: &'a Value,
    keep: impl Fn(&Value) -> bool + 'a,
) -> impl Iterator<Item = (&'a Value, f64)> + 'a {
    points
        .as_array()
        .into_iter()
        .flatten()
        .filter(move |q| {
            !(q["method"] == "dop853" && (f(&q["tol"]) / crate::study::REF_TOL - 1.0).abs() < 1e-9)
                && keep(q)
        })
        .map(move |q| (q, combined(q, check, level)))
        .filter(move |(_, e)| *e <= level)
}

/// The cheapest point of `points` (by `key`) whose error meets `level` ([`meeting`]).
fn cheapest(
    points: &Value,
    key: &str,
    level: f64,
    check: &Value,
    keep: impl Fn(&Value) -> bool,
) -> Met {
    meeting(points, level, check, keep)
        .min_by(|a, b| f(&a.0[key]).total_cmp(&f(&b.0[key])))
        .map(|(q, e)| (q.clone(), e))
}

/// Whether a Rust study point ran configuration `a`.
fn is_config(q: &Value, a: rocking::Accuracy) -> bool {
    q["method"] == crate::study::method_name(a.method) && (f(&q["tol"]) / a.tol - 1.0).abs() < 1e-9
}

/// Every heyoka case at every level of [`LEVELS`], matched against the Rust study's `cases`.
fn matches(hy: &Value, cases: &[Value]) -> Vec<Match> {
    let mut out = Vec::new();
    for c in hy["cases"].as_array().into_iter().flatten() {
        let Some(rc) = cases.iter().find(|r| r["name"] == c["name"]) else {
            continue;
        };
        let check = &rc["check"];
        for level in LEVELS {
            let judged = match (
                resolves(check, "max_theta", level),
                resolves(check, "impact_time_rel", level),
            ) {
                (true, true) => Judged::Both,
                (true, false) => Judged::MaxThetaOnly,
                (false, true) => Judged::ImpactOnly,
                (false, false) => Judged::Neither,
            };
            let preset = rocking::Preset::ALL
                .into_iter()
                .filter_map(|p| {
                    cheapest(&rc["points"], "cpu_s", level, check, |q| {
                        is_config(q, p.accuracy())
                    })
                })
                .min_by(|a, b| f(&a.0["cpu_s"]).total_cmp(&f(&b.0["cpu_s"])));
            out.push(Match {
                case: c["name"].as_str().unwrap_or("").to_string(),
                level,
                judged,
                heyoka: cheapest(&c["points"], "seconds", level, check, |_| true),
                heyoka_tols: meeting(&c["points"], level, check, |_| true)
                    .map(|(q, _)| f(&q["tol"]))
                    .collect(),
                rust: cheapest(&rc["points"], "cpu_s", level, check, |_| true),
                preset,
            });
        }
    }
    out
}

/// The levels table: per case and level, the cheapest heyoka run against the cheapest Rust
/// configuration ([`matches`]).
fn levels_table(w: &mut String, hy: &Value, cases: &[Value]) -> Result<()> {
    writeln!(w, "At the error levels of the targets of issue 13: the cheapest heyoka run and the cheapest Rust configuration (either method, any tolerance but the reference's) whose error, the worse of max θ/α (absolute) and impact τ (relative) as for the presets, is at most the level (a measure the reference does not resolve to a tenth of the level is left out). Times as above.\n")?;
    writeln!(w, "| case | error ≤ | heyoka (tol: time, error) | Rust (config: time, error) | heyoka / Rust |\n|---|---|---|---|---|")?;
    let by_name: std::collections::HashMap<&str, &Value> = cases
        .iter()
        .map(|c| (c["name"].as_str().unwrap_or(""), c))
        .collect();
    for m in matches(hy, cases) {
        let (name, level) = (m.case.as_str(), m.level);
        let errors = &by_name[name]["check"]["errors"];
        let judged = match m.judged {
            Judged::Both => String::new(),
            Judged::MaxThetaOnly => format!(
                " (max θ/α only: the reference's impact τ to {})",
                sci(f(&errors["impact_time_rel"]))
            ),
            Judged::ImpactOnly => format!(
                " (impact τ only: the reference's max θ/α to {})",
                sci(f(&errors["max_theta"]))
            ),
            Judged::Neither => " (not resolved by the reference)".to_string(),
        };
        if m.judged == Judged::Neither {
            writeln!(w, "| `{name}` | {level:.0e}{judged} | – | – | – |")?;
            continue;
        }
        let h_txt = m.heyoka.as_ref().map_or("–".to_string(), |(q, e)| {
            format!(
                "{:.0e}: {}, {}",
                f(&q["tol"]),
                ms(f(&q["seconds"])),
                sci(*e)
            )
        });
        let r_txt = m.rust.as_ref().map_or("–".to_string(), |(q, e)| {
            let method = q["method"].as_str().unwrap_or("");
            format!(
                "{method} {:.0e}: {}, {}",
                f(&q["tol"]),
                ms(f(&q["cpu_s"])),
                sci(*e)
            )
        });
        let ratio = match (&m.heyoka, &m.rust) {
            (Some((hq, _)), Some((rq, _))) => {
                format!("**{:.2}×**", f(&hq["seconds"]) / f(&rq["cpu_s"]))
            }
            _ => "–".to_string(),
        };
        writeln!(
            w,
            "| `{name}` | {level:.0e}{judged} | {h_txt} | {r_txt} | {ratio} |"
        )?;
    }
    writeln!(w)?;
    Ok(())
}

/// The matched points of the targets' levels timed again in alternated rounds
/// (`bench/paired.py`'s `paired.json`): per round the ratio heyoka / Rust, median and range.
pub(crate) fn paired_table(w: &mut String, paired: &Value) -> Result<()> {
    let us = |v: &Value| format!("{:.0}", 1e6 * f(v));
    let times = |v: &Value| {
        format!(
            "{} µs ({}–{})",
            us(&v["median"]),
            us(&v["min"]),
            us(&v["max"])
        )
    };
    let ratio = |v: &Value| {
        format!(
            "**{:.2}×** ({:.2}–{:.2})",
            f(&v["median"]),
            f(&v["min"]),
            f(&v["max"])
        )
    };
    writeln!(w, "The same matched points for the targets of issue 31, timed again in {} alternated rounds by `bench/paired.py` (after the heyoka peer in `cargo xtask bench`; by hand: `PYTHONPATH=derive .venv/bin/python bench/paired.py`): each round times every heyoka tolerance that meets the level (median of ≥ 5 runs, in one process, as the peer does) and takes the fastest of that round as heyoka's time (the table names the tolerance fastest in most rounds), and every Rust configuration (`rocking-bench probe`, {} s each), in reverse order every other round, so both tools run in the same minutes. Times: median over the rounds (smallest–largest); ratios: heyoka / Rust of each round, median (smallest–largest). *Preset*: the cheapest preset whose configuration meets the level.\n", paired["rounds"], f(&paired["rust_seconds"]))?;
    writeln!(w, "| case | error ≤ | heyoka | Rust, cheapest configuration | heyoka / Rust | cheapest preset | heyoka / preset |\n|---|---|---|---|---|---|---|")?;
    for r in paired["rows"].as_array().into_iter().flatten() {
        let config = |c: &Value| {
            if c.is_null() {
                return ("–".to_string(), "–".to_string());
            }
            let label = match c["name"].as_str() {
                Some(n) => format!(
                    "`{n}` ({} {:.0e})",
                    c["method"].as_str().unwrap_or(""),
                    f(&c["tol"])
                ),
                None => format!(
                    "{} {:.0e}",
                    c["method"].as_str().unwrap_or(""),
                    f(&c["tol"])
                ),
            };
            (
                format!("{label}: {}", times(&c["seconds"])),
                ratio(&c["ratio"]),
            )
        };
        let (rust, rust_ratio) = config(&r["rust"]);
        let (preset, preset_ratio) = config(&r["preset"]);
        writeln!(
            w,
            "| `{}` | {:.0e} | {:.0e}: {} | {rust} | {rust_ratio} | {preset} | {preset_ratio} |",
            r["case"].as_str().unwrap_or(""),
            f(&r["level"]),
            f(&r["heyoka_tol"]),
            times(&r["heyoka_s"]),
        )?;
    }
    writeln!(w)?;
    Ok(())
}

/// The matched points of the targets' levels as JSON, for `bench/paired.py`: per case and level
/// resolved by the reference, heyoka's cheapest tolerance and every heyoka tolerance that meets
/// it (`candidates`: one draw of heyoka's time does not tell them apart, so the rounds time them
/// all), the cheapest Rust configuration and the cheapest preset that meet it (either may be
/// null).
pub fn pairs(dir: &Path) -> Result<Value> {
    let read = |name: &str| -> Result<Value> {
        let path = dir.join(name);
        let text = std::fs::read_to_string(&path)
            .map_err(|e| format!("{}: {e} (run `cargo xtask bench` first)", path.display()))?;
        Ok(serde_json::from_str(&text).map_err(|e| format!("{}: {e}", path.display()))?)
    };
    let (rust, mut hy) = (read("rust.json")?, read("heyoka.json")?);
    let cases = rust["cases"].as_array().cloned().unwrap_or_default();
    // heyoka's errors against the Rust reference, as the report measures them.
    for c in hy["cases"].as_array_mut().into_iter().flatten() {
        if let Some(rc) = cases.iter().find(|r| r["name"] == c["name"]) {
            add_scipy_errors(rc, c);
        }
    }
    let config = |q: &Value| serde_json::json!({"method": q["method"], "tol": q["tol"], "seconds": q["cpu_s"]});
    let rows: Vec<Value> = matches(&hy, &cases)
        .into_iter()
        .filter(|m| m.judged != Judged::Neither)
        .filter_map(|m| {
            let (h, _) = m.heyoka?;
            Some(serde_json::json!({
                "case": m.case,
                "level": m.level,
                "heyoka": {"tol": h["tol"], "seconds": h["seconds"], "candidates": m.heyoka_tols},
                "rust": m.rust.map(|(q, _)| config(&q)),
                "preset": m.preset.map(|(q, _)| {
                    // Every preset of that configuration (`fast` and `default` may share one).
                    let names: Vec<&str> = rocking::Preset::ALL
                        .into_iter()
                        .filter(|p| is_config(&q, p.accuracy()))
                        .map(|p| p.name())
                        .collect();
                    let mut c = config(&q);
                    c["name"] = names.join(", ").into();
                    c
                }),
            }))
        })
        .collect();
    Ok(Value::Array(rows))
}

/// A peer's results for one case: its series name in the diagrams and its case entry.
type Peer<'a> = (&'a str, &'a Value);

/// The work-precision diagram of a case: per error measure, the Rust methods' runs (without
/// the reference's own configuration) and the peers'.
fn diagram(case: &Value, peers: &[Peer]) -> Diagram {
    let measures = [
        ("max_theta", "error in max |θ|/α"),
        ("impact_time", "error in impact times τ"),
    ];
    let panels = measures
        .iter()
        .map(|&(key, label)| {
            let mut series = Vec::new();
            for (m, name) in [
                ("dopri5", "dopri5 (Rust)"),
                ("dop853", "dop853 (Rust)"),
                ("taylor", "taylor (Rust)"),
            ] {
                let points = case["points"]
                    .as_array()
                    .into_iter()
                    .flatten()
                    .filter(|p| p["method"] == m && !p["failed"].is_string())
                    .filter(|p| {
                        !(m == "dop853"
                            && (f(&p["tol"]) / crate::study::REF_TOL - 1.0).abs() < 1e-9)
                    })
                    .map(|p| [f(&p["cpu_s"]), err(p, key), f(&p["tol"])])
                    .filter(|p| p.iter().all(|v| v.is_finite()))
                    .collect();
                series.push(diagram::Series {
                    name: name.to_string(),
                    points,
                });
            }
            for (name, sp) in peers {
                let points = sp["points"]
                    .as_array()
                    .into_iter()
                    .flatten()
                    .filter(|p| p["errors"].is_object())
                    .map(|p| [f(&p["seconds"]), err(p, key), f(&p["tol"])])
                    .filter(|p| p.iter().all(|v| v.is_finite()))
                    .collect();
                series.push(diagram::Series {
                    name: name.to_string(),
                    points,
                });
            }
            diagram::DiagramPanel {
                label: label.to_string(),
                series,
            }
        })
        .collect();
    Diagram {
        title: case["title"]
            .as_str()
            .or(case["name"].as_str())
            .unwrap_or("")
            .to_string(),
        panels,
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

pub fn run(dir: &Path, docs: &Path) -> Result<()> {
    let rust: Value = serde_json::from_str(&std::fs::read_to_string(dir.join("rust.json"))?)?;
    let mut scipy: Option<Value> = std::fs::read_to_string(dir.join("scipy.json"))
        .ok()
        .and_then(|s| serde_json::from_str(&s).ok());
    let mut heyoka: Option<Value> = std::fs::read_to_string(dir.join("heyoka.json"))
        .ok()
        .and_then(|s| serde_json::from_str(&s).ok());
    let paired: Option<Value> = std::fs::read_to_string(dir.join("paired.json"))
        .ok()
        .and_then(|s| serde_json::from_str(&s).ok());
    let opensees: Option<Value> = std::fs::read_to_string(dir.join("opensees.json"))
        .ok()
        .and_then(|s| serde_json::from_str(&s).ok());
    let img = docs.join("img");
    std::fs::create_dir_all(&img)?;
    let cases = rust["cases"].as_array().cloned().unwrap_or_default();
    for peer in [scipy.as_mut(), heyoka.as_mut()].into_iter().flatten() {
        if let Some(list) = peer["cases"].as_array_mut() {
            for c in list {
                if let Some(rc) = cases.iter().find(|r| r["name"] == c["name"]) {
                    add_scipy_errors(rc, c);
                }
            }
        }
    }
    let peer_case = |peer: &Option<Value>, name: &Value| -> Option<Value> {
        peer.as_ref().and_then(|s| {
            s["cases"]
                .as_array()
                .and_then(|l| l.iter().find(|c| c["name"] == *name).cloned())
        })
    };
    let sp_case = |name: &Value| peer_case(&scipy, name);
    let hy_case = |name: &Value| peer_case(&heyoka, name);

    let quick = rust["quick"].as_bool().unwrap_or(false);
    let mut md = String::new();
    let w = &mut md;
    writeln!(w, "# Accuracy study: every case, method and tolerance\n")?;
    writeln!(
        w,
        "<!-- generated by `cargo xtask bench{}` (crates/rocking-bench, bench/); do not edit -->\n",
        if quick { " --quick" } else { "" }
    )?;
    writeln!(w, "Generated by `cargo xtask bench{}`{}. Every case runs with each integrator (Dormand–Prince 5(4) `dopri5`, `dop853`, and the Taylor method `taylor`) at each tolerance; errors are against a reference solution, DOP853 at {:.0e} (its convergence is shown below against {:.0e}). CPU time is the process CPU time per simulation, the median of repeated runs (repeated until ≥ {} s, at least 3 times; a run of more than five times that is timed once), for the whole simulated duration (no early stop), without event log, history or energy bookkeeping; the errors come from a separate diagnostic run of the same configuration with the event log, the per-step history and the energy bookkeeping on (these do not change the trajectory). RHS evaluations are per simulation. Machine: {} cores; load average after the study `{}`; other builds may have been running on the second core, so treat the last digit of timings as noise.\n",
        if quick { " --quick" } else { "" },
        if quick { " (quick: fewer tolerances and cases; run `cargo xtask bench` for the full study)" } else { "" },
        crate::study::REF_TOL, crate::study::CHECK_TOL, f(&rust["min_total_s"]), rust["cpus"], rust["loadavg_after"].as_str().unwrap_or(""))?;
    writeln!(w, "Error measures: **max θ/α**: |Δ max|θ|/α|; **impact τ**: for each significant reference impact (|θ'| ≥ 0.01 α p) the distance to the nearest impact of the run, max over impacts up to the first *branch divergence* (no impact of the run within {} τ: a grazing uplift or impact that one run takes and the other does not; counted in column *div*); **ovt**: runs whose overturning decision differs; **final**: max-norm of the difference of [θ/α, u/u_cr, θ'/(αp), u'/(u_cr ω_n)] at the end of the run; **energy**: the run's own energy-balance residual /E_ref (non-overturned runs); **boundary**: the smallest overturning amplitude a_p/(g tan α) of the spectrum slice, difference to the reference. *Kernel share*: RHS evaluations × ns per rocking RHS (timed in the same binary) / CPU time.\n", crate::study::BRANCH_GAP)?;

    writeln!(w, "## Cases\n")?;
    writeln!(w, "Each case stands for a class of runs (`study::Class`). The presets are chosen on the `standard` class, where their errors hold; the other classes are measured and their errors stated per preset in \"Each preset's error by class of run\" below.\n")?;
    writeln!(
        w,
        "| case | class | description | kernel variant |\n|---|---|---|---|"
    )?;
    for c in &cases {
        writeln!(
            w,
            "| `{}` | {} | {} | {} |",
            c["name"].as_str().unwrap_or(""),
            class_of(c),
            c["title"].as_str().unwrap_or(""),
            c["variant"].as_str().unwrap_or("")
        )?;
    }

    writeln!(
        w,
        "\n## The reference has converged (DOP853 {:.0e} against {:.0e})\n",
        crate::study::REF_TOL,
        crate::study::CHECK_TOL
    )?;
    writeln!(w, "| case | max θ/α | impact τ (abs) | impact τ (rel) | div | ovt | final state | boundary | energy residual of the reference |\n|---|---|---|---|---|---|---|---|---|")?;
    for c in &cases {
        let ch = &c["check"];
        if ch["failed"].is_string() {
            writeln!(
                w,
                "| `{}` | {:.0e} failed: {} | | | | | | | |",
                c["name"].as_str().unwrap_or(""),
                crate::study::CHECK_TOL,
                ch["failed"].as_str().unwrap_or("")
            )?;
            continue;
        }
        let e = |k: &str| f(&ch["errors"][k]);
        let ref_energy = c["reference"]["answers"]
            .as_array()
            .into_iter()
            .flatten()
            .filter(|a| a["overturned"] == false)
            .map(|a| f(&a["energy_residual"]).abs())
            .fold(0.0, f64::max);
        writeln!(
            w,
            "| `{}` | {} | {} | {} | {} | {} | {} | {} | {} |",
            c["name"].as_str().unwrap_or(""),
            sci(e("max_theta")),
            sci(e("impact_time")),
            sci(e("impact_time_rel")),
            e("branch_divergences"),
            e("overturn_mismatch"),
            sci(e("final_state")),
            sci(e("boundary")),
            sci(ref_energy)
        )?;
    }

    // Event location against Housner's exact impact times.
    for c in &cases {
        if let Some(ex) = c["exact"].as_object() {
            writeln!(
                w,
                "\n## Event location: impact times against Housner's exact solution\n"
            )?;
            writeln!(w, "Case `{}`: the exact impact times follow from the exact quarter period of the point-mass block (quadrature, verification.md §2) and the amplitude recursion with e = cos 2α. At the reference preset the largest relative error of the first {} impact times is **{}** (target ≤ 1e-10).\n", c["name"].as_str().unwrap_or(""), ex["compared"], sci(f(&ex["reference_rel_err"])))?;
            writeln!(w, "| method | tol | max rel. error of impact times vs exact | CPU time |\n|---|---|---|---|")?;
            for p in c["points"].as_array().into_iter().flatten() {
                writeln!(
                    w,
                    "| {} | {:.0e} | {} | {} |",
                    p["method"].as_str().unwrap_or(""),
                    f(&p["tol"]),
                    sci(f(&p["exact_rel_err"])),
                    ms(f(&p["cpu_s"]))
                )?;
            }
            let imp = ex["impacts"].as_array().cloned().unwrap_or_default();
            let refi = c["reference"]["answers"][0]["impacts"]
                .as_array()
                .cloned()
                .unwrap_or_default();
            writeln!(
                w,
                "\n| impact | exact τ | reference τ | rel. error |\n|---|---|---|---|"
            )?;
            for (k, (a, b)) in imp.iter().zip(&refi).take(8).enumerate() {
                writeln!(
                    w,
                    "| {} | {:.12} | {:.12} | {} |",
                    k + 1,
                    f(a),
                    f(b),
                    sci(((f(b) - f(a)) / f(a)).abs())
                )?;
            }
        }
    }

    writeln!(w, "\n## Work-precision per case\n")?;
    writeln!(w, "Diagrams: error against CPU time per simulation, log-log, one line per method and peer (SciPy's DOP853 and heyoka's Taylor integrator where they ran), each point one tolerance labelled with its exponent. Each diagram's data is beside it (`docs/img/accuracy-CASE.json`): `cargo run -p rocking-bench -- redraw` draws the images again from it.\n")?;
    for c in &cases {
        let name = c["name"].as_str().unwrap_or("case");
        let (sp, hy) = (sp_case(&c["name"]), hy_case(&c["name"]));
        let mut peers: Vec<Peer> = Vec::new();
        if let Some(sp) = &sp {
            peers.push(("SciPy DOP853", sp));
        }
        if let Some(hy) = &hy {
            peers.push(("heyoka Taylor", hy));
        }
        diagram(c, &peers).write(&img, &format!("accuracy-{name}"))?;
        writeln!(w, "### `{name}`\n\n{}\n", c["title"].as_str().unwrap_or(""))?;
        writeln!(
            w,
            "![work-precision {name}](../img/accuracy-{name}.png) ([SVG](../img/accuracy-{name}.svg))\n"
        )?;
        let slice = c["amplitudes"].is_array();
        if slice {
            writeln!(w, "Reference boundary: smallest overturning a_p/(g tan α) on the grid {}; bisected between the bracketing grid amplitudes {} to 1e-12 relative: **{:.12}** (DOP853 {:.0e} gives a boundary {} away). Column *boundary*: the error of the grid boundary; *bisected*: the error of the bisected boundary with that configuration. Times and RHS counts are per cell.\n",
                f(&c["reference"]["boundary"]), c["reference"]["bracket"], f(&c["reference"]["boundary_bisect"]), crate::study::CHECK_TOL, sci(f(&c["check"]["boundary_bisect_diff"])))?;
        }
        writeln!(w, "| method | tol | CPU time | RHS evals | steps | max θ/α | impact τ | impact τ rel | div | ovt | final state | energy | {}kernel share |", if slice { "boundary | bisected | " } else { "" })?;
        writeln!(
            w,
            "|---|---|---|---|---|---|---|---|---|---|---|---|{}---|",
            if slice { "---|---|" } else { "" }
        )?;
        for p in c["points"].as_array().into_iter().flatten() {
            let (m, tol) = (p["method"].as_str().unwrap_or(""), f(&p["tol"]));
            if let Some(fail) = p["failed"].as_str() {
                writeln!(
                    w,
                    "| {m} | {tol:.0e} | failed: {fail} |||||||||||{}",
                    if slice { "||" } else { "" }
                )?;
                continue;
            }
            writeln!(w, "| {m} | {tol:.0e} | {} | {:.0} | {:.0} | {} | {} | {} | {} | {} | {} | {} | {}{:.0} % |", ms(f(&p["cpu_s"])), f(&p["rhs"]), f(&p["steps"]),
                sci(err(p, "max_theta")), sci(err(p, "impact_time")), sci(err(p, "impact_time_rel")), err(p, "branch_divergences"), err(p, "overturn_mismatch"), sci(err(p, "final_state")), sci(err(p, "energy")),
                if slice { format!("{} | {} | ", sci(err(p, "boundary")), sci(f(&p["boundary_bisect_err"]))) } else { String::new() }, 100.0 * f(&p["kernel_share"]))?;
        }
        writeln!(w)?;
    }

    // Presets.
    writeln!(w, "## Accuracy presets\n")?;
    let mut configs: Vec<(String, f64)> = Vec::new();
    for p in cases
        .first()
        .and_then(|c| c["points"].as_array())
        .into_iter()
        .flatten()
    {
        configs.push((p["method"].as_str().unwrap_or("").to_string(), f(&p["tol"])));
    }
    // The presets are chosen on the standard class (rust.json without classes: every case).
    let standard: Vec<Value> = cases
        .iter()
        .filter(|c| class_of(c) == crate::study::Class::Standard.name())
        .cloned()
        .collect();
    let stats = |m: &str, tol: f64, target: f64| preset_stats(&standard, m, tol, target);
    let targets = rocking::Preset::ALL.map(|p| (p.name(), p.target()));
    let is_study_reference =
        |m: &str, t: f64| m == "dop853" && (t / crate::study::REF_TOL - 1.0).abs() < 1e-9;
    // The cheapest configuration (of `method` when given) meeting `target`.
    let cheapest = |target: f64, method: Option<&str>| {
        configs
            .iter()
            .filter(|(m, t)| !is_study_reference(m, *t) && method.is_none_or(|x| x == m))
            .map(|(m, t)| (m.clone(), *t, stats(m, *t, target)))
            .filter(|(_, _, s)| s.0 <= target)
            .min_by(|a, b| a.2 .1.total_cmp(&b.2 .1))
    };
    writeln!(w, "Chosen from the data above: for each target, the configuration (of the methods the preset allows) with the smallest geometric-mean CPU time over the `standard` cases whose worst error (the worse of the absolute error of max θ/α and the relative error of the impact times, over every such case and every cell of the slice) meets the target, with no failure and no differing overturning decision. A measure the reference does not resolve to a tenth of the target (its DOP853 {:.0e} vs {:.0e} difference is larger, e.g. the late impact times of `near-rigid`) is left out of that case's error. The study's reference itself (DOP853 {:.0e}) is not a candidate. *DOP853*: the cheapest DOP853 configuration that meets the target, what a preset runs on a motion without a Taylor series (`Preset::accuracy_for`), and its cost against the cheapest configuration of any method.\n", crate::study::REF_TOL, crate::study::CHECK_TOL, crate::study::REF_TOL)?;
    writeln!(w, "| preset | target | chosen | worst error (max θ/α abs., impact τ rel.) | worst final-state error | geo-mean CPU time | cheapest DOP853 (error, time) | DOP853 / cheapest of any method |\n|---|---|---|---|---|---|---|---|")?;
    let mut stale = Vec::new();
    let mut restricted = Vec::new();
    for (preset, (name, target)) in rocking::Preset::ALL.into_iter().zip(targets) {
        let among = preset.method_among().map(crate::study::method_name);
        let (any, dop) = (cheapest(target, None), cheapest(target, Some("dop853")));
        let dop_txt = dop
            .as_ref()
            .map_or("none meets it".to_string(), |(m, t, s)| {
                format!("{m} {t:.0e} ({}, {})", sci(s.0), ms(s.1))
            });
        let ratio = match (&dop, &any) {
            (Some(d), Some(a)) => format!("{:.2}×", d.2 .1 / a.2 .1),
            _ => "–".to_string(),
        };
        match cheapest(target, among) {
            Some((m, t, s)) => {
                writeln!(
                    w,
                    "| `{name}` | ≤ {target:.0e} | **{m} {t:.0e}**{} | {} | {} | {} | {dop_txt} | {ratio} |",
                    among.map_or(String::new(), |x| format!(" ({x} only)")),
                    sci(s.0),
                    sci(s.2),
                    ms(s.1)
                )?;
                if let (Some(x), Some((am, at, a_s))) = (among, &any) {
                    restricted.push(format!(
                        "`{name}` is chosen among {x} only (`Preset::method_among`): it is the independent check the tests and users hold the other presets to, which run the Taylor kernels, step rule and polynomial event roots. The cheapest of any method for its target, {am} {at:.0e} ({}, {}), would cost {:.2}× less: the price of that independence",
                        sci(a_s.0),
                        ms(a_s.1),
                        s.1 / a_s.1
                    ));
                }
                if let Some((_, dt, _)) = &dop {
                    if (preset.dop853_tol() / dt - 1.0).abs() > 1e-9 {
                        stale.push(format!(
                            "`{name}` runs DOP853 {:.0e} on a motion without a Taylor series, the study's cheapest DOP853 is {dt:.0e}",
                            preset.dop853_tol()
                        ));
                    }
                }
                let a = preset.accuracy();
                if crate::study::method_name(a.method) != m || (a.tol / t - 1.0).abs() > 1e-9 {
                    stale.push(format!(
                        "`{name}` is {} {:.0e}, the study's cheapest {m} {t:.0e}",
                        crate::study::method_name(a.method),
                        a.tol
                    ));
                }
            }
            None => writeln!(
                w,
                "| `{name}` | ≤ {target:.0e} | none meets it | | | | {dop_txt} | |"
            )?,
        }
    }
    if !restricted.is_empty() {
        writeln!(w, "\n{}.", restricted.join(". "))?;
    }
    writeln!(w)?;
    writeln!(w, "The presets as `Preset::accuracy` and `Preset::measured` (crates/rocking/src/options.rs, the table `rocking --help` prints) define them, measured here:\n")?;
    stale.extend(presets_measured(w, &standard)?);
    if stale.is_empty() {
        writeln!(w, "\noptions.rs agrees with this study (the cheapest configurations; errors and times within a factor of two).\n")?;
    } else {
        writeln!(w, "\n**options.rs is stale**: {}.\n", stale.join("; "))?;
        eprintln!("rocking-bench: options.rs is stale: {}", stale.join("; "));
    }

    by_class(w, &cases)?;

    // SciPy peer.
    writeln!(w, "\n## Peer: SciPy `solve_ivp` (DOP853 with events)\n")?;
    match &scipy {
        None => writeln!(w, "Not run (no {}/scipy.json).\n", dir.display())?,
        Some(sp) => {
            writeln!(w, "`bench/scipy_peer.py`: the same model through the CasADi functions of the derivation package (no physics re-typed), the hybrid logic the Python peers' shared driver (`bench/hybrid.py`: the Rust driver's phases, impact policy, energy cap and rest rule), integrated by `solve_ivp(method='DOP853', events=...)` (terminal directional events, restart at every event and every kink of the excitation), at the same rtol and the same scaled atol as the Rust run. Python time: `time.perf_counter`, median of {} repeats (one when a run exceeds 20 s). Versions: {}. The spectrum slice runs every 4th cell (every 3rd in --quick). *Agreement*: SciPy against Rust DOP853 at the same tolerance; *error*: each against the Rust reference.\n", sp["repeats"], sp["versions"])?;
            writeln!(w, "| case | tol | SciPy s/sim | Rust s/sim (DOP853, same tol) | ratio | ratio at matched accuracy (cheapest Rust config with error ≤ SciPy's) | RHS SciPy / Rust | agreement max θ/α | agreement impact τ | agreement ovt | SciPy error max θ/α | SciPy error impact τ | Rust error max θ/α | Rust error impact τ |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")?;
            for c in sp["cases"].as_array().into_iter().flatten() {
                let rc = cases.iter().find(|r| r["name"] == c["name"]);
                for p in c["points"].as_array().into_iter().flatten() {
                    let tol = f(&p["tol"]);
                    if let Some(fail) = p["failed"].as_str() {
                        writeln!(
                            w,
                            "| `{}` | {tol:.0e} | failed: {fail} ||||||||||||",
                            c["name"].as_str().unwrap_or("")
                        )?;
                        continue;
                    }
                    let rp = rc.and_then(|rc| {
                        rc["points"].as_array().into_iter().flatten().find(|q| {
                            q["method"] == "dop853" && (f(&q["tol"]) / tol - 1.0).abs() < 1e-9
                        })
                    });
                    let (rt, rrhs) =
                        rp.map_or((f64::NAN, f64::NAN), |q| (f(&q["cpu_s"]), f(&q["rhs"])));
                    let st = f(&p["seconds"]);
                    // matched accuracy: the cheapest Rust configuration whose error (the worse of
                    // max θ/α and impact τ) is at most the SciPy run's
                    let e_sp = err(p, "max_theta").max(err(p, "impact_time"));
                    let matched = rc.and_then(|rc| {
                        rc["points"]
                            .as_array()
                            .into_iter()
                            .flatten()
                            .filter(|q| {
                                !q["failed"].is_string()
                                    && err(q, "max_theta").max(err(q, "impact_time")) <= e_sp
                            })
                            .filter(|q| {
                                !(q["method"] == "dop853"
                                    && (f(&q["tol"]) / crate::study::REF_TOL - 1.0).abs() < 1e-9)
                            })
                            .min_by(|a, b| f(&a["cpu_s"]).partial_cmp(&f(&b["cpu_s"])).unwrap())
                    });
                    let matched_txt = matched.map_or("–".to_string(), |q| {
                        format!(
                            "**{:.0}×** ({} {:.0e}, {})",
                            st / f(&q["cpu_s"]),
                            q["method"].as_str().unwrap_or(""),
                            f(&q["tol"]),
                            ms(f(&q["cpu_s"]))
                        )
                    });
                    writeln!(w, "| `{}` | {tol:.0e} | {} | {} | {:.0}× | {} | {:.2} | {} | {} | {} | {} | {} | {} | {} |", c["name"].as_str().unwrap_or(""), ms(st), ms(rt), st / rt, matched_txt, f(&p["nfev"]) / rrhs,
                        sci(f(&p["agreement"]["max_theta"])), sci(f(&p["agreement"]["impact_time"])), f(&p["agreement"]["overturn_mismatch"]),
                        sci(err(p, "max_theta")), sci(err(p, "impact_time")),
                        rp.map_or("–".into(), |q| sci(err(q, "max_theta"))), rp.map_or("–".into(), |q| sci(err(q, "impact_time"))))?;
                }
            }
            writeln!(w, "\nTarget: ≥ 1000× per simulation at matched accuracy. *ratio*: against the Rust DOP853 run at the same tolerance; *matched accuracy*: against the cheapest Rust configuration (either method, any tolerance of the study except the reference itself) whose error against the reference is at most the SciPy run's. A slice's times are per cell (SciPy: the sampled cells; Rust: all cells).\n")?;
        }
    }

    // heyoka peer.
    writeln!(
        w,
        "## Peer: heyoka.py (Taylor integrator compiled with LLVM, events as polynomial roots)\n"
    )?;
    match &heyoka {
        None => writeln!(w, "Not run (no {}/heyoka.json).\n", dir.display())?,
        Some(hy) => {
            writeln!(w, "`bench/heyoka_peer.py`: the same model, the derivation's CasADi instruction tapes replayed into heyoka expressions (rocking and contact right-hand sides, uplift functions; no physics re-typed) and integrated by heyoka's `taylor_adaptive` (compiled with LLVM at run time, with fast-math flags, not in compact mode: every tape is short enough to unroll) in the study's scaled state [θ/α, u/u_s, θ'/(αp), u'/u'_s] with tolerance = tol. heyoka's tolerance only sets its order, ⌈−ln tol / 2 + 1⌉ (its step rule does not see it otherwise: two tolerances of one order give the same answers), so its tolerances are the study's grid from 1e-5 to 1e-12 thinned to one per order, orders 7 to 15, the loosest of each. Uplift, impact and overturning are heyoka's terminal directional `t_event`s and the maxima of |θ| a non-terminal one; each span between kinks of the excitation is one `propagate_until` (records: the ground acceleration linear in time per segment, its coefficients runtime parameters). The per-event quantities (uplift functions, θ'' at lift-off, kinetic energy, impact maps) are the same tapes as straight-line Python functions, so no CasADi function runs during a simulation; the hybrid logic is the Python peers' shared driver (`bench/hybrid.py`: the Rust driver's phases, impact policy, energy cap and rest rule). The integrators are built once per variant, excitation kind and tolerance and reused by every run. Time: the process's CPU time (`time.process_time`, as Rust's), median of ≥ {} repeats (repeated for ≥ 0.5 s, one when a run exceeds 20 s), per simulation; the one-time LLVM compilation of the integrators (one rocking + contact pair per variant, excitation kind and tolerance) is not in it and is shown apart (total {:.1} s, compiled into a fresh temporary cache: heyoka 7.13 otherwise reuses machine code cached on disk by an earlier run). Versions: {}. The spectrum slice runs the SciPy peer's cells. The peer before this design (CasADi impact maps, a slower Python event loop) is in bench/NOTES.md. *Agreement*: heyoka against Rust DOP853 at the same tolerance; *error*: each against the Rust reference.\n", hy["repeats"], f(&hy["compile_s"]), hy["versions"])?;
            writeln!(w, "| case | tol | heyoka s/sim | compile (s) | Taylor steps | Rust s/sim (DOP853, same tol) | ratio | ratio at matched accuracy (cheapest Rust config with error ≤ heyoka's) | SciPy s/sim (same tol) | agreement max θ/α | agreement impact τ | agreement ovt | heyoka error max θ/α | heyoka error impact τ | Rust error max θ/α | Rust error impact τ |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")?;
            for c in hy["cases"].as_array().into_iter().flatten() {
                let rc = cases.iter().find(|r| r["name"] == c["name"]);
                let spc = sp_case(&c["name"]);
                for p in c["points"].as_array().into_iter().flatten() {
                    let tol = f(&p["tol"]);
                    let name = c["name"].as_str().unwrap_or("");
                    if let Some(fail) = p["failed"].as_str() {
                        writeln!(w, "| `{name}` | {tol:.0e} | failed: {fail} ||||||||||||||")?;
                        continue;
                    }
                    let same_tol = |q: &&Value| (f(&q["tol"]) / tol - 1.0).abs() < 1e-9;
                    let rp = rc.and_then(|rc| {
                        rc["points"]
                            .as_array()
                            .into_iter()
                            .flatten()
                            .filter(same_tol)
                            .find(|q| q["method"] == "dop853")
                    });
                    let sp_t = spc.as_ref().and_then(|s| {
                        s["points"]
                            .as_array()
                            .into_iter()
                            .flatten()
                            .filter(same_tol)
                            .find(|q| q["seconds"].is_number())
                            .map(|q| f(&q["seconds"]))
                    });
                    let rt = rp.map_or(f64::NAN, |q| f(&q["cpu_s"]));
                    let st = f(&p["seconds"]);
                    let e_hy = err(p, "max_theta").max(err(p, "impact_time"));
                    let matched = rc.and_then(|rc| {
                        rc["points"]
                            .as_array()
                            .into_iter()
                            .flatten()
                            .filter(|q| {
                                !q["failed"].is_string()
                                    && err(q, "max_theta").max(err(q, "impact_time")) <= e_hy
                            })
                            .filter(|q| {
                                !(q["method"] == "dop853"
                                    && (f(&q["tol"]) / crate::study::REF_TOL - 1.0).abs() < 1e-9)
                            })
                            .min_by(|a, b| f(&a["cpu_s"]).partial_cmp(&f(&b["cpu_s"])).unwrap())
                    });
                    let matched_txt = matched.map_or("–".to_string(), |q| {
                        format!(
                            "**{:.2}×** ({} {:.0e}, {})",
                            st / f(&q["cpu_s"]),
                            q["method"].as_str().unwrap_or(""),
                            f(&q["tol"]),
                            ms(f(&q["cpu_s"]))
                        )
                    });
                    writeln!(w, "| `{name}` | {tol:.0e} | {} | {:.1} | {:.0} | {} | {:.2}× | {} | {} | {} | {} | {} | {} | {} | {} | {} |", ms(st), f(&p["compile_s"]), f(&p["steps"]), ms(rt), st / rt, matched_txt, sp_t.map_or("–".into(), ms),
                        sci(f(&p["agreement"]["max_theta"])), sci(f(&p["agreement"]["impact_time"])), f(&p["agreement"]["overturn_mismatch"]),
                        sci(err(p, "max_theta")), sci(err(p, "impact_time")),
                        rp.map_or("–".into(), |q| sci(err(q, "max_theta"))), rp.map_or("–".into(), |q| sci(err(q, "impact_time"))))?;
                }
            }
            writeln!(w, "\n*ratio*: heyoka's time per simulation over the Rust DOP853 run's at the same tolerance (above 1: Rust faster); *matched accuracy*: over the cheapest Rust configuration (either method, any tolerance of the study except the reference itself) whose error against the reference is at most heyoka's. Both are process CPU times; heyoka's include its Python driver. A slice's times are per cell (heyoka: the sampled cells; Rust: all cells).\n")?;
            levels_table(w, hy, &cases)?;
            if let Some(paired) = &paired {
                paired_table(w, paired)?;
            }
        }
    }

    // OpenSees.
    writeln!(
        w,
        "## Peer: OpenSees (openseespy) on a rigid free-rocking block\n"
    )?;
    match &opensees {
        None => writeln!(w, "Not run (no {}/opensees.json).\n", dir.display())?,
        Some(o) => {
            if let Some(msg) = o["skipped"].as_str() {
                writeln!(w, "Skipped: {msg}\n")?;
            }
            if let Some(t) = o["text"].as_str() {
                writeln!(w, "{t}\n")?;
            }
            if let Some(rows) = o["rows"].as_array() {
                writeln!(w, "| tool | setting | wall time for the same duration | first-impact τ (quarter period) | rel. error vs Housner | period pT = 4 × first impact | rel. error vs Housner |\n|---|---|---|---|---|---|---|")?;
                for r in rows {
                    writeln!(
                        w,
                        "| {} | {} | {} | {:.9} | {} | {:.9} | {} |",
                        r["tool"].as_str().unwrap_or(""),
                        r["setting"].as_str().unwrap_or(""),
                        ms(f(&r["seconds"])),
                        f(&r["quarter"]),
                        sci(f(&r["quarter_err"])),
                        f(&r["period"]),
                        sci(f(&r["period_err"]))
                    )?;
                }
                writeln!(w)?;
            }
        }
    }

    // Overhead.
    writeln!(w, "## Time outside the kernels\n")?;
    writeln!(w, "Kernel cost per call, timed in the bench binary (best of 5 loops of 2·10⁶ calls; criterion's command is in docs/performance.md):\n")?;
    writeln!(
        w,
        "| variant | rocking RHS (ns) | contact RHS (ns) |\n|---|---|---|"
    )?;
    if let Some(k) = rust["kernels"].as_object() {
        for (v, x) in k {
            writeln!(
                w,
                "| {v} | {:.1} | {:.1} |",
                f(&x["rocking_rhs_ns"]),
                f(&x["contact_rhs_ns"])
            )?;
        }
    }
    writeln!(w, "\nKernel share of a simulation's CPU time = RHS evaluations × (f × rocking-RHS ns + (1 − f) × contact-RHS ns) / CPU time, f the fraction of accepted steps in a rocking phase (from the diagnostic run). The uplift and event functions evaluated by the driver are not counted as kernel time, and a kernel inlined into the integrator may run faster or slower than in the microbenchmark loop, so this is an estimate. The rest is the integrator, the event location, the dense output, the ground motion and the driver. Target: overhead (1 − share) ≤ 30 %.\n")?;
    writeln!(w, "| case | dopri5 1e-7 share | overhead | dop853 1e-10 share | overhead |\n|---|---|---|---|---|")?;
    for c in &cases {
        let get = |m: &str, t: f64| {
            c["points"]
                .as_array()
                .into_iter()
                .flatten()
                .find(|p| p["method"] == m && (f(&p["tol"]) / t - 1.0).abs() < 1e-9)
                .map_or(f64::NAN, |p| f(&p["kernel_share"]))
        };
        let (a, b) = (get("dopri5", 1e-7), get("dop853", 1e-10));
        writeln!(
            w,
            "| `{}` | {:.0} % | **{:.0} %** | {:.0} % | **{:.0} %** |",
            c["name"].as_str().unwrap_or(""),
            100.0 * a,
            100.0 * (1.0 - a),
            100.0 * b,
            100.0 * (1.0 - b)
        )?;
    }
    writeln!(w, "\nStudy wall time: {:.0} s.", f(&rust["study_wall_s"]))?;
    let page = crate::summary::page(&rust, &cases, &standard, paired.as_ref())?;
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

/// A configuration over the cases (the standard class when choosing presets): its worst
/// error by [`combined`] at `target`, geometric-mean CPU time, worst final-state error and
/// per-case times; a case without the configuration counts as an infinite error.
fn preset_stats(cases: &[Value], m: &str, tol: f64, target: f64) -> (f64, f64, f64, Vec<f64>) {
    let (mut worst, mut logsum, mut n, mut fin, mut times) =
        (0.0f64, 0.0f64, 0.0f64, 0.0f64, Vec::new());
    for c in cases {
        match point_of(c, m, tol) {
            Some(p) => {
                worst = worst.max(combined(p, &c["check"], target));
                fin = fin.max(err(p, "final_state"));
                let t = f(&p["cpu_s"]);
                times.push(t);
                if t.is_finite() {
                    logsum += t.ln();
                    n += 1.0;
                }
            }
            None => {
                worst = f64::INFINITY;
                times.push(f64::NAN);
            }
        }
    }
    (worst, (logsum / n.max(1.0)).exp(), fin, times)
}

/// The presets as options.rs defines them, measured on the standard cases (a table); returns
/// where options.rs is stale (its numbers off the study's by more than a factor of two).
pub(crate) fn presets_measured(w: &mut String, standard: &[Value]) -> Result<Vec<String>> {
    let mut stale = Vec::new();
    writeln!(w, "| preset | config | options.rs says (error, time) | measured worst error | measured geo-mean CPU time | per case |\n|---|---|---|---|---|---|")?;
    for preset in rocking::Preset::ALL {
        let a = preset.accuracy();
        let (m, t) = (crate::study::method_name(a.method), a.tol);
        let s = preset_stats(standard, m, t, preset.target());
        let said = preset.measured();
        let per: Vec<String> = standard
            .iter()
            .zip(&s.3)
            .map(|(c, x)| format!("{} {}", c["name"].as_str().unwrap_or(""), ms(*x)))
            .collect();
        writeln!(
            w,
            "| `{}` | {m} {t:.0e} | {}, {} | {} | {} | {} |",
            preset.name(),
            sci(said.error),
            ms(said.seconds),
            sci(s.0),
            ms(s.1),
            per.join(", ")
        )?;
        // The table in options.rs states the study's numbers to a factor of two.
        let off = |a: f64, b: f64| !(a / b).is_finite() || !(0.5..=2.0).contains(&(a / b));
        if off(said.error.max(1e-16), s.0.max(1e-16)) || off(said.seconds, s.1) {
            stale.push(format!(
                "`{}`: options.rs says {} and {}, measured {} and {}",
                preset.name(),
                sci(said.error),
                ms(said.seconds),
                sci(s.0),
                ms(s.1)
            ));
        }
    }
    Ok(stale)
}

/// The class of a study case (`study::Class`); a rust.json from before the classes is `standard`.
pub(crate) fn class_of(c: &Value) -> &str {
    c["class"]
        .as_str()
        .unwrap_or(crate::study::Class::Standard.name())
}

/// The point of configuration `method` at `tol` of a case.
pub(crate) fn point_of<'a>(c: &'a Value, method: &str, tol: f64) -> Option<&'a Value> {
    c["points"]
        .as_array()
        .into_iter()
        .flatten()
        .find(|p| p["method"] == method && (f(&p["tol"]) / tol - 1.0).abs() < 1e-9)
}

/// Each preset's error on each class of run: the worst over the class's cases of max θ/α
/// (absolute), the impact times (relative, up to the first branch divergence), the branch
/// divergences and the overturning decisions, with the reference's own resolution (DOP853
/// `REF_TOL` against `CHECK_TOL`) and an independent method's distance to it (Taylor at the
/// study's tightest tolerance): where those two are larger than a preset's target, the class does
/// not determine the answer to that target, and no preset can be held to it there.
fn by_class(w: &mut String, cases: &[Value]) -> Result<()> {
    use crate::study::{Class, CHECK_TOL, REF_TOL};
    writeln!(w, "\n## Each preset's error by class of run\n")?;
    writeln!(w, "The presets are chosen on the `standard` class (above). On the other classes each preset's configuration is measured against the same reference; the worst over the class's cases. *Reference resolution*: the reference against DOP853 {CHECK_TOL:.0e}; *Taylor vs reference*: the tightest Taylor configuration against the reference, an independent method (its own steps, event roots and kernels). Where both are small the reference is converged on that class, and a preset's error there is its own; a measure they do not resolve to a tenth of a target is not counted in the verdict (the answer is not determined that finely).\n")?;
    for class in Class::ALL {
        let members: Vec<&Value> = cases
            .iter()
            .filter(|c| class_of(c) == class.name())
            .collect();
        if members.is_empty() {
            continue;
        }
        let names: Vec<String> = members
            .iter()
            .map(|c| format!("`{}`", c["name"].as_str().unwrap_or("")))
            .collect();
        writeln!(
            w,
            "### `{}`: {} ({})\n",
            class.name(),
            class.description(),
            names.join(", ")
        )?;
        writeln!(w, "| configuration | max θ/α (abs.) | impact τ (rel.) | div | ovt | verdict |\n|---|---|---|---|---|---|")?;
        // The worst of each measure over the class; None when a case lacks the point.
        let worst = |pick: &dyn Fn(&Value) -> Option<Value>| -> Option<[f64; 4]> {
            let mut out = [0.0f64; 4];
            for c in &members {
                let e = pick(c)?;
                if e["failed"].is_string() {
                    return Some([f64::INFINITY; 4]);
                }
                for (k, key) in [
                    "max_theta",
                    "impact_time_rel",
                    "branch_divergences",
                    "overturn_mismatch",
                ]
                .iter()
                .enumerate()
                {
                    out[k] = out[k].max(f(&e["errors"][key]));
                }
            }
            Some(out)
        };
        let row = |w: &mut String, label: &str, e: Option<[f64; 4]>, verdict: &str| -> Result<()> {
            match e {
                Some(e) => writeln!(
                    w,
                    "| {label} | {} | {} | {} | {} | {verdict} |",
                    sci(e[0]),
                    sci(e[1]),
                    e[2],
                    e[3]
                )?,
                None => writeln!(w, "| {label} | not run | | | | |")?,
            }
            Ok(())
        };
        row(
            w,
            &format!("reference resolution (DOP853 {REF_TOL:.0e} vs {CHECK_TOL:.0e})"),
            worst(&|c| Some(c["check"].clone())),
            "",
        )?;
        let tightest = members[0]["points"]
            .as_array()
            .into_iter()
            .flatten()
            .filter(|p| p["method"] == "taylor")
            .map(|p| f(&p["tol"]))
            .fold(f64::INFINITY, f64::min);
        if tightest.is_finite() {
            row(
                w,
                &format!("Taylor {tightest:.0e} vs reference"),
                worst(&|c| point_of(c, "taylor", tightest).cloned()),
                "",
            )?;
        }
        for preset in rocking::Preset::ALL {
            let a = preset.accuracy();
            let (m, t) = (crate::study::method_name(a.method), a.tol);
            let target = preset.target();
            // The verdict: the presets' own error measure, case by case.
            let judged = members
                .iter()
                .map(|c| point_of(c, m, t).map(|p| combined(p, &c["check"], target)))
                .collect::<Option<Vec<f64>>>()
                .map(|v| v.into_iter().fold(0.0, f64::max));
            // Per case, the measures the reference does not resolve to a tenth of the target.
            let unresolved = |c: &Value| -> Vec<&str> {
                [("max_theta", "max θ/α"), ("impact_time_rel", "impact τ")]
                    .into_iter()
                    .filter(|(k, _)| !resolves(&c["check"], k, target))
                    .map(|(_, label)| label)
                    .collect()
            };
            let name = |c: &Value| format!("`{}`", c["name"].as_str().unwrap_or(""));
            let (mut neither, mut partly) = (Vec::new(), Vec::new());
            for c in &members {
                match unresolved(c).as_slice() {
                    [] => {}
                    [one] => partly.push(format!("{one} on {}", name(c))),
                    _ => neither.push(name(c)),
                }
            }
            let mut verdict = match judged {
                None => String::new(),
                Some(_) if neither.len() == members.len() => {
                    format!("not determined to {target:.0e} here")
                }
                Some(e) if e <= target => format!("meets ≤ {target:.0e}"),
                Some(e) if e.is_finite() => {
                    format!("**{:.0}× its target {target:.0e}**", e / target)
                }
                Some(_) => "**fails or decides an overturning otherwise**".to_string(),
            };
            if judged.is_some() && neither.len() < members.len() {
                if !neither.is_empty() {
                    verdict +=
                        &format!("; not determined to {target:.0e} on {}", neither.join(", "));
                }
                if !partly.is_empty() {
                    verdict += &format!(
                        "; {} not determined to {:.0e}",
                        partly.join(", "),
                        0.1 * target
                    );
                }
            }
            row(
                w,
                &format!("`{}` ({m} {t:.0e})", preset.name()),
                worst(&|c| point_of(c, m, t).cloned()),
                &verdict,
            )?;
        }
        writeln!(w)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    fn point(method: &str, tol: f64, cpu_s: f64, max_theta: f64, impact: f64) -> Value {
        json!({"method": method, "tol": tol, "cpu_s": cpu_s,
               "errors": {"max_theta": max_theta, "impact_time_rel": impact, "overturn_mismatch": 0.0}})
    }

    /// The per-class table judges each preset by the presets' own error on the class's cases
    /// only: a long record's amplified error is reported against the target there, and a measure
    /// the reference does not resolve does not decide.
    #[test]
    fn each_class_states_each_presets_error_on_its_own_cases() {
        let pts = |scale: f64| -> Vec<Value> {
            rocking::Preset::ALL
                .into_iter()
                .map(|p| {
                    let a = p.accuracy();
                    let m = crate::study::method_name(a.method);
                    point(m, a.tol, 1e-3, scale * a.tol, 0.0)
                })
                .collect()
        };
        let resolved = json!({"errors": {"max_theta": 0.0, "impact_time_rel": 0.0}});
        let cases = vec![
            json!({"name": "short", "class": "standard", "check": resolved, "points": pts(1.0)}),
            // 1e4 × each tolerance in max θ/α; the impact times unresolved (1e-3) do not count.
            json!({"name": "long", "class": "many-impacts",
                   "check": {"errors": {"max_theta": 1e-12, "impact_time_rel": 1e-3}},
                   "points": pts(1e4)}),
        ];
        let mut w = String::new();
        by_class(&mut w, &cases).expect("writes");
        let section = |name: &str| {
            let start = w
                .find(&format!("### `{name}`"))
                .expect("a section per class present");
            let rest = &w[start + 4..];
            rest[..rest.find("### ").unwrap_or(rest.len())].to_string()
        };
        let (standard, long) = (section("standard"), section("many-impacts"));
        assert!(
            !w.contains("### `chatter`"),
            "no section for a class without cases"
        );
        assert!(standard.contains("(`short`)") && long.contains("(`long`)"));
        let default = rocking::Preset::Default;
        let ratio = 1e4 * default.accuracy().tol / default.target();
        let line = |sec: &str, name: &str| {
            sec.lines()
                .find(|l| l.starts_with(&format!("| `{name}`")))
                .expect("a row per preset")
                .to_string()
        };
        assert!(
            line(&standard, "default").contains("meets ≤ 1e-6"),
            "{standard}"
        );
        assert!(!standard.contains("not determined"), "{standard}");
        // Resolved in max θ/α only: the verdict says the impact times are not determined.
        assert!(
            line(&long, "default").contains("; impact τ on `long` not determined to 1e-7"),
            "{long}"
        );
        assert!(
            line(&long, "default").contains(&format!("**{ratio:.0}× its target 1e-6**")),
            "{long}"
        );
    }

    /// The matched points are the cheapest that meet each level: the study's reference is never
    /// one, a preset is one of the presets' configurations, and a measure the reference does
    /// not resolve does not decide.
    #[test]
    fn matches_take_the_cheapest_point_meeting_each_level() {
        let accurate = rocking::Preset::Accurate.accuracy();
        let acc_method = crate::study::method_name(accurate.method);
        let rust_case = json!({
            "name": "c",
            // The reference resolves max θ/α to 1e-16 but the impact times only to 1e-9.
            "check": {"errors": {"max_theta": 1e-16, "impact_time_rel": 1e-9}},
            "points": [
                point("dop853", crate::study::REF_TOL, 1e-6, 0.0, 0.0),
                point("taylor", 3.3e-9, 2e-4, 5e-13, 5e-9),
                point("taylor", 3.3e-8, 1e-4, 5e-10, 5e-9),
                point(acc_method, accurate.tol, 4e-4, 1e-14, 5e-9),
            ],
        });
        let hy = json!({"cases": [{"name": "c", "points": [
            {"tol": 1e-7, "seconds": 1e-3, "errors": {"max_theta": 1e-11, "impact_time_rel": 1.0, "overturn_mismatch": 0.0}},
            {"tol": 1e-9, "seconds": 2e-3, "errors": {"max_theta": 1e-13, "impact_time_rel": 1.0, "overturn_mismatch": 0.0}},
        ]}]});
        let m = matches(&hy, &[rust_case]);
        assert_eq!(m.len(), LEVELS.len());
        let at = |level: f64| m.iter().find(|x| x.level == level).expect("every level");
        let tol = |p: &Met| p.as_ref().map(|(q, _)| f(&q["tol"]));
        // At 1e-9: the 3.3e-8 run; the impact times (5e-9 off), unresolved there, do not count.
        let m9 = at(1e-9);
        assert!(m9.judged == Judged::MaxThetaOnly);
        assert_eq!(tol(&m9.heyoka), Some(1e-7));
        assert_eq!(tol(&m9.rust), Some(3.3e-8));
        assert_eq!(tol(&m9.preset), Some(accurate.tol));
        // At 1e-12: 3.3e-8 fails; the dearer 3.3e-9 meets it; heyoka needs its 1e-9.
        let m12 = at(1e-12);
        assert_eq!(tol(&m12.heyoka), Some(1e-9));
        assert_eq!(tol(&m12.rust), Some(3.3e-9));
        assert_eq!(tol(&m12.preset), Some(accurate.tol));
        // heyoka's candidates for the paired rounds: every tolerance that meets the level.
        assert_eq!(m9.heyoka_tols, vec![1e-7, 1e-9]);
        assert_eq!(m12.heyoka_tols, vec![1e-9]);
        let check = json!({"errors": {"max_theta": 1e-16, "impact_time_rel": 1e-9}});
        assert_eq!(
            meeting(&hy["cases"][0]["points"], 1e-14, &check, |_| true).count(),
            0
        );
    }
}
