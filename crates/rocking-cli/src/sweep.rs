//! `rocking spectrum` and `rocking batch`: sweeps of a scene over axes of scene values, run in
//! parallel and resumable through `rocking-spectra`, with cells.csv, meta.json and plots.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use rocking_spectra::{cells_csv, CellClass, Outcome, Progress, Shard, Sweep};
use rocking_study::plan::{program_digest, Plan, Records};
use rocking_study::{Invariant, StudyError};
use serde_json::json;

use crate::error::CliError;
use crate::out_dir::write_atomic;
use crate::shard;
use rocking_plot::figure as plot;
use rocking_scene::SceneError;

/// The most threads `--threads` may ask for: more than the cores only adds switching.
const MAX_THREADS: usize = 1024;

pub(crate) fn threads_pool(threads: Option<usize>) -> Result<rayon::ThreadPool, CliError> {
    let mut b = rayon::ThreadPoolBuilder::new();
    if let Some(n) = threads {
        if !(1..=MAX_THREADS).contains(&n) {
            return Err(SceneError::input(format!(
                "--threads {n} is not allowed: 1 <= threads <= {MAX_THREADS}"
            ))
            .into());
        }
        b = b.num_threads(n);
    }
    b.build().map_err(CliError::ThreadPool)
}

pub(crate) fn out_dir(scene: &Path, out: Option<PathBuf>, what: &str) -> PathBuf {
    out.unwrap_or_else(|| {
        let stem = scene
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_else(|| "scene".into());
        Path::new("out").join(format!("{stem}-{what}"))
    })
}

/// `rocking spectrum`.
pub fn spectrum(
    scene_path: &Path,
    sets: &[String],
    axis_args: &[String],
    out: Option<PathBuf>,
    quiet: bool,
    threads: Option<usize>,
    shard: Option<Shard>,
) -> Result<(), CliError> {
    let plan = Plan::spectrum(crate::load_base(scene_path, sets)?, axis_args)?;
    let sweep = &plan.sweep;
    let dir = out_dir(scene_path, out, "spectrum");
    crate::out_dir::refuse_a_file(&dir)?;
    let progress = if quiet {
        Progress::Quiet
    } else {
        Progress::Auto
    };
    let pool = threads_pool(threads)?;
    if let Some(shard) = shard {
        return shard::run_shard(&plan, shard::Kind::Spectrum, shard, &dir, progress, &pool);
    }
    let outcome = pool
        .install(|| rocking_spectra::run(sweep, &dir, progress, |values| plan.run_cell(values)))
        .map_err(CliError::from)?;
    let mut written = pool.install(|| write_outputs(&plan, &outcome, &dir))?;
    written.push(write_timing(&outcome, &dir, pool.current_num_threads())?);
    let mut counts: BTreeMap<&str, usize> = BTreeMap::new();
    for c in &outcome.cells {
        *counts.entry(c.class.as_str()).or_default() += 1;
    }
    out!(
        "{}: {} cells ({} computed now, {} resumed) in {:.2} s on {} threads ({:.3} ms per computed cell)",
        scene_path.display(),
        outcome.cells.len(),
        outcome.computed,
        outcome.cells.len() - outcome.computed,
        outcome.elapsed.as_secs_f64(),
        pool.current_num_threads(),
                1e3 * outcome.elapsed.as_secs_f64() / outcome.computed.max(1) as f64
    );
    for (class, n) in counts {
        out!("  {class}: {n}");
    }
    out!("  wrote:");
    for p in written {
        out!("    {}", p.display());
    }
    failed_runs(&outcome, "cells", "cells.csv")
}

/// Exit status 1 when any cell failed (on a first run and on a resume alike): its results are
/// written, marked `failed`, with the messages in meta.json.
pub(crate) fn failed_runs(
    outcome: &Outcome,
    what: &'static str,
    table: &'static str,
) -> Result<(), CliError> {
    match outcome.failures.first() {
        None => Ok(()),
        Some((_, first)) => Err(CliError::FailedCells {
            failed: outcome.failures.len(),
            total: outcome.cells.len(),
            what,
            table,
            first: first.clone(),
        }),
    }
}

