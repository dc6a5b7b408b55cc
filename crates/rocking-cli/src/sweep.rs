//! `rocking spectrum` and `rocking batch`: sweeps of a scene over axes of scene values, run in
//! parallel and resumable through `rocking-spectra`, with cells.csv, meta.json and plots.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::time::Instant;

use rocking::{History, Summary};
use rocking_spectra::{cells_csv, fnv1a, Axis, Cell, CellClass, Outcome, Progress, Sweep};
use serde_json::json;

use crate::report::write_atomic;
use crate::scene::{self, CliError};
use crate::{model, plot};
use rocking_scene::knob::{self, Knob, KnobValue};

/// The paper's spectrum axes (Figs 6-8).
pub const DEFAULT_AXES: [&str; 2] = [
    "excitation.omega_p_over_p=1:10:40",
    "excitation.amplitude=1:20:40",
];

/// A scene that every cell of a sweep starts from.
pub struct Base {
    path: PathBuf,
    text: String,
    parsed: scene::Parsed,
    sets: Vec<String>,
    title: Option<String>,
    /// The scene with the command line's overrides, loaded once: cells apply knobs to it.
    scene: scene::Scene,
    /// Digest of the scene's record file (contents), when it has one.
    record_digest: Option<String>,
}

/// A digest of a file's contents: results computed from a record are reused only while the
/// record's bytes are the same.
pub fn file_digest(path: &Path) -> Result<String, CliError> {
    let bytes = std::fs::read(path)
        .map_err(|e| CliError::Input(format!("{}: cannot read: {e}", path.display())))?;
    Ok(format!("{:016x}", fnv1a(&bytes)))
}

/// A digest of the running program (its executable), so that a journal written by another build
/// is not reused; the package version when the executable cannot be read.
fn program_digest() -> &'static str {
    static DIGEST: std::sync::OnceLock<String> = std::sync::OnceLock::new();
    DIGEST.get_or_init(|| {
        let exe = std::env::current_exe().and_then(std::fs::read);
        match exe {
            Ok(bytes) => format!("{} {:016x}", env!("CARGO_PKG_VERSION"), fnv1a(&bytes)),
            Err(_) => env!("CARGO_PKG_VERSION").to_string(),
        }
    })
}

impl Base {
    /// Reads and validates the scene with the command line's overrides.
    pub fn load(path: &Path, sets: &[String]) -> Result<(Base, scene::Scene), CliError> {
        let text = scene::read(path)?;
        let parsed = scene::parse_text(path, text.clone())?;
        let sc = parsed.load(sets)?;
        let m = model::build(&sc)?;
        let title = m.title.clone().map(|t| {
            if sets.is_empty() {
                t
            } else {
                format!("{t} [{}]", sets.join(", "))
            }
        });
        let record = sc.spec.excitation.as_ref().and_then(|e| {
            (e.kind.as_deref() == Some("record"))
                .then(|| e.path.as_ref().map(|p| sc.src.dir().join(p)))
                .flatten()
        });
        let record_digest = record.as_deref().map(file_digest).transpose()?;
        let base = Base {
            path: path.to_path_buf(),
            text,
            parsed,
            sets: sets.to_vec(),
            title,
            record_digest,
            scene: sc.clone(),
        };
        Ok((base, sc))
    }

    /// Resolves the keys of the axes once; `None` when one is not a knob (then cells go through
    /// `--set` overrides).
    fn knobs(&self, keys: &[&str]) -> Option<Vec<Knob>> {
        keys.iter()
            .map(|k| Knob::resolve(&self.scene, k).ok())
            .collect()
    }

    /// Runs a cell: the scene with its knobs set, summary only.
    pub fn run_knobs(&self, cell: &[(&Knob, KnobValue)]) -> Result<Summary, CliError> {
        let m = knob::setup(&self.scene, cell)?;
        self.simulate(m)
    }

    /// Runs the scene with extra overrides, summary only (no history, events or energy).
    pub fn run(&self, extra: &[String]) -> Result<Summary, CliError> {
        let mut sets = self.sets.clone();
        sets.extend_from_slice(extra);
        let sc = self.parsed.load(&sets)?;
        self.simulate(model::build(&sc)?)
    }

    fn simulate(&self, mut m: model::Model) -> Result<Summary, CliError> {
        m.options.history = History::None;
        m.options.event_log = false;
        m.options.energy = false;
        m.options.stop_when_known = true;
        rocking::simulate(&m.structure, &m.excitation, &m.effects, &m.options)
            .map(|r| r.summary)
            .map_err(|e| {
                CliError::Internal(format!("{}: simulation failed: {e}", self.path.display()))
            })
    }

