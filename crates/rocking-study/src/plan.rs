//! Sweeps of a scene file: the scene loaded once with its overrides ([`Base`]), and the two
//! kinds of study built on it, a spectrum over axes of scene values ([`Plan::spectrum`]) and a
//! record suite at scale factors ([`Plan::batch`]). The command line and the Python package
//! both plan here, so a cell means the same thing wherever it is run.

use std::path::{Path, PathBuf};

use rocking::History;
use rocking_scene::knob::{self, Knob, KnobValue};
use rocking_scene::scene::{self, Scene};
use rocking_scene::setup::{self, Setup};
use rocking_scene::SceneError;

use rocking::SimError;
use rocking_spectra::{fnv1a, Axis, CellClass, CellFailure, CellRun, Sweep};

use crate::run_report;

/// The paper's spectrum axes (Figs 6-8), used when neither the command nor the scene names any.
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
    /// The scene with the overrides, loaded once: cells apply knobs to it.
    scene: Scene,
    /// The scene has a compliant ground (which the sweeps refuse, [`Base::refuse_ground`]).
    ground: bool,
    /// Digest of the scene's record file (contents), when it has one.
    record_digest: Option<String>,
    /// What every cell reports besides its class, max θ/α and impacts (`[sweep] report`).
    report: Vec<String>,
}

/// A sweep engine's error as a study reports it: a journal of another sweep in the output
/// directory is the user's to fix (input), anything else a failure.
pub fn sweep_error(e: rocking_spectra::SweepError) -> SceneError {
    match e {
        rocking_spectra::SweepError::Mismatch(_) | rocking_spectra::SweepError::NotJournal(..) => {
            SceneError::input(e.to_string())
        }
        other => SceneError::failure(other.to_string()),
    }
}

/// A digest of a file's contents: results computed from a record are reused only while the
/// record's bytes are the same.
pub fn file_digest(path: &Path) -> Result<String, SceneError> {
    let bytes = std::fs::read(path)
        .map_err(|e| SceneError::input(format!("{}: cannot read: {e}", path.display())))?;
    Ok(format!("{:016x}", fnv1a(&bytes)))
}

/// A digest of the running program (its executable), so that a journal written by another build
/// is not reused; the package version when the executable cannot be read.
pub fn program_digest() -> &'static str {
    static DIGEST: std::sync::OnceLock<String> = std::sync::OnceLock::new();
    DIGEST.get_or_init(
        || match std::env::current_exe().and_then(|exe| executable_hash(&exe)) {
            Ok(hash) => format!("{} {hash:016x}", env!("CARGO_PKG_VERSION")),
            Err(_) => env!("CARGO_PKG_VERSION").to_string(),
        },
    )
}

/// FxHash of a file's bytes, read through one reused 1 MiB buffer: reading the ~20 MB executable
/// whole into a fresh allocation cost a page fault per 4 KiB (about 2 % of a 100 × 100
/// spectrum's samples, `perf record`). Every chunk but the last is full, so the hash does not
/// depend on how the operating system splits the reads.
fn executable_hash(path: &Path) -> std::io::Result<u64> {
    use std::hash::Hasher as _;
    use std::io::Read as _;
    const CHUNK: usize = 1 << 20;
    let mut file = std::fs::File::open(path)?;
    let mut buf = Vec::with_capacity(CHUNK);
    let mut h = rustc_hash::FxHasher::default();
    loop {
        buf.clear();
        let n = (&mut file).take(CHUNK as u64).read_to_end(&mut buf)?;
        h.write(&buf);
        if n < CHUNK {
            return Ok(h.finish());
        }
    }
}

/// Whether the reported quantity `key` needs the cell's fixed-base twin.
fn needs_twin(key: &str) -> bool {
    key.starts_with("fixed_base.") || run_report::RATIOS.contains(&key)
}

/// The number at `key` (`a.b` for a nested entry) of a run's quantities: +∞ for an unbounded
/// one (`"inf"`, [`run_report::number`]), which cells.csv and runs.csv write as `inf`.
fn lookup(q: &serde_json::Map<String, serde_json::Value>, key: &str) -> Option<f64> {
    let (head, tail) = match key.split_once('.') {
        Some((h, t)) => (h, Some(t)),
        None => (key, None),
    };
    let v = q.get(head)?;
    match tail {
        Some(t) => lookup(v.as_object()?, t),
        None => run_report::number(v),
    }
}