/// A cell's axis values for meta.json: numbers, and the texts of text axes.
fn cell_values(sweep: &Sweep, index: usize) -> Vec<serde_json::Value> {
    sweep
        .axes
        .iter()
        .zip(sweep.values(index))
        .map(|(a, v)| match a.text(v) {
            Some(t) => json!(t),
            None => json!(v),
        })
        .collect()
}

/// What a run took: timing.json, apart from meta.json, which is a function of the study alone
/// (the same bytes whether run at once, resumed, or sharded and merged).
fn write_timing(outcome: &Outcome, dir: &Path, threads: usize) -> Result<PathBuf, CliError> {
    let timing = json!({
        "cells": outcome.cells.len(),
        "computed_now": outcome.computed,
        "seconds": outcome.elapsed.as_secs_f64(),
        "threads": threads,
    });
    let path = dir.join("timing.json");
    write_atomic(
        &path,
        (serde_json::to_string_pretty(&timing).unwrap_or_default() + "\n").as_bytes(),
    )?;
    Ok(path)
}

/// cells.csv, meta.json and the plots of a spectrum (also of a merge of its shards); with
/// `[sweep] reference`, the reference structure's cells (run here, in memory) in reference.csv
/// and on the figure.
pub(crate) fn write_outputs(
    plan: &Plan,
    outcome: &Outcome,
    dir: &Path,
) -> Result<Vec<PathBuf>, CliError> {
    let (base, sweep) = (&plan.base, &plan.sweep);
    let mut written = Vec::new();
    let cells = dir.join("cells.csv");
    write_atomic(&cells, cells_csv(sweep, &outcome.cells).as_bytes())?;
    written.push(cells);
    let reference = match plan.reference()? {
        Some(r) => {
            let run =
                rocking_spectra::run_in_memory(&r.plan.sweep, |values| r.plan.run_cell(values))
                    .map_err(CliError::from)?;
            let path = dir.join("reference.csv");
            write_atomic(&path, cells_csv(&r.plan.sweep, &run.cells).as_bytes())?;
            written.push(path);
            if let Some((_, first)) = run.failures.first() {
                eprintln!(
                    "note: {} of {} cells of the reference ({}) failed (marked `failed` in \
                     reference.csv); first: {first}",
                    r.name,
                    run.failures.len(),
                    run.cells.len()
                );
            }
            Some((r, run))
        }
        None => None,
    };
    let mut meta = json!({
        "scene": base.path().display().to_string(),
        "scene_text": base.text(),
        "set": base.sets(),
        "axes": sweep.axes.iter().map(|a| if a.is_text() {
            json!({"key": a.key, "values": a.texts})
        } else {
            json!({"key": a.key, "values": a.values})
        }).collect::<Vec<_>>(),
        "fingerprint": sweep.fingerprint,
        "cells": outcome.cells.len(),
        "failures": outcome.failures.iter().map(|(i, m)| {
            json!({"cell": i, "values": cell_values(sweep, *i), "message": m})
        }).collect::<Vec<_>>(),
        "versions": {"rocking": env!("CARGO_PKG_VERSION"), "kernels": "generated/ir (CasADi 3.8.2)"},
    });
    if !outcome.beyond_model.is_empty() {
        meta["beyond_model"] = outcome
            .beyond_model
            .iter()
            .map(|(i, m)| json!({"cell": i, "values": cell_values(sweep, *i), "message": m}))
            .collect();
    }
    if let Some((r, run)) = &reference {
        meta["reference"] = json!({
            "name": r.name,
            "set": r.plan.base.sets(),
            "axes": r.plan.sweep.axes.iter().map(|a| a.key.clone()).collect::<Vec<_>>(),
            "cells": run.cells.len(),
            "failures": run.failures.iter().map(|(i, m)| {
                json!({"cell": i, "values": r.plan.sweep.values(*i), "message": m})
            }).collect::<Vec<_>>(),
        });
    }
    let path = dir.join("meta.json");
    write_atomic(
        &path,
        (serde_json::to_string_pretty(&meta).unwrap_or_default() + "\n").as_bytes(),
    )?;
    written.push(path);
    let kind = match sweep.axes.len() {
        1 => "one-axis sweep",
        2 => "rocking spectrum",
        _ => "overturning boundaries",
    };
    let title = match base.title() {
        Some(t) => format!("{t}: {kind}"),
        None => kind.to_string(),
    };
    let shown = reference.as_ref().map(|(r, run)| plot::Reference {
        label: r.label,
        sweep: &r.plan.sweep,
        cells: &run.cells,
    });
    let theta_cr = rocking_plot::figure_file::theta_cr_over_alpha(plan)?;
    if plot::drawable(sweep) {
        let (figure, name) =
            plot::sweep_figure(&title, sweep, &outcome.cells, shown.as_ref(), theta_cr);
        written.extend(figure.write(dir, name)?);
        if sweep.axes.len() == 2 {
            for k in 0..sweep.reported.len() {
                let (figure, name) = plot::reported_figure(&title, sweep, &outcome.cells, k);
                written.extend(figure.write(dir, &name)?);
            }
        }
    }
    Ok(written)
}

