//! `rocking._rocking`: the compiled half of the Python package `rocking`. It exposes the same
//! library code paths as the `rocking` command (scene loading, `rocking_study::report` for the
//! summary, history and events, `rocking_study::plan` for sweeps), so that a result from
//! Python is the command's result. The pure-Python wrapper (`python/rocking/__init__.py`) turns
//! what this module returns into numpy arrays and friendly objects.
//!
//! Every simulation and sweep runs with the GIL released (`Python::detach`).
//!
//! It owns the Python API; it must not compute or format anything the library crates do (a
//! result from Python is the command's).

mod error;
mod figure;

use std::path::{Path, PathBuf};
use std::sync::Arc;

use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict, PyList};
use rocking_scene::models;
use rocking_scene::scene;
use rocking_scene::setup::{self, Animation, Setup};
use rocking_scene::SceneError;
use rocking_spectra::{Outcome, Sweep};
use rocking_study::plan::{Base, Plan};
use rocking_study::report;
use rocking_study::StudyError;

use crate::error::py_err;

/// f64 values as native-endian bytes, for `numpy.frombuffer` (one copy, exact).
fn f64_bytes<'py>(py: Python<'py>, values: impl Iterator<Item = f64>) -> Bound<'py, PyBytes> {
    let bytes: Vec<u8> = values.flat_map(f64::to_ne_bytes).collect();
    PyBytes::new(py, &bytes)
}

/// A scene loaded and validated with its overrides; `run()` simulates it.
#[pyclass(module = "rocking._rocking", frozen)]
struct Scene {
    path: PathBuf,
    text: String,
    sets: Vec<String>,
    model: Arc<Setup>,
}

impl Scene {
    fn build(path: PathBuf, text: String, sets: Vec<String>) -> Result<Scene, SceneError> {
        let sc = scene::load_text(&path, text.clone(), &sets)?;
        let mut m = setup::build(&sc)?;
        // As `rocking run` does: a scene with plots logs its events (impacts are marked on them).
        if m.plots {
            m.options.event_log = true;
        }
        Ok(Scene {
            path,
            text,
            sets,
            model: Arc::new(m),
        })
    }
}

#[pymethods]
impl Scene {
    /// Loads the scene file `path` with the overrides `set` (`key.path=value` strings).
    #[staticmethod]
    #[pyo3(signature = (path, set = Vec::new()))]
    fn load(py: Python<'_>, path: PathBuf, set: Vec<String>) -> PyResult<Scene> {
        py.detach(|| {
            let text = scene::read(&path)?;
            Scene::build(path, text, set)
        })
        .map_err(py_err)
    }

    /// A scene from its TOML text; `path` names it in messages and resolves relative paths
    /// (records) against its directory.
    #[staticmethod]
    #[pyo3(signature = (text, path, set = Vec::new()))]
    fn from_text(py: Python<'_>, text: String, path: PathBuf, set: Vec<String>) -> PyResult<Scene> {
        py.detach(|| Scene::build(path, text, set)).map_err(py_err)
    }

    /// The scene file's path (as given).
    #[getter]
    fn path(&self) -> PathBuf {
        self.path.clone()
    }

    /// The scene's TOML text.
    #[getter]
    fn text(&self) -> &str {
        &self.text
    }

    /// The overrides, `key.path=value`.
    #[getter]
    fn sets(&self) -> Vec<String> {
        self.sets.clone()
    }

    /// The scene's title, if it has one.
    #[getter]
    fn title(&self) -> Option<String> {
        self.model.title.clone()
    }

    /// The kernel variant the solver picked and why.
    #[getter]
    fn kernel_variant(&self) -> (&'static str, Vec<String>) {
        (self.model.variant.name, self.model.reasons.clone())
    }

    /// Simulates the scene (GIL released) and returns the run.
    fn run(&self, py: Python<'_>) -> PyResult<RunOutput> {
        let model = Arc::clone(&self.model);
        let path = self.path.clone();
        let sets = self.sets.clone();
        py.detach(move || {
            let report = report::simulate(&model, &path)?;
            let summary = report::summary_json(&model, &path, &sets, &report)?.to_string();
            let run = report.run;
            Ok::<_, StudyError>(RunOutput {
                model,
                run,
                summary,
            })
        })
        .map_err(py_err)
    }
}