/// Refuses a reported quantity that no run of the scene has: the allowed ones are the numeric
/// entries of a run's quantities (found by a run of the scene that ends at once, forces on, with
/// its fixed-base twin; the force maxima in SI only for a physical scene), and the ratios to the
/// twin.
fn check_report(sc: &Scene, m: &Setup, report: &[String]) -> Result<(), SceneError> {
    if report.is_empty() {
        return Ok(());
    }
    let probe = rocking::Options {
        t_end: 1e-9,
        forces: true,
        history: History::None,
        event_log: false,
        ..m.options
    };
    let run = |o: &rocking::Options| {
        rocking::simulate(&m.structure, &m.excitation, &m.effects, o)
            .map(|r| r.summary)
            .map_err(|e| SceneError::failure(format!("{}: {e}", sc.src.path.display())))
    };
    let twin = run(&probe.fixed_base_twin())?;
    let q = run_report::quantities(&run(&probe)?, Some(&twin), run_report::si_scale(m))?;
    let mut allowed: Vec<String> = Vec::new();
    for (k, v) in &q {
        match v {
            serde_json::Value::Object(o) => allowed.extend(
                o.iter()
                    .filter(|(_, x)| run_report::number(x).is_some())
                    .map(|(j, _)| format!("{k}.{j}")),
            ),
            v if run_report::number(v).is_some() => allowed.push(k.clone()),
            _ => {}
        }
    }
    allowed.extend(run_report::RATIOS.iter().map(|r| r.to_string()));
    allowed.sort();
    allowed.dedup();
    for (i, key) in report.iter().enumerate() {
        if report[..i].contains(key) {
            return Err(sc.src.err(
                &format!("sweep.report.{i}"),
                format_args!("`report` in [sweep] names `{key}` twice: give each quantity once"),
            ));
        }
        if needs_twin(key) {
            // As `run` refuses `fixed_base_reference` (the same words).
            setup::check_twin(
                &sc.src,
                &format!("sweep.report.{i}"),
                &format!("`{key}` in [sweep] report"),
                &m.options,
            )?;
        }
        if !allowed.contains(key) {
            let names: Vec<&str> = allowed.iter().map(String::as_str).collect();
            let hint = if run_report::SI_MAXIMA
                .iter()
                .any(|q| key.strip_prefix("fixed_base.").unwrap_or(key) == *q)
            {
                "; the maxima in SI need a scene in physical units".to_string()
            } else {
                rocking_scene::scene::suggest(key, &names)
                    .map(|s| format!("; did you mean `{s}`?"))
                    .unwrap_or_default()
            };
            return Err(sc.src.err(
                &format!("sweep.report.{i}"),
                format_args!(
                    "`report` in [sweep] names `{key}`, which a run does not report as a number \
                     (allowed: {}){hint}",
                    allowed.join(", ")
                ),
            ));
        }
    }
    Ok(())
}

impl Base {
    /// Reads and validates the scene file with the overrides `sets`.
    pub fn load(path: &Path, sets: &[String]) -> Result<Base, SceneError> {
        Base::from_text(path, scene::read(path)?, sets)
    }

    /// The same from the scene's text; `path` names it in messages and resolves relative paths.
    pub fn from_text(path: &Path, text: String, sets: &[String]) -> Result<Base, SceneError> {
        let parsed = scene::parse_text(path, text.clone())?;
        let sc = parsed.load(sets)?;
        let m = setup::build(&sc)?;
        let title = m.title.clone().map(|t| {
            if sets.is_empty() {
                t
            } else {
                let shown: Vec<String> = sets.iter().map(|s| labelled(s)).collect();
                format!("{t} [{}]", shown.join(", "))
            }
        });
        let record = sc.spec.excitation.as_ref().and_then(|e| {
            (e.kind.as_deref() == Some("record"))
                .then(|| e.path.as_ref().map(|p| sc.src.dir().join(p)))
                .flatten()
        });
        let record_digest = record.as_deref().map(file_digest).transpose()?;
        let report = sc
            .spec
            .sweep
            .as_ref()
            .and_then(|s| s.report.clone())
            .unwrap_or_default();
        check_report(&sc, &m, &report)?;
        Ok(Base {
            path: path.to_path_buf(),
            text,
            parsed,
            sets: sets.to_vec(),
            title,
            record_digest,
            scene: sc,
            report,
            ground: m.ground.is_some(),
        })
    }