/// `rocking batch`: every record at every scale factor (and every cell of the `--axis` axes);
/// per scale (and axis cell), the fraction that overturned.
#[allow(clippy::too_many_arguments)] // the command's arguments, one to one
pub fn batch(
    scene_path: &Path,
    sets: &[String],
    records: &[PathBuf],
    scales: &[f64],
    axes: &[String],
    out: Option<PathBuf>,
    quiet: bool,
    threads: Option<usize>,
    shard: Option<Shard>,
) -> Result<(), CliError> {
    let plan = Plan::batch(crate::load_base(scene_path, sets)?, records, scales, axes)?;
    let dir = out_dir(scene_path, out, "batch");
    crate::out_dir::refuse_a_file(&dir)?;
    let progress = if quiet {
        Progress::Quiet
    } else {
        Progress::Auto
    };
    let pool = threads_pool(threads)?;
    if let Some(shard) = shard {
        return shard::run_shard(&plan, shard::Kind::Batch, shard, &dir, progress, &pool);
    }
    let outcome = pool
        .install(|| rocking_spectra::run(&plan.sweep, &dir, progress, |v| plan.run_cell(v)))
        .map_err(CliError::from)?;
    let (mut written, tally) = write_batch_outputs(&plan, &outcome, &dir)?;
    written.push(write_timing(&outcome, &dir, pool.current_num_threads())?);
    let own = &plan.sweep.axes[2..];
    let axis_cells: String = own
        .iter()
        .map(|a| format!(" x {} {}", a.values.len(), a.key))
        .collect();
    out!(
        "{}: {} records x {} scales{axis_cells} ({} runs computed now) in {:.2} s",
        scene_path.display(),
        plan.records.as_ref().map_or(0, |r| r.files.len()),
        plan.records.as_ref().map_or(0, |r| r.scales.len()),
        outcome.computed,
        outcome.elapsed.as_secs_f64()
    );
    for t in &tally {
        let mut notes = String::new();
        if t.failed > 0 {
            notes.push_str(&format!("; {} of {} runs failed", t.failed, t.runs));
        }
        if t.beyond_model > 0 {
            notes.push_str(&format!(
                "; {} of {} runs beyond the model",
                t.beyond_model, t.runs
            ));
        }
        let at: String = t.axes.iter().map(|v| format!("{v} ")).collect();
        match t.fraction() {
            Some(x) => out!(
                "  {at}scale {}: {}/{} overturned ({:.1} %){notes}",
                t.scale,
                t.overturned,
                t.completed(),
                100.0 * x
            ),
            None => out!("  {at}scale {}: no run finished{notes}", t.scale),
        }
    }
    out!("  wrote:");
    for p in written {
        out!("    {}", p.display());
    }
    failed_runs(&outcome, "runs", "runs.csv")
}