/// One simulation's results: the summary (as `rocking run --json` prints it), and the history
/// and events tables of history.csv and events.csv, made on demand.
#[pyclass(module = "rocking._rocking", frozen)]
struct RunOutput {
    model: Arc<Setup>,
    run: rocking::Run,
    summary: String,
}

/// Parses a table of `report` (CSV with a header) into columns: numbers as f64 bytes, text as
/// strings; a column that is empty in every row (seconds of a dimensionless run) is left out.
/// Rust prints every f64 in its shortest round-trip form, so the numbers are the run's exactly.
fn columns<'py>(py: Python<'py>, csv: &str) -> PyResult<Bound<'py, PyDict>> {
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().unwrap_or_default().split(',').collect();
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    let out = PyDict::new(py);
    for (j, name) in header.iter().enumerate() {
        let cells: Vec<&str> = rows
            .iter()
            .map(|r| r.get(j).copied().unwrap_or(""))
            .collect();
        if !cells.is_empty() && cells.iter().all(|c| c.is_empty()) {
            continue;
        }
        let numbers: Option<Vec<f64>> = cells.iter().map(|c| c.parse().ok()).collect();
        match numbers {
            Some(v) => out.set_item(*name, f64_bytes(py, v.into_iter()))?,
            None => out.set_item(*name, PyList::new(py, &cells)?)?,
        }
    }
    Ok(out)
}

#[pymethods]
impl RunOutput {
    /// The summary as one JSON object, exactly as `rocking run --json` prints it.
    #[getter]
    fn summary_json(&self) -> &str {
        &self.summary
    }

    /// history.csv's columns (numbers as float64 bytes, `phase` as strings), or None when the
    /// scene asks for no history (`[output] history_dt`).
    fn history<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyDict>>> {
        if !self.model.history_csv {
            return Ok(None);
        }
        let csv = py
            .detach(|| report::history_csv(&self.model, &self.run))
            .map_err(py_err)?;
        columns(py, &csv).map(Some)
    }

    /// events.csv's columns, or None when the run logged no events (`[output] events`).
    fn events<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyDict>>> {
        if !self.model.options.event_log {
            return Ok(None);
        }
        let csv = py
            .detach(|| report::events_csv(&self.model, &self.run))
            .map_err(py_err)?;
        columns(py, &csv).map(Some)
    }

    /// The animated GIF of the run (its bytes), drawn as `rocking run --animate` draws it:
    /// `frames`, `width` and `height` default to the scene's `[output] animation_*` (else 150,
    /// 480, 600), within the same bounds. The run needs its history rows (a scene with
    /// `[output] animation = true` records them).
    #[pyo3(signature = (frames=None, width=None, height=None))]
    fn animation<'py>(
        &self,
        py: Python<'py>,
        frames: Option<i64>,
        width: Option<i64>,
        height: Option<i64>,
    ) -> PyResult<Bound<'py, PyBytes>> {
        let scene = self.model.animation.unwrap_or_default();
        // The scene's bounds, named as the arguments here.
        let pick = |name: &str, given: Option<i64>, bounds: (&str, i64, i64, i64), default: i64| {
            let (_, _, lo, hi) = bounds;
            match given {
                None => Ok(default),
                Some(v) if (lo..=hi).contains(&v) => Ok(v),
                Some(v) => Err(PyValueError::new_err(format!(
                    "{name} = {v} is not allowed: {lo} <= {name} <= {hi}"
                ))),
            }
        };
        let spec = Animation {
            frames: pick("frames", frames, Animation::FRAMES, scene.frames as i64)? as usize,
            width: pick("width", width, Animation::WIDTH, i64::from(scene.width))? as u32,
            height: pick("height", height, Animation::HEIGHT, i64::from(scene.height))? as u32,
        };
        let (gif, _) = py
            .detach(|| rocking_plot::animation::render(&self.model, &self.run, &spec))
            .map_err(|e| PyValueError::new_err(format!("cannot draw the animation: {e}")))?;
        Ok(PyBytes::new(py, &gif))
    }
}

/// The most threads a sweep may ask for (the command's bound).
const MAX_THREADS: usize = 1024;

/// A thread pool of `threads` threads (default: all cores), within the command's bound.
fn pool(threads: Option<usize>) -> PyResult<rayon::ThreadPool> {
    let mut b = rayon::ThreadPoolBuilder::new();
    if let Some(n) = threads {
        if !(1..=MAX_THREADS).contains(&n) {
            return Err(PyValueError::new_err(format!(
                "threads = {n} is not allowed: 1 <= threads <= {MAX_THREADS}"
            )));
        }
        b = b.num_threads(n);
    }
    b.build()
        .map_err(|e| PyRuntimeError::new_err(format!("cannot start the thread pool: {e}")))
}