    /// Identifies everything a cell's result depends on: the program, the scene text, the
    /// overrides, the record contents, the axes and `extra` (for batch, the records and their
    /// digests).
    fn fingerprint(&self, axes: &[Axis], extra: &str) -> String {
        let mut key = format!(
            "{}\n{}\n{:?}\n{:?}\n{extra}\n",
            program_digest(),
            self.text,
            self.sets,
            self.record_digest
        );
        for a in axes {
            key.push_str(&format!("{}={:?}\n", a.key, a.values));
        }
        format!("{:016x}", fnv1a(key.as_bytes()))
    }
}

fn set_arg(key: &str, v: f64) -> String {
    format!("{key}={v:?}")
}

/// The most threads `--threads` may ask for: more than the cores only adds switching.
const MAX_THREADS: usize = 1024;

fn threads_pool(threads: Option<usize>) -> Result<rayon::ThreadPool, CliError> {
    let mut b = rayon::ThreadPoolBuilder::new();
    if let Some(n) = threads {
        if !(1..=MAX_THREADS).contains(&n) {
            return Err(CliError::Input(format!(
                "--threads {n} is not allowed: 1 <= threads <= {MAX_THREADS}"
            )));
        }
        b = b.num_threads(n);
    }
    b.build()
        .map_err(|e| CliError::Internal(format!("cannot start the thread pool: {e}")))
}

fn out_dir(scene: &Path, out: Option<PathBuf>, what: &str) -> PathBuf {
    out.unwrap_or_else(|| {
        let stem = scene
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_else(|| "scene".into());
        Path::new("out").join(format!("{stem}-{what}"))
    })
}

fn sweep_error(e: rocking_spectra::SweepError) -> CliError {
    match e {
        rocking_spectra::SweepError::Mismatch(_) | rocking_spectra::SweepError::NotJournal(..) => {
            CliError::Input(e.to_string())
        }
        other => CliError::Internal(other.to_string()),
    }
}