    /// Refuses a compliant ground (issue 44): the sweeps do not run one yet (exit 2 naming
    /// `ground.kind`; `rocking run` and `check` take the scene).
    pub fn refuse_ground(&self) -> Result<(), SceneError> {
        if !self.ground {
            return Ok(());
        }
        let m = setup::build(&self.scene)?;
        setup::refuse_ground(&self.scene.src, &m, "sweeps (spectrum, batch, ida)")
    }

    /// The quantities every cell reports (`[sweep] report`).
    pub fn report(&self) -> &[String] {
        &self.report
    }

    /// The scene file's path.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// The scene file's text.
    pub fn text(&self) -> &str {
        &self.text
    }

    /// The overrides (`key.path=value`).
    pub fn sets(&self) -> &[String] {
        &self.sets
    }

    /// The scene's title with the overrides, when it has one.
    pub fn title(&self) -> Option<&str> {
        self.title.as_deref()
    }

    /// The scene with the overrides.
    pub fn scene(&self) -> &Scene {
        &self.scene
    }

    /// Resolves the keys of the axes once; `None` when one is not a knob (then cells go through
    /// `--set` overrides).
    pub fn knobs(&self, keys: &[&str]) -> Option<Vec<Knob>> {
        keys.iter()
            .map(|k| Knob::resolve(&self.scene, k).ok())
            .collect()
    }

    /// Runs a cell: the scene with its knobs set, summary and reported quantities only.
    pub fn run_knobs(&self, cell: &[(&Knob, KnobValue)]) -> Result<CellRun, SceneError> {
        let m = knob::setup(&self.scene, cell)?;
        self.simulate(m)
    }

    /// Runs the scene with extra overrides, summary and reported quantities only (no history,
    /// events or energy).
    pub fn run(&self, extra: &[String]) -> Result<CellRun, SceneError> {
        self.simulate(self.model(extra)?)
    }

    /// A sweep's cell with these knobs set ([`Base::run_knobs`]), or why it has no result.
    fn knobs_cell(&self, cell: &[(&Knob, KnobValue)]) -> Result<CellRun, CellFailure> {
        self.cell(knob::setup(&self.scene, cell).map_err(|e| e.to_string())?)
    }

    /// A sweep's cell with extra overrides ([`Base::run`]), or why it has no result.
    fn sets_cell(&self, extra: &[String]) -> Result<CellRun, CellFailure> {
        self.cell(self.model(extra).map_err(|e| e.to_string())?)
    }

    /// The scene with the overrides and `extra` ones, built.
    pub fn model(&self, extra: &[String]) -> Result<Setup, SceneError> {
        let mut sets = self.sets.clone();
        sets.extend_from_slice(extra);
        setup::build(&self.parsed.load(&sets)?)
    }

    fn simulate(&self, m: Setup) -> Result<CellRun, SceneError> {
        self.cell(m).map_err(|f| SceneError::failure(f.message))
    }

    /// A cell's run, or why it has no result: a run whose mass matrix became singular left the
    /// model's validity (its own class, [`CellClass::BeyondModel`]); any other error is a failure.
    fn cell(&self, mut m: Setup) -> Result<CellRun, CellFailure> {
        m.options.history = History::None;
        m.options.event_log = false;
        m.options.energy = false;
        m.options.stop_when_known = true;
        // The forces cost a kernel per step: only a sweep that reports some pays for them.
        m.options.forces = !self.report.is_empty();
        // A cell keeps its class, max θ/α and impacts, and the reported quantities: max |u| is
        // only needed for the latter.
        m.options.max_deflection = !self.report.is_empty();
        let path = self.path.display();
        let run = |options: &rocking::Options| {
            rocking::simulate(&m.structure, &m.excitation, &m.effects, options).map_err(|e| match e
            {
                SimError::SingularMassMatrix { .. } => CellFailure {
                    class: CellClass::BeyondModel,
                    message: format!("{path}: beyond the model: {e}"),
                },
                e => format!("{path}: simulation failed: {e}").into(),
            })
        };
        let summary = run(&m.options)?.summary;
        if self.report.is_empty() {
            return Ok(summary.into());
        }
        let twin = if self.report.iter().any(|k| needs_twin(k)) {
            Some(run(&m.options.fixed_base_twin())?.summary)
        } else {
            None
        };
        let q = run_report::quantities(&summary, twin.as_ref(), run_report::si_scale(&m))
            .map_err(|e| e.to_string())?;
        let reported = self
            .report
            .iter()
            .map(|k| {
                lookup(&q, k).ok_or_else(|| {
                    format!(
                        "{path}: the run has no value of `{k}` (a ratio to a fixed-base twin that \
                         carries no force has none)"
                    )
                })
            })
            .collect::<Result<Vec<f64>, _>>()?;
        Ok(CellRun { summary, reported })
    }