/// Runs a planned sweep in memory on `threads` threads (default: all cores), GIL released.
fn run_plan(py: Python<'_>, plan: &Plan, threads: Option<usize>) -> PyResult<Outcome> {
    let pool = pool(threads)?;
    py.detach(|| pool.install(|| rocking_spectra::run_in_memory(&plan.sweep, |v| plan.run_cell(v))))
        .map_err(|e| py_err(StudyError::from(e)))
}

/// A sweep's outcome as plain Python values: axis keys and values, per cell (in sweep order, the
/// last axis fastest) the class name, max θ/α (float64 bytes) and impacts, the failures and the
/// cells beyond the model.
fn outcome_dict<'py>(
    py: Python<'py>,
    sweep: &Sweep,
    outcome: &Outcome,
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    let keys: Vec<&str> = sweep.axes.iter().map(|a| a.key.as_str()).collect();
    let values: Vec<Bound<'py, PyBytes>> = sweep
        .axes
        .iter()
        .map(|a| f64_bytes(py, a.values.iter().copied()))
        .collect();
    let texts: Vec<&[String]> = sweep.axes.iter().map(|a| a.texts.as_slice()).collect();
    d.set_item("keys", keys)?;
    d.set_item("values", values)?;
    d.set_item("texts", texts)?;
    let classes: Vec<&str> = outcome.cells.iter().map(|c| c.class.as_str()).collect();
    d.set_item("classes", classes)?;
    // What a class means is the library's ([`rocking_spectra::CellClass`]): Python does not
    // re-derive it from the names.
    let has_result: Vec<bool> = outcome.cells.iter().map(|c| c.class.has_result()).collect();
    d.set_item("has_result", has_result)?;
    let overturned: Vec<bool> = outcome
        .cells
        .iter()
        .map(|c| c.class.overturned() == Some(true))
        .collect();
    d.set_item("overturned", overturned)?;
    d.set_item(
        "max_theta_over_alpha",
        f64_bytes(py, outcome.cells.iter().map(|c| c.max_theta_over_alpha)),
    )?;
    let impacts: Vec<u64> = outcome.cells.iter().map(|c| c.impacts).collect();
    d.set_item("impacts", impacts)?;
    // The quantities of `[sweep] report` (the ground's keys on compliant ground), one float64
    // array per quantity, NaN where a cell has no result or its run no value of the quantity (a
    // time of an event that did not happen; cells.csv leaves those fields empty).
    let reported = PyDict::new(py);
    for (j, name) in sweep.reported.iter().enumerate() {
        let values = outcome.cells.iter().map(|c| {
            if c.class.has_result() {
                c.reported.get(j).copied().flatten().unwrap_or(f64::NAN)
            } else {
                f64::NAN
            }
        });
        reported.set_item(name, f64_bytes(py, values))?;
    }
    d.set_item("reported", reported)?;
    d.set_item("failures", outcome.failures.clone())?;
    d.set_item("beyond_model", outcome.beyond_model.clone())?;
    Ok(d)
}

fn base(scene: &Scene) -> Result<Base, StudyError> {
    Base::from_text(&scene.path, scene.text.clone(), &scene.sets)
}

/// A spectrum of `scene` over `axes` (`key.path=start:stop:count` or `key.path=v1,v2,...`;
/// default: the scene's `[sweep] axes`, else the paper's), as `rocking spectrum` plans it.
#[pyfunction]
#[pyo3(signature = (scene, axes = Vec::new(), threads = None))]
fn spectrum<'py>(
    py: Python<'py>,
    scene: &Scene,
    axes: Vec<String>,
    threads: Option<usize>,
) -> PyResult<Bound<'py, PyDict>> {
    let plan = py
        .detach(|| Plan::spectrum(base(scene)?, &axes))
        .map_err(py_err)?;
    let outcome = run_plan(py, &plan, threads)?;
    outcome_dict(py, &plan.sweep, &outcome)
}