/// `rocking spectrum`.
pub fn spectrum(
    scene_path: &Path,
    sets: &[String],
    axis_args: &[String],
    out: Option<PathBuf>,
    quiet: bool,
    threads: Option<usize>,
) -> Result<(), CliError> {
    let (base, sc) = Base::load(scene_path, sets)?;
    let specs: Vec<String> = if !axis_args.is_empty() {
        axis_args.to_vec()
    } else if let Some(a) = sc.spec.sweep.as_ref().and_then(|s| s.axes.clone()) {
        a
    } else {
        DEFAULT_AXES.iter().map(|s| s.to_string()).collect()
    };
    let axes = specs
        .iter()
        .map(|s| {
            Axis::parse(s).map_err(|e| CliError::Input(format!("{}: {e}", scene_path.display())))
        })
        .collect::<Result<Vec<_>, _>>()?;
    // Bound the sweep, then validate every axis value against the scene before running anything.
    rocking_spectra::Sweep::checked_len(&axes)
        .map_err(|e| CliError::Input(format!("{}: {e}", scene_path.display())))?;
    let keys: Vec<&str> = axes.iter().map(|a| a.key.as_str()).collect();
    if let Some(k) = keys
        .iter()
        .enumerate()
        .find_map(|(i, k)| keys[..i].contains(k).then_some(k))
    {
        return Err(CliError::Input(format!(
            "{}: two axes on `{k}`: each key may have one axis (list its values in one --axis)",
            scene_path.display()
        )));
    }
    for a in &axes {
        for &v in &a.values {
            let sc = scene::load_text(
                scene_path,
                base.text.clone(),
                &[sets, &[set_arg(&a.key, v)]].concat(),
            )?;
            model::build(&sc)?;
        }
    }
    let sweep = Sweep {
        fingerprint: base.fingerprint(&axes, "spectrum"),
        axes,
    };
    let keys: Vec<&str> = sweep.axes.iter().map(|a| a.key.as_str()).collect();
    let knobs = base.knobs(&keys);
    let dir = out_dir(scene_path, out, "spectrum");
    let progress = if quiet {
        Progress::Quiet
    } else {
        Progress::Auto
    };
    let start = Instant::now();
    let pool = threads_pool(threads)?;
    let outcome = pool
        .install(|| {
            rocking_spectra::run(&sweep, &dir, progress, |values| match &knobs {
                Some(knobs) => {
                    let cell: Vec<(&Knob, KnobValue)> = knobs
                        .iter()
                        .zip(values)
                        .map(|(k, &v)| (k, KnobValue::Number(v)))
                        .collect();
                    base.run_knobs(&cell).map_err(|e| e.to_string())
                }
                None => {
                    let extra: Vec<String> = sweep
                        .axes
                        .iter()
                        .zip(values)
                        .map(|(a, &v)| set_arg(&a.key, v))
                        .collect();
                    base.run(&extra).map_err(|e| e.to_string())
                }
            })
        })
        .map_err(sweep_error)?;
    let written = write_outputs(
        &base,
        &sweep,
        &outcome,
        &dir,
        start,
        pool.current_num_threads(),
    )?;
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
fn failed_runs(outcome: &Outcome, what: &str, table: &str) -> Result<(), CliError> {
    match outcome.failures.first() {
        None => Ok(()),
        Some((_, first)) => Err(CliError::Internal(format!(
            "{} of {} {what} failed (marked `failed` in {table}, messages in meta.json); first: {first}",
            outcome.failures.len(),
            outcome.cells.len()
        ))),
    }
}

fn write_outputs(
    base: &Base,
    sweep: &Sweep,
    outcome: &Outcome,
    dir: &Path,
    start: Instant,
    threads: usize,
) -> Result<Vec<PathBuf>, CliError> {
    let mut written = Vec::new();
    let cells = dir.join("cells.csv");
    write_atomic(&cells, cells_csv(sweep, &outcome.cells).as_bytes())?;
    written.push(cells);
    let meta = json!({
        "scene": base.path.display().to_string(),
        "scene_text": base.text,
        "set": base.sets,
        "axes": sweep.axes.iter().map(|a| json!({"key": a.key, "values": a.values})).collect::<Vec<_>>(),
        "fingerprint": sweep.fingerprint,
        "cells": outcome.cells.len(),
                "computed_now": outcome.computed,
        "failures": outcome.failures.iter().map(|(i, m)| {
            let v = sweep.values(*i);
            json!({"cell": i, "values": v, "message": m})
        }).collect::<Vec<_>>(),
        "seconds": start.elapsed().as_secs_f64(),
        "threads": threads,
        "versions": {"rocking": env!("CARGO_PKG_VERSION"), "kernels": "generated/ir (CasADi 3.8.2)"},
    });
    let path = dir.join("meta.json");
    write_atomic(
        &path,
        (serde_json::to_string_pretty(&meta).unwrap_or_default() + "\n").as_bytes(),
    )?;
    written.push(path);
    let kind = if sweep.axes.len() >= 3 {
        "overturning boundaries"
    } else {
        "rocking spectrum"
    };
    let title = match &base.title {
        Some(t) => format!("{t}: {kind}"),
        None => kind.to_string(),
    };
    written.extend(plot::spectrum_plots(&title, sweep, &outcome.cells, dir)?);
    Ok(written)
}

/// `rocking batch`: every record at every scale factor; per scale, the fraction that overturned.
pub fn batch(
    scene_path: &Path,
    sets: &[String],
    records: &[PathBuf],
    scales: &[f64],
    out: Option<PathBuf>,
    quiet: bool,
    threads: Option<usize>,
) -> Result<(), CliError> {
    let (base, sc) = Base::load(scene_path, sets)?;
    let sweep_spec = sc.spec.sweep.as_ref();
    let mut files: Vec<PathBuf> = records.to_vec();
    if files.is_empty() {
        let dir = sc.src.dir();
        files = sweep_spec
            .and_then(|s| s.records.clone())
            .unwrap_or_default()
            .iter()
            .map(|r| dir.join(r))
            .collect();
    }
    // A directory stands for all the .AT2 files in it.
    let mut list = Vec::new();
    for f in files {
        if f.is_dir() {
            let mut found: Vec<PathBuf> = std::fs::read_dir(&f)
                .map_err(|e| CliError::Input(format!("{}: {e}", f.display())))?
                .filter_map(|e| e.ok().map(|e| e.path()))
                .filter(|p| p.extension().is_some_and(|x| x.eq_ignore_ascii_case("at2")))
                .collect();
            found.sort();
            list.extend(found);
        } else {
            list.push(f);
        }
    }
    if list.is_empty() {
        return Err(CliError::Input(format!(
            "{}: no records: give --records FILE|DIR or `records = [...]` in [sweep]",
            scene_path.display()
        )));
    }
    let scales: Vec<f64> = if scales.is_empty() {
        sweep_spec
            .and_then(|s| s.scales.clone())
            .unwrap_or_else(|| vec![1.0])
    } else {
        scales.to_vec()
    };
    if let Some(bad) = scales.iter().find(|s| !(s.is_finite() && **s > 0.0)) {
        return Err(CliError::Input(format!(
            "scale factor {bad} is not allowed: scales must be > 0"
        )));
    }
    let abs: Vec<String> = list
        .iter()
        .map(|p| {
            std::fs::canonicalize(p)
                .unwrap_or_else(|_| p.clone())
                .display()
                .to_string()
        })
        .collect();
    let record_set = |i: usize| format!("excitation.path={:?}", abs[i]);
    // Validate every record (readable, well formed) before running anything.
    for i in 0..abs.len() {
        let sc = scene::load_text(
            scene_path,
            base.text.clone(),
            &[sets, &[record_set(i)]].concat(),
        )?;
        model::build(&sc)?;
    }
    let axes = vec![
        Axis {
            key: "record".into(),
            values: (0..abs.len()).map(|i| i as f64).collect(),
        },
        Axis {
            key: "excitation.scale".into(),
            values: scales.clone(),
        },
    ];
    rocking_spectra::Sweep::checked_len(&axes)
        .map_err(|e| CliError::Input(format!("{}: records x scales: {e}", scene_path.display())))?;
    let digests = list
        .iter()
        .map(|p| file_digest(p))
        .collect::<Result<Vec<_>, _>>()?;
    let records_key: Vec<String> = abs
        .iter()
        .zip(&digests)
        .map(|(a, d)| format!("{a} {d}"))
        .collect();
    let sweep = Sweep {
        fingerprint: base.fingerprint(&axes, &records_key.join("\n")),
        axes,
    };
    let knobs = base
        .knobs(&["excitation.path", "excitation.scale"])
        .expect("record path and scale are knobs");
    let dir = out_dir(scene_path, out, "batch");
    let progress = if quiet {
        Progress::Quiet
    } else {
        Progress::Auto
    };
    let pool = threads_pool(threads)?;
    let outcome = pool
        .install(|| {
            rocking_spectra::run(&sweep, &dir, progress, |v| {
                let cell = [
                    (&knobs[0], KnobValue::Text(abs[v[0] as usize].clone())),
                    (&knobs[1], KnobValue::Number(v[1])),
                ];
                base.run_knobs(&cell).map_err(|e| e.to_string())
            })
        })
        .map_err(sweep_error)?;
    let names: Vec<String> = list
        .iter()
        .map(|p| {
            p.file_name()
                .map(|n| n.to_string_lossy().into_owned())
                .unwrap_or_default()
        })
        .collect();
    let messages: BTreeMap<usize, &str> = outcome
        .failures
        .iter()
        .map(|(i, m)| (*i, m.as_str()))
        .collect();
    // Per scale: runs, failed, overturned (of the runs that finished).
    let mut tally: Vec<(f64, usize, usize, usize)> = scales.iter().map(|&s| (s, 0, 0, 0)).collect();
    let mut runs = csv::Writer::from_writer(Vec::new());
    let csv_err = |e: csv::Error| CliError::Internal(format!("cannot write runs.csv: {e}"));
    runs.write_record([
        "record",
        "scale",
        "class",
        "overturned",
        "max_theta_over_alpha",
        "impacts",
        "message",
    ])
    .map_err(csv_err)?;
    for c in &outcome.cells {
        let v = sweep.values(c.index);
        let (r, k) = (v[0] as usize, c.index % scales.len());
        let t = &mut tally[k];
        t.1 += 1;
        let row = if c.class == CellClass::Failed {
            t.2 += 1;
            // A failed run has no result: its fields are empty, never a made-up "survived".
            let m = messages.get(&c.index).copied().unwrap_or("failed");
            [
                names[r].clone(),
                v[1].to_string(),
                c.class.as_str().into(),
                String::new(),
                String::new(),
                String::new(),
                m.to_string(),
            ]
        } else {
            let over = is_overturned(c.class);
            t.3 += usize::from(over);
            [
                names[r].clone(),
                v[1].to_string(),
                c.class.as_str().into(),
                over.to_string(),
                c.max_theta_over_alpha.to_string(),
                c.impacts.to_string(),
                String::new(),
            ]
        };
        runs.write_record(&row).map_err(csv_err)?;
    }
    let rows = runs
        .into_inner()
        .map_err(|e| CliError::Internal(format!("cannot write runs.csv: {e}")))?;
    let mut written = Vec::new();
    let path = dir.join("runs.csv");
    write_atomic(&path, &rows)?;
    written.push(path);
    // The fraction overturned is of the runs that finished; failed runs are counted apart, and a
    // scale whose runs all failed has no fraction (an empty field, no plotted point).
    let fraction = |n: usize, f: usize, o: usize| (n > f).then(|| o as f64 / (n - f) as f64);
    let mut frag = String::from("scale,runs,failed,completed,overturned,fraction_overturned\n");
    for &(s, n, f, o) in &tally {
        let x = fraction(n, f, o).map_or(String::new(), |x| x.to_string());
        frag.push_str(&format!("{s},{n},{f},{},{o},{x}\n", n - f));
    }
    let path = dir.join("fragility.csv");
    write_atomic(&path, frag.as_bytes())?;
    written.push(path);
    let meta = json!({
        "scene": base.path.display().to_string(),
        "scene_text": base.text,
        "set": base.sets,
        "records": abs.iter().zip(&digests).map(|(a, d)| json!({"path": a, "digest": d})).collect::<Vec<_>>(),
        "scales": scales,
        "fingerprint": sweep.fingerprint,
        "runs": outcome.cells.len(),
        "computed_now": outcome.computed,
        "failed": outcome.failures.len(),
        "failures": outcome.failures.iter().map(|(i, m)| {
            let v = sweep.values(*i);
            json!({"run": i, "record": names[v[0] as usize], "scale": v[1], "message": m})
        }).collect::<Vec<_>>(),
        "versions": {"rocking": env!("CARGO_PKG_VERSION"), "program": program_digest()},
    });
    let path = dir.join("meta.json");
    write_atomic(
        &path,
        (serde_json::to_string_pretty(&meta).unwrap_or_default() + "\n").as_bytes(),
    )?;
    written.push(path);
    let points: Vec<(f64, f64)> = tally
        .iter()
        .filter_map(|&(s, n, f, o)| fraction(n, f, o).map(|x| (s, x)))
        .collect();
    written.extend(plot::fragility_plots(&points, list.len(), &dir)?);
    out!(
        "{}: {} records x {} scales ({} runs computed now) in {:.2} s",
        scene_path.display(),
        list.len(),
        scales.len(),
        outcome.computed,
        outcome.elapsed.as_secs_f64()
    );
    for &(s, n, f, o) in &tally {
        let failed = if f > 0 {
            format!("; {f} of {n} runs failed")
        } else {
            String::new()
        };
        match fraction(n, f, o) {
            Some(x) => out!(
                "  scale {s}: {o}/{} overturned ({:.1} %){failed}",
                n - f,
                100.0 * x
            ),
            None => out!("  scale {s}: no run finished{failed}"),
        }
    }
    out!("  wrote:");
    for p in written {
        out!("    {}", p.display());
    }
    failed_runs(&outcome, "runs", "runs.csv")
}

/// Whether a class is one of the overturned ones.
fn is_overturned(class: CellClass) -> bool {
    matches!(
        class,
        CellClass::OverturnedNoImpact
            | CellClass::OverturnedOneImpact
            | CellClass::OverturnedImpacts
    )
}

/// One boundary: the family value and, per x value, the smallest overturning y.
type Line = (f64, BTreeMap<u64, (f64, f64)>);

/// The smallest value of the last axis at which cells overturn, per value of the others (the
/// overturning boundary of Fig. 9), for cells of a 2- or 3-axis sweep.
pub fn boundary(sweep: &Sweep, cells: &[Cell]) -> Vec<(f64, Vec<(f64, f64)>)> {
    let n = sweep.axes.len();
    // Keyed by the bit patterns of the family and x values (exact, ordered for positive values).
    let mut lines: BTreeMap<u64, Line> = BTreeMap::new();
    for c in cells {
        let v = sweep.values(c.index);
        let family = if n >= 3 { v[n - 3] } else { 0.0 };
        let x = v[n - 2];
        let y = v[n - 1];
        let over = matches!(
            c.class,
            CellClass::OverturnedNoImpact
                | CellClass::OverturnedOneImpact
                | CellClass::OverturnedImpacts
        );
        let line = lines
            .entry(family.to_bits())
            .or_insert((family, BTreeMap::new()));
        let e = line.1.entry(x.to_bits()).or_insert((x, f64::INFINITY));
        if over {
            e.1 = e.1.min(y);
        }
    }
    lines
        .into_values()
        .map(|(f, pts)| {
            let mut p: Vec<(f64, f64)> = pts.into_values().filter(|(_, y)| y.is_finite()).collect();
            p.sort_by(|a, b| a.0.total_cmp(&b.0));
            (f, p)
        })
        .collect()
}