/// What the runs at one scale factor (and one cell of the batch's axes) gave.
pub(crate) struct ScaleTally {
    /// The cell of the batch's own axes as `key=value` (empty without axes).
    axes: Vec<String>,
    scale: f64,
    runs: usize,
    /// Runs that failed (no result).
    failed: usize,
    /// Runs beyond the model's validity (no result; docs/spectra.md).
    beyond_model: usize,
    overturned: usize,
}

impl ScaleTally {
    /// The runs with a result.
    fn completed(&self) -> usize {
        self.runs - self.failed - self.beyond_model
    }

    /// The fraction overturned of the runs with a result; none when no run has one.
    fn fraction(&self) -> Option<f64> {
        let n = self.completed();
        (n > 0).then(|| self.overturned as f64 / n as f64)
    }
}

/// Per cell of the batch's own axes (in cell order) and, within it, per scale factor (in the
/// order of the scales); per scale factor alone without axes.
type Tally = Vec<ScaleTally>;
/// A CSV field: quoted (quotes doubled) when it holds a comma, a quote or a line break.
fn csv_field(s: &str) -> String {
    if s.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", s.replace('"', "\"\""))
    } else {
        s.to_string()
    }
}

/// runs.csv, fragility.csv, meta.json and the fragility plots of a record suite (also of a merge
/// of its shards). The batch's own axes (`--axis`, the sweep's axes after record and scale) add
/// one column each to runs.csv and fragility.csv (the text of a text axis), and fragility.csv
/// then has one row per axis cell and scale; without them every output is as before.
pub(crate) fn write_batch_outputs(
    plan: &Plan,
    outcome: &Outcome,
    dir: &Path,
) -> Result<(Vec<PathBuf>, Tally), CliError> {
    let (base, sweep) = (&plan.base, &plan.sweep);
    let Some(Records {
        files: list,
        paths: abs,
        digests,
        names,
        scales,
    }) = &plan.records
    else {
        return Err(StudyError::Internal(Invariant::BatchRecords).into());
    };
    let own = &sweep.axes[2..];
    // The cells of the batch's own axes (1 without them): the fastest-varying part of an index.
    let own_cells: usize = own.iter().map(|a| a.values.len()).product();
    let own_values = |mut a: usize| -> Vec<String> {
        let mut out = vec![String::new(); own.len()];
        for (k, axis) in own.iter().enumerate().rev() {
            let n = axis.values.len();
            out[k] = axis.display(axis.values[a % n]);
            a /= n;
        }
        out
    };
    let messages: BTreeMap<usize, &str> = outcome
        .failures
        .iter()
        .chain(&outcome.beyond_model)
        .map(|(i, m)| (*i, m.as_str()))
        .collect();
    // Per axis cell and scale: runs, failed, overturned (of the runs that finished).
    let mut tally: Tally = (0..own_cells)
        .flat_map(|a| {
            let values = own_values(a);
            scales.iter().map(move |&scale| ScaleTally {
                axes: own
                    .iter()
                    .zip(&values)
                    .map(|(ax, v)| format!("{}={v}", ax.key))
                    .collect(),
                scale,
                runs: 0,
                failed: 0,
                beyond_model: 0,
                overturned: 0,
            })
        })
        .collect();
    let mut runs = csv::Writer::from_writer(Vec::new());
    let csv_err = |source| CliError::Table {
        name: "runs.csv",
        source,
    };
    // The quantities of `[sweep] report` after the run's own, as in a spectrum's cells.csv.
    let head = ["record", "scale"]
        .into_iter()
        .chain(own.iter().map(|a| a.key.as_str()))
        .chain(["class", "overturned", "max_theta_over_alpha", "impacts"])
        .chain(sweep.reported.iter().map(String::as_str));
    runs.write_record(head.chain(["message"]))
        .map_err(csv_err)?;
    for c in &outcome.cells {
        let v = sweep.values(c.index);
        let r = v[0] as usize;
        let (a, k) = (c.index % own_cells, (c.index / own_cells) % scales.len());
        let t = &mut tally[a * scales.len() + k];
        t.runs += 1;
        let mut row = vec![names[r].clone(), v[1].to_string()];
        row.extend(own_values(a));
        if !c.class.has_result() {
            if c.class == CellClass::BeyondModel {
                t.beyond_model += 1;
            } else {
                t.failed += 1;
            }
            // A failed run (or one beyond the model) has no result: its fields are empty, never
            // a made-up "survived".
            let m = messages.get(&c.index).copied().unwrap_or("failed");
            row.push(c.class.as_str().into());
            row.extend(std::iter::repeat_n(String::new(), 3 + sweep.reported.len()));
            row.push(m.to_string());
        } else {
            let over = c.class.overturned() == Some(true);
            t.overturned += usize::from(over);
            row.extend([
                c.class.as_str().into(),
                over.to_string(),
                c.max_theta_over_alpha.to_string(),
                c.impacts.to_string(),
            ]);
            row.extend(c.reported.iter().map(f64::to_string));
            row.push(String::new());
        }
        runs.write_record(&row).map_err(csv_err)?;
    }
    let rows = runs
        .into_inner()
        .map_err(|e| csv_err(e.into_error().into()))?;
    let mut written = Vec::new();
    let path = dir.join("runs.csv");
    write_atomic(&path, &rows)?;
    written.push(path);
    // The fraction overturned is of the runs with a result; failed runs and runs beyond the
    // model are counted apart, and a scale with no result has no fraction (an empty field, no
    // plotted point).
    let mut frag: String = own.iter().map(|a| csv_field(&a.key) + ",").collect();
    frag.push_str("scale,runs,failed,beyond_model,completed,overturned,fraction_overturned\n");
    for (i, t) in tally.iter().enumerate() {
        let x = t.fraction().map_or(String::new(), |x| x.to_string());
        for v in own_values(i / scales.len()) {
            frag.push_str(&csv_field(&v));
            frag.push(',');
        }
        frag.push_str(&format!(
            "{},{},{},{},{},{},{x}\n",
            t.scale,
            t.runs,
            t.failed,
            t.beyond_model,
            t.completed(),
            t.overturned
        ));
    }
    let path = dir.join("fragility.csv");
    write_atomic(&path, frag.as_bytes())?;
    written.push(path);
    // A run's entry in meta.json: with axes, also its cell of them (texts for text axes).
    let entry = |i: usize, m: &str| {
        let v = sweep.values(i);
        let mut e = json!({"run": i, "record": names[v[0] as usize], "scale": v[1], "message": m});
        if !own.is_empty() {
            e["axes"] = cell_values(sweep, i)[2..].to_vec().into();
        }
        e
    };
    let mut meta = json!({
        "scene": base.path().display().to_string(),
        "scene_text": base.text(),
        "set": base.sets(),
        "records": abs.iter().zip(digests).map(|(a, d)| json!({"path": a, "digest": d})).collect::<Vec<_>>(),
        "scales": scales,
        "fingerprint": sweep.fingerprint,
        "runs": outcome.cells.len(),
        "failed": outcome.failures.len(),
        "failures": outcome.failures.iter().map(|(i, m)| entry(*i, m)).collect::<Vec<_>>(),
        "beyond_model": outcome.beyond_model.iter().map(|(i, m)| entry(*i, m)).collect::<Vec<_>>(),
        "versions": {"rocking": env!("CARGO_PKG_VERSION"), "program": program_digest()},
    });
    if !own.is_empty() {
        meta["axes"] = own
            .iter()
            .map(|a| {
                if a.is_text() {
                    json!({"key": a.key, "values": a.texts})
                } else {
                    json!({"key": a.key, "values": a.values})
                }
            })
            .collect();
    }
    let path = dir.join("meta.json");
    write_atomic(
        &path,
        (serde_json::to_string_pretty(&meta).unwrap_or_default() + "\n").as_bytes(),
    )?;
    written.push(path);
    // One curve of the fraction against the scale: without axes only (with axes, the curves per
    // axis cell are the rows of fragility.csv).
    if own.is_empty() {
        let points: Vec<(f64, f64)> = tally
            .iter()
            .filter_map(|t| t.fraction().map(|x| (t.scale, x)))
            .collect();
        written.extend(plot::fragility_plots(&points, list.len(), dir)?);
    }
    Ok((written, tally))
}
