//! The peers against the study: SciPy's DOP853, heyoka's Taylor integrator, OpenSees on the
//! rigid block.

use std::fmt::Write as _;
use std::path::Path;

use serde_json::Value;

use super::heyoka::{levels_table, paired_table};
use super::{err, f, ms, sci, Results};
use crate::Result;

/// SciPy's `solve_ivp` against the Rust runs.
pub(super) fn scipy(w: &mut String, r: &Results, dir: &Path) -> Result<()> {
    let (scipy, cases) = (&r.scipy, &r.cases[..]);
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
    Ok(())
}

/// heyoka against the Rust runs, at the same tolerance and at the error levels.
pub(super) fn heyoka(w: &mut String, r: &Results, dir: &Path) -> Result<()> {
    let (heyoka, paired, cases) = (&r.heyoka, &r.paired, &r.cases[..]);
    let sp_case = |name: &Value| Results::peer_case(&r.scipy, name);
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
            levels_table(w, hy, cases)?;
            if let Some(paired) = &paired {
                paired_table(w, paired)?;
            }
        }
    }
    Ok(())
}

/// OpenSees's rocking element on the rigid block, against Housner.
pub(super) fn opensees(w: &mut String, r: &Results, dir: &Path) -> Result<()> {
    let opensees = &r.opensees;
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
    Ok(())
}
