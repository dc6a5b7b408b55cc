//! The matched points against heyoka: at each error level, the cheapest heyoka run, Rust
//! configuration and preset that meet it, and the paired rounds' table.

use std::fmt::Write as _;
use std::path::Path;

use serde_json::Value;

use super::{combined, f, ms, resolves, sci};
use crate::Result;

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
pub(super) fn levels_table(w: &mut String, hy: &Value, cases: &[Value]) -> Result<()> {
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
    super::judge(&mut hy, &cases);
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

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    fn point(method: &str, tol: f64, cpu_s: f64, max_theta: f64, impact: f64) -> Value {
        json!({"method": method, "tol": tol, "cpu_s": cpu_s,
               "errors": {"max_theta": max_theta, "impact_time_rel": impact, "overturn_mismatch": 0.0}})
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