    /// Identifies everything a cell's result depends on: the program, the scene text, the
    /// overrides, the record contents, the axes and `extra` (for batch, the records and their
    /// digests).
    pub fn fingerprint(&self, axes: &[Axis], extra: &str) -> String {
        let mut key = format!(
            "{}\n{}\n{:?}\n{:?}\n{extra}\n",
            program_digest(),
            self.text,
            self.sets,
            self.record_digest
        );
        for a in axes {
            if a.is_text() {
                key.push_str(&format!("{}={:?}\n", a.key, a.texts));
            } else {
                key.push_str(&format!("{}={:?}\n", a.key, a.values));
            }
        }
        format!("{:016x}", fnv1a(key.as_bytes()))
    }
}

/// The reference `[sweep] reference` names and its override, checked against [`REFERENCES`].
type ReferenceKind = (&'static str, &'static str, &'static str);

fn reference_sets(base: &Base) -> Result<Option<ReferenceKind>, SceneError> {
    let spec = base.scene.spec.sweep.as_ref();
    let Some(name) = spec.and_then(|s| s.reference.as_deref()) else {
        return Ok(None);
    };
    match REFERENCES.iter().find(|(n, _, _)| *n == name) {
        Some(&r) => Ok(Some(r)),
        None => {
            let allowed: Vec<String> = REFERENCES
                .iter()
                .map(|(n, _, _)| format!("\"{n}\""))
                .collect();
            Err(base.scene.src.err(
                "sweep.reference",
                format!(
                    "`sweep.reference = \"{name}\"` is not a reference structure: allowed: {}",
                    allowed.join(", ")
                ),
            ))
        }
    }
}

/// Everything a spectrum or batch would refuse in the scene's `[sweep]` table, checked without
/// one (`[sweep] report` is checked by [`Base::load`]): `rocking check` refuses what they refuse.
pub fn check_table(base: &Base) -> Result<(), SceneError> {
    reference_sets(base).map(|_| ())
}

/// Record files as given: a file stands for itself, a folder for its record files
/// ([`rocking_motion::record_files_in`], the one rule of `ida` and `batch`), sorted by name.
pub fn expand_records(
    given: impl IntoIterator<Item = PathBuf>,
) -> Result<Vec<PathBuf>, SceneError> {
    let mut files = Vec::new();
    for f in given {
        if f.is_dir() {
            files.extend(
                rocking_motion::record_files_in(&f)
                    .map_err(|e| SceneError::input(e.to_string()))?,
            );
        } else {
            files.push(f);
        }
    }
    Ok(files)
}

/// An override `key=value` as a title shows it: a number in the paper's notation
/// (`ω_n/p = 2.5`), anything else as written.
fn labelled(set: &str) -> String {
    if let Some((_, _, label)) = REFERENCES.iter().find(|(_, s, _)| *s == set) {
        return (*label).to_string();
    }
    match set.split_once('=') {
        Some((key, value)) => match value.trim().parse::<f64>() {
            Ok(v) => rocking_scene::labels::axis_value(key.trim(), v),
            Err(_) => set.to_string(),
        },
        None => set.to_string(),
    }
}

/// The reference structures a spectrum's figure can be drawn against (`[sweep] reference`): name,
/// the override that makes one from the scene, and its legend text.
pub const REFERENCES: [(&str, &str, &str); 1] =
    [("rigid", "effects.flexibility=false", "rigid column")];

/// The sweep of a reference structure over the axes a spectrum's figure shows.
pub struct ReferencePlan {
    /// Its name in `[sweep] reference`.
    pub name: &'static str,
    /// Its legend text.
    pub label: &'static str,
    /// The reference scene swept over the figure's axes.
    pub plan: Plan,
}

/// An override `key=value` that reads back as the same f64.
fn set_arg(axis: &Axis, v: f64) -> String {
    match axis.text(v) {
        // A JSON string is a TOML basic string (the same escapes).
        Some(t) => format!("{}={}", axis.key, serde_json::Value::from(t)),
        None => format!("{}={v:?}", axis.key),
    }
}

/// The keys a batch sets itself, from its records and scale factors: not axes of its own.
const BATCH_KEYS: [(&str, &str); 3] = [
    ("record", "--records"),
    ("excitation.path", "--records"),
    ("excitation.scale", "--scales"),
];

/// The axes of a batch's own (`--axis`), parsed as a spectrum's, one per key and none on a key
/// the batch sets from its records and scales.
fn batch_axes(path: &Path, specs: &[String]) -> Result<Vec<Axis>, SceneError> {
    let mut axes: Vec<Axis> = Vec::new();
    for s in specs {
        let a =
            Axis::parse(s).map_err(|e| SceneError::input(format!("{}: --{e}", path.display())))?;
        if let Some((_, flag)) = BATCH_KEYS.iter().find(|(k, _)| *k == a.key) {
            return Err(SceneError::input(format!(
                "{}: --axis `{s}`: a batch sets `{}` itself from {flag}: give its values there \
                 (an axis may be any other numeric or text key of the scene)",
                path.display(),
                a.key
            )));
        }
        if axes.iter().any(|b| b.key == a.key) {
            return Err(SceneError::input(format!(
                "{}: --axis `{s}`: two axes on `{}`: each key may have one axis (list its values \
                 in one --axis)",
                path.display(),
                a.key
            )));
        }
        axes.push(a);
    }
    Ok(axes)
}

/// How a cell's axis values reach its simulation.
enum Cells {
    /// Knobs resolved once (the fast path).
    Knobs(Vec<Knob>),
    /// Overrides re-parsed per cell (keys that are not knobs).
    Sets,
    /// A record suite: the record's index, the scale factor and the values of the batch's own
    /// axes (`--axis`), set through knobs resolved once (`knobs`: path, scale, then one per
    /// axis), or, when an axis's key is not a knob (`structure.model`), through overrides
    /// re-parsed per cell (`knobs` is `None`).
    Records {
        knobs: Option<Vec<Knob>>,
        paths: Vec<String>,
    },
}

/// The records of a batch study.
pub struct Records {
    /// The record files as given (a directory expanded to its .AT2 files, sorted).
    pub files: Vec<PathBuf>,
    /// Their canonical paths (what the scene is given).
    pub paths: Vec<String>,
    /// Digests of their contents.
    pub digests: Vec<String>,
    /// Their file names (for tables).
    pub names: Vec<String>,
    /// The scale factors.
    pub scales: Vec<f64>,
}

/// A planned sweep: the base scene, the cells (axes and fingerprint) and how each cell runs.
pub struct Plan {
    /// The scene every cell starts from.
    pub base: Base,
    /// The axes and the fingerprint.
    pub sweep: Sweep,
    /// The records of a batch study (`None` for a spectrum).
    pub records: Option<Records>,
    cells: Cells,
}

impl Plan {
    /// A spectrum: `axis_specs` (`key.path=start:stop:count` or `key.path=v1,v2,...`), else the
    /// scene's `[sweep] axes`, else the paper's. Every axis value is validated against the scene
    /// before anything runs.
    pub fn spectrum(base: Base, axis_specs: &[String]) -> Result<Plan, SceneError> {
        base.refuse_ground()?;
        let path = base.path.clone();
        let specs: Vec<String> = if !axis_specs.is_empty() {
            axis_specs.to_vec()
        } else if let Some(a) = base.scene.spec.sweep.as_ref().and_then(|s| s.axes.clone()) {
            a
        } else {
            DEFAULT_AXES.iter().map(|s| s.to_string()).collect()
        };
        let axes = specs
            .iter()
            .map(|s| {
                Axis::parse(s).map_err(|e| SceneError::input(format!("{}: {e}", path.display())))
            })
            .collect::<Result<Vec<_>, _>>()?;
        // Bound the sweep, then validate every axis value against the scene.
        Sweep::checked_len(&axes)
            .map_err(|e| SceneError::input(format!("{}: {e}", path.display())))?;
        let keys: Vec<&str> = axes.iter().map(|a| a.key.as_str()).collect();
        if let Some(k) = keys
            .iter()
            .enumerate()
            .find_map(|(i, k)| keys[..i].contains(k).then_some(k))
        {
            return Err(SceneError::input(format!(
                "{}: two axes on `{k}`: each key may have one axis (list its values in one --axis)",
                path.display()
            )));
        }
        for a in &axes {
            for &v in &a.values {
                base.model(&[set_arg(a, v)])?;
            }
        }
        reference_sets(&base)?;
        let cells = match base.knobs(&keys) {
            Some(k) => Cells::Knobs(k),
            None => Cells::Sets,
        };
        let sweep = Sweep {
            fingerprint: base.fingerprint(&axes, "spectrum"),
            axes,
            reported: base.report.clone(),
        };
        Ok(Plan {
            base,
            sweep,
            records: None,
            cells,
        })
    }

    /// A record suite: every record (files, or directories of .AT2 files; else the scene's
    /// `[sweep] records`) at every scale factor (else the scene's `[sweep] scales`, else 1), and
    /// at every cell of the axes `axis_specs` (`--axis`, as [`Plan::spectrum`] reads them:
    /// numbers or texts, e.g. `structure.model=cubic,cantilever_modes2`). The cells are records
    /// x scales x the axes' cells (the last axis fastest). Every record and every axis value is
    /// read and validated before anything runs; the number of runs is bounded as a spectrum's
    /// cells ([`rocking_spectra::MAX_CELLS`]).
    pub fn batch(
        base: Base,
        records: &[PathBuf],
        scales: &[f64],
        axis_specs: &[String],
    ) -> Result<Plan, SceneError> {
        base.refuse_ground()?;
        let path = base.path.clone();
        let sweep_spec = base.scene.spec.sweep.as_ref();
        let mut given: Vec<PathBuf> = records.to_vec();
        if given.is_empty() {
            let dir = base.scene.src.dir();
            given = sweep_spec
                .and_then(|s| s.records.clone())
                .unwrap_or_default()
                .iter()
                .map(|r| dir.join(r))
                .collect();
        }
        // A directory stands for all the .AT2 files in it.
        let files = expand_records(given)?;
        if files.is_empty() {
            return Err(SceneError::input(format!(
                "{}: no records: give --records FILE|DIR or `records = [...]` in [sweep] ({})",
                path.display(),
                rocking_motion::formats::FOLDER_RULE
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
            return Err(SceneError::input(format!(
                "scale factor {bad} is not allowed: scales must be > 0"
            )));
        }
        let paths: Vec<String> = files
            .iter()
            .map(|p| {
                std::fs::canonicalize(p)
                    .unwrap_or_else(|_| p.clone())
                    .display()
                    .to_string()
            })
            .collect();
        let record_set = |i: usize| format!("excitation.path={:?}", paths[i]);
        for i in 0..paths.len() {
            base.model(&[record_set(i)])?;
        }
        let own = batch_axes(&path, axis_specs)?;
        let mut axes = vec![
            Axis::numbers("record", (0..paths.len()).map(|i| i as f64).collect()),
            Axis::numbers("excitation.scale", scales.clone()),
        ];
        axes.extend(own.iter().cloned());
        let what = if own.is_empty() {
            "records x scales"
        } else {
            "records x scales x axes"
        };
        Sweep::checked_len(&axes)
            .map_err(|e| SceneError::input(format!("{}: {what}: {e}", path.display())))?;
        for a in &own {
            for &v in &a.values {
                base.model(&[set_arg(a, v)])?;
            }
        }
        let digests = files
            .iter()
            .map(|p| file_digest(p))
            .collect::<Result<Vec<_>, _>>()?;
        let key: Vec<String> = paths
            .iter()
            .zip(&digests)
            .map(|(a, d)| format!("{a} {d}"))
            .collect();
        let mut keys = vec!["excitation.path", "excitation.scale"];
        keys.extend(own.iter().map(|a| a.key.as_str()));
        // Without axes, the record path and scale are always knobs (as before the axes).
        let knobs = base.knobs(&keys);
        if own.is_empty() && knobs.is_none() {
            return Err(SceneError::failure("record path and scale are not knobs"));
        }
        let names = files
            .iter()
            .map(|p| {
                p.file_name()
                    .map(|n| n.to_string_lossy().into_owned())
                    .unwrap_or_default()
            })
            .collect();
        let sweep = Sweep {
            fingerprint: base.fingerprint(&axes, &key.join("\n")),
            axes,
            reported: base.report.clone(),
        };
        Ok(Plan {
            base,
            sweep,
            cells: Cells::Records {
                knobs,
                paths: paths.clone(),
            },
            records: Some(Records {
                files,
                paths,
                digests,
                names,
                scales,
            }),
        })
    }

    /// The sweep of the reference structure `[sweep] reference` asks for (the rigid column: the
    /// scene with `effects.flexibility = false`) over the axes the figure shows (the last two),
    /// or `None`. Its cells are cheap beside the sweep's (one structure, the rigid model) and are
    /// run where the figure is drawn, so a sharded sweep's merge draws the same figure.
    pub fn reference(&self) -> Result<Option<ReferencePlan>, SceneError> {
        if self.records.is_some() {
            return Ok(None);
        }
        let Some((name, set, label)) = reference_sets(&self.base)? else {
            return Ok(None);
        };
        let mut sets = self.base.sets.clone();
        sets.push(set.to_string());
        let base = Base::from_text(&self.base.path, self.base.text.clone(), &sets)?;
        let n = self.sweep.axes.len();
        let specs: Vec<String> = self.sweep.axes[n.saturating_sub(2)..]
            .iter()
            .map(Axis::spec)
            .collect();
        Ok(Some(ReferencePlan {
            name,
            label,
            plan: Plan::spectrum(base, &specs)?,
        }))
    }

    /// Runs the cell with these axis values (summary only), or says why it has no result.
    pub fn run_cell(&self, values: &[f64]) -> Result<CellRun, CellFailure> {
        match &self.cells {
            Cells::Knobs(knobs) => {
                let cell: Vec<(&Knob, KnobValue)> = knobs
                    .iter()
                    .zip(&self.sweep.axes)
                    .zip(values)
                    .map(|((k, a), &v)| {
                        let value = match a.text(v) {
                            Some(t) => KnobValue::Text(t.to_string()),
                            None => KnobValue::Number(v),
                        };
                        (k, value)
                    })
                    .collect();
                self.base.knobs_cell(&cell)
            }
            Cells::Sets => {
                let extra: Vec<String> = self
                    .sweep
                    .axes
                    .iter()
                    .zip(values)
                    .map(|(a, &v)| set_arg(a, v))
                    .collect();
                self.base.sets_cell(&extra)
            }
            Cells::Records {
                knobs: Some(knobs),
                paths,
            } => {
                let mut cell = vec![
                    (
                        &knobs[0],
                        KnobValue::Text(paths[values[0] as usize].clone()),
                    ),
                    (&knobs[1], KnobValue::Number(values[1])),
                ];
                for ((k, a), &v) in knobs[2..]
                    .iter()
                    .zip(&self.sweep.axes[2..])
                    .zip(&values[2..])
                {
                    let value = match a.text(v) {
                        Some(t) => KnobValue::Text(t.to_string()),
                        None => KnobValue::Number(v),
                    };
                    cell.push((k, value));
                }
                self.base.knobs_cell(&cell)
            }
            Cells::Records { knobs: None, paths } => {
                let mut extra = vec![
                    format!("excitation.path={:?}", paths[values[0] as usize]),
                    format!("excitation.scale={:?}", values[1]),
                ];
                extra.extend(
                    self.sweep.axes[2..]
                        .iter()
                        .zip(&values[2..])
                        .map(|(a, &v)| set_arg(a, v)),
                );
                self.base.sets_cell(&extra)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::executable_hash;

    /// The hash follows every byte of a file of several chunks, the last one partial, and
    /// nothing else: the same bytes in another file give the same hash.
    #[test]
    fn executable_hash_follows_the_bytes_across_chunks() {
        let dir = tempfile::tempdir().unwrap();
        let bytes: Vec<u8> = (0..(5 << 19) + 123)
            .map(|i: u32| (i * 7 % 251) as u8)
            .collect();
        let write = |name: &str, b: &[u8]| {
            let p = dir.path().join(name);
            std::fs::write(&p, b).unwrap();
            executable_hash(&p).unwrap()
        };
        let base = write("a", &bytes);
        assert_eq!(write("b", &bytes), base, "same bytes, another file");
        for at in [0, (1 << 20) - 1, 1 << 20, bytes.len() - 1] {
            let mut changed = bytes.clone();
            changed[at] ^= 1;
            assert_ne!(write("c", &changed), base, "byte {at} flipped");
        }
        assert_ne!(
            write("d", &bytes[..bytes.len() - 1]),
            base,
            "one byte shorter"
        );
        assert_ne!(
            write("e", &bytes[..1 << 20]),
            base,
            "cut at a chunk boundary"
        );
    }
}