/// Every record (AT2 files or folders of them; default: the scene's `[sweep] records`) at every
/// scale factor (default: `[sweep] scales`, else 1) and every cell of `axes` (`--axis`), as
/// `rocking batch` plans it.
#[pyfunction]
#[pyo3(signature = (scene, records = Vec::new(), scales = Vec::new(), threads = None, axes = Vec::new()))]
fn batch<'py>(
    py: Python<'py>,
    scene: &Scene,
    records: Vec<PathBuf>,
    scales: Vec<f64>,
    threads: Option<usize>,
    axes: Vec<String>,
) -> PyResult<Bound<'py, PyDict>> {
    let plan = py
        .detach(|| Plan::batch(base(scene)?, &records, &scales, &axes))
        .map_err(py_err)?;
    let outcome = run_plan(py, &plan, threads)?;
    let d = outcome_dict(py, &plan.sweep, &outcome)?;
    if let Some(r) = &plan.records {
        d.set_item("record_names", r.names.clone())?;
        d.set_item("record_paths", r.paths.clone())?;
        d.set_item("scales", r.scales.clone())?;
    }
    // fragility.csv's rows, from the study's table as the command writes it.
    let tables = plan.batch_tables(&outcome).map_err(py_err)?;
    let rows: Vec<serde_json::Value> = tables
        .fragility
        .objects()
        .into_iter()
        .map(serde_json::Value::Object)
        .collect();
    d.set_item("fragility", serde_json::Value::Array(rows).to_string())?;
    Ok(d)
}

/// A record-suite fragility study of the scene's `[ida]` table, as `rocking ida` runs it (IDA by
/// hunt-and-fill, or multiple stripes): `(fragility, records)` as two JSON strings, the first
/// what fragility.json holds (without the scene), the second per record its intensity measures,
/// capacity and analyses.
#[pyfunction]
#[pyo3(signature = (scene, records = Vec::new(), threads = None))]
fn ida(
    py: Python<'_>,
    scene: &Scene,
    records: Vec<PathBuf>,
    threads: Option<usize>,
) -> PyResult<(String, String)> {
    let base = py.detach(|| base(scene)).map_err(py_err)?;
    let pool = pool(threads)?;
    let study = py
        .detach(|| pool.install(|| rocking_study::ida::run(&base, &records)))
        .map_err(py_err)?;
    Ok((
        study.fragility_json().to_string(),
        study.records_json(base.report()).to_string(),
    ))
}

/// How the scene's results converge over `models` (in order), as `rocking convergence` reports
/// it: a JSON string, what convergence.json holds.
#[pyfunction]
#[pyo3(signature = (scene, models, quantities = Vec::new(), tolerance = rocking_study::convergence::DEFAULT_TOLERANCE, threads = None))]
fn convergence(
    py: Python<'_>,
    scene: &Scene,
    models: Vec<String>,
    quantities: Vec<String>,
    tolerance: f64,
    threads: Option<usize>,
) -> PyResult<String> {
    let study = py
        .detach(|| {
            rocking_study::convergence::plan(
                &scene.path,
                scene.text.clone(),
                &scene.sets,
                &models,
                &quantities,
                tolerance,
            )
        })
        .map_err(py_err)?;
    let outcome = run_plan(py, &study.plan, threads)?;
    Ok(study.report(&outcome).json().to_string())
}

/// The generated models, their variants and parameters, as `rocking models --json` prints them
/// (a JSON string).
#[pyfunction]
fn models_json() -> String {
    models::json().to_string()
}

/// The columns of history.csv and events.csv and the reportable summary quantities, with their
/// labels and units (`rocking_study::report::catalogue`, a JSON string).
#[pyfunction]
fn columns_json() -> String {
    report::catalogue().to_string()
}

/// Reads a scene file's text (the command's message when it cannot).
#[pyfunction]
fn read_scene(path: PathBuf) -> PyResult<String> {
    scene::read(Path::new(&path)).map_err(py_err)
}

/// The compiled module.
#[pymodule]
fn _rocking(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<Scene>()?;
    m.add_class::<RunOutput>()?;
    m.add_function(wrap_pyfunction!(spectrum, m)?)?;
    m.add_function(wrap_pyfunction!(batch, m)?)?;
    m.add_function(wrap_pyfunction!(ida, m)?)?;
    m.add_function(wrap_pyfunction!(convergence, m)?)?;
    m.add_function(wrap_pyfunction!(models_json, m)?)?;
    m.add_function(wrap_pyfunction!(columns_json, m)?)?;
    m.add_function(wrap_pyfunction!(read_scene, m)?)?;
    m.add_function(wrap_pyfunction!(figure::figure, m)?)?;
    m.add(
        "SimulationError",
        m.py().get_type::<error::SimulationError>(),
    )?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
