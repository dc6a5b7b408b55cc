//! `rocking spectrum` and `rocking batch`: sweeps of a scene over axes of scene values, run in
//! parallel and resumable through `rocking-spectra`, with cells.csv, meta.json and plots.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use rocking_spectra::{cells_csv, Outcome, Progress, Shard, Sweep};
use rocking_study::plan::{program_digest, BatchTables, Plan, Records, ScaleTally};
use rocking_study::report::Table;
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

/// A study's table as CSV (runs.csv, fragility.csv, records.csv, ida.csv, stripes.csv: the
/// tables `rocking_study` builds), `name` its file for an error.
pub(crate) fn table_csv(table: &Table, name: &'static str) -> Result<Vec<u8>, CliError> {
    let csv_err = |source| CliError::Table { name, source };
    let mut w = csv::Writer::from_writer(Vec::new());
    w.write_record(&table.columns).map_err(csv_err)?;
    for row in &table.rows {
        w.write_record(row.iter().map(|e| e.text()))
            .map_err(csv_err)?;
    }
    w.into_inner().map_err(|e| csv_err(e.into_error().into()))
}

/// runs.csv, fragility.csv, meta.json and the fragility plots of a record suite (also of a merge
/// of its shards). The batch's own axes (`--axis`, the sweep's axes after record and scale) add
/// one column each to runs.csv and fragility.csv (the text of a text axis), and fragility.csv
/// then has one row per axis cell and scale; without them every output is as before.
pub(crate) fn write_batch_outputs(
    plan: &Plan,
    outcome: &Outcome,
    dir: &Path,
) -> Result<(Vec<PathBuf>, Vec<ScaleTally>), CliError> {
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
    let BatchTables {
        runs,
        fragility,
        tally,
    } = plan.batch_tables(outcome)?;
    let mut written = Vec::new();
    for (name, table) in [("runs.csv", &runs), ("fragility.csv", &fragility)] {
        let path = dir.join(name);
        write_atomic(&path, &table_csv(table, name)?)?;
        written.push(path);
    }
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
