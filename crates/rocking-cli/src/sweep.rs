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
        let base = Base {
            path: path.to_path_buf(),
            text,
            parsed,
            sets: sets.to_vec(),
            title,
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

    fn fingerprint(&self, axes: &[Axis], extra: &str) -> String {
        let mut key = format!(
            "{}\n{}\n{:?}\n{extra}\n",
            env!("CARGO_PKG_VERSION"),
            self.text,
            self.sets
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

fn threads_pool(threads: Option<usize>) -> Result<rayon::ThreadPool, CliError> {
    let mut b = rayon::ThreadPoolBuilder::new();
    if let Some(n) = threads {
        if n == 0 {
            return Err(CliError::Input("--threads: must be at least 1".into()));
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
        rocking_spectra::SweepError::Mismatch(_) => CliError::Input(e.to_string()),
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
    // Validate every axis value against the scene before running anything.
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
    println!(
        "{}: {} cells ({} computed now, {} resumed) in {:.2} s on {} threads ({:.3} ms per computed cell)",
        scene_path.display(),
        outcome.cells.len(),
        outcome.computed,
        outcome.cells.len() - outcome.computed,
        outcome.elapsed.as_secs_f64(),
        pool.current_num_threads(),
                1e3 * outcome.elapsed.as_secs_f64() / outcome.computed.max(1) as f64
    );
    if !outcome.failures.is_empty() {
        eprintln!(
            "warning: {} cells failed and are marked `failed` (messages in meta.json); first: {}",
            outcome.failures.len(),
            outcome.failures[0].1
        );
    }
    for (class, n) in counts {
        println!("  {class}: {n}");
    }
    println!("  wrote:");
    for p in written {
        println!("    {}", p.display());
    }
    Ok(())
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
    let sweep = Sweep {
        fingerprint: base.fingerprint(&axes, &abs.join("\n")),
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
    for (i, m) in &outcome.failures {
        eprintln!("warning: run {i} failed and is marked `failed`: {m}");
    }
    let mut rows = String::from("record,scale,class,overturned,max_theta_over_alpha,impacts\n");
    let mut fraction: Vec<(f64, usize, usize)> = scales.iter().map(|&s| (s, 0, 0)).collect();
    for c in &outcome.cells {
        let v = sweep.values(c.index);
        let (r, k) = (v[0] as usize, c.index % scales.len());
        let over = matches!(
            c.class,
            CellClass::OverturnedNoImpact
                | CellClass::OverturnedOneImpact
                | CellClass::OverturnedImpacts
        );
        let name = list[r]
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default();
        rows.push_str(&format!(
            "{name},{},{},{over},{},{}\n",
            v[1],
            c.class.as_str(),
            c.max_theta_over_alpha,
            c.impacts
        ));
        fraction[k].1 += 1;
        fraction[k].2 += usize::from(over);
    }
    let mut written = Vec::new();
    let path = dir.join("runs.csv");
    write_atomic(&path, rows.as_bytes())?;
    written.push(path);
    let mut frag = String::from("scale,records,overturned,fraction_overturned\n");
    for (s, n, o) in &fraction {
        frag.push_str(&format!("{s},{n},{o},{}\n", *o as f64 / *n as f64));
    }
    let path = dir.join("fragility.csv");
    write_atomic(&path, frag.as_bytes())?;
    written.push(path);
    let points: Vec<(f64, f64)> = fraction
        .iter()
        .map(|(s, n, o)| (*s, *o as f64 / *n as f64))
        .collect();
    written.extend(plot::fragility_plots(&points, list.len(), &dir)?);
    println!(
        "{}: {} records x {} scales ({} runs computed now) in {:.2} s",
        scene_path.display(),
        list.len(),
        scales.len(),
        outcome.computed,
        outcome.elapsed.as_secs_f64()
    );
    for (s, n, o) in &fraction {
        println!(
            "  scale {s}: {o}/{n} overturned ({:.1} %)",
            100.0 * *o as f64 / *n as f64
        );
    }
    println!("  wrote:");
    for p in written {
        println!("    {}", p.display());
    }
    Ok(())
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
