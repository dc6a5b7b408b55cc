//! The presets: chosen from the study on the `standard` class, as options.rs states them, and
//! each preset's error on each class of run.

use std::fmt::Write as _;

use serde_json::Value;

use super::{combined, err, f, ms, resolves, sci};
use crate::Result;

/// The presets chosen from the study (a table), and whether options.rs agrees; returns the
/// `standard` cases they are chosen on.
pub(super) fn chosen(w: &mut String, cases: &[Value]) -> Result<Vec<Value>> {
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
    Ok(standard)
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
pub(super) fn by_class(w: &mut String, cases: &[Value]) -> Result<()> {
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
}
