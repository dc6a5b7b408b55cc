//! The scene every cell of a sweep starts from ([`Base`]): loaded once with its overrides, its
//! reported quantities checked, and a cell's run from knobs or overrides.

use std::path::{Path, PathBuf};

use rocking::History;
use rocking_scene::knob::{self, Knob, KnobValue};
use rocking_scene::scene::{self, Scene};
use rocking_scene::setup::{self, Setup};
use rocking_scene::SceneError;

use rocking::SimError;
use rocking_spectra::{fnv1a, Axis, CellClass, CellFailure, CellRun};

use crate::{report, StudyError};

use super::{file_digest, labelled, program_digest};

/// A scene that every cell of a sweep starts from.
pub struct Base {
    pub(super) path: PathBuf,
    pub(super) text: String,
    pub(super) parsed: scene::Parsed,
    pub(super) sets: Vec<String>,
    pub(super) title: Option<String>,
    /// The scene with the overrides, loaded once: cells apply knobs to it.
    pub(super) scene: Scene,
    /// Digest of the scene's record file (contents), when it has one.
    pub(super) record_digest: Option<String>,
    /// What every cell reports besides its class, max θ/α and impacts (`[sweep] report`).
    pub(super) report: Vec<String>,
}

/// Whether the reported quantity `key` needs the cell's fixed-base twin.
fn needs_twin(key: &str) -> bool {
    key.starts_with("fixed_base.") || report::RATIOS.contains(&key)
}

/// The value of the reported quantity `key` (`a.b` for a nested entry) of a run's quantities:
/// its number (+∞ for an unbounded one, `"inf"`, [`report::number`], which cells.csv and
/// runs.csv write as `inf`), `Some(None)` for the `null` of a time of an event that did not
/// happen ([`report::nullable`]), `None` where the run has no value.
fn lookup(q: &serde_json::Map<String, serde_json::Value>, key: &str) -> Option<Option<f64>> {
    fn at<'a>(
        q: &'a serde_json::Map<String, serde_json::Value>,
        key: &str,
    ) -> Option<&'a serde_json::Value> {
        match key.split_once('.') {
            Some((head, tail)) => at(q.get(head)?.as_object()?, tail),
            None => q.get(key),
        }
    }
    match at(q, key)? {
        serde_json::Value::Null if report::nullable(key) => Some(None),
        v => report::number(v).map(Some),
    }
}

/// Refuses a reported quantity that no run of the scene has: the allowed ones are
/// [`report::reportable_keys`] (the numbers a run of the scene reports, the twin's and the ratios
/// to it; the force maxima in SI only for a physical scene).
fn check_report(sc: &Scene, m: &Setup, report: &[String]) -> Result<(), StudyError> {
    if report.is_empty() {
        return Ok(());
    }
    let allowed = report::reportable_keys(m);
    for (i, key) in report.iter().enumerate() {
        if report[..i].contains(key) {
            return Err(sc
                .src
                .err(
                    &format!("sweep.report.{i}"),
                    format_args!(
                        "`report` in [sweep] names `{key}` twice: give each quantity once"
                    ),
                )
                .into());
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
            let hint = if let Some(wanted) = report::unmet_needs(key, m) {
                format!("; `{key}` needs {wanted}")
            } else {
                rocking_scene::scene::suggest(key, &names)
                    .map(|s| format!("; did you mean `{s}`?"))
                    .unwrap_or_default()
            };
            return Err(sc
                .src
                .err(
                    &format!("sweep.report.{i}"),
                    format_args!(
                    "`report` in [sweep] names `{key}`, which a run of this scene does not report \
                     (allowed: {}){hint}",
                    allowed.join(", ")
                ),
                )
                .into());
        }
    }
    Ok(())
}

impl Base {
    /// Reads and validates the scene file with the overrides `sets`.
    pub fn load(path: &Path, sets: &[String]) -> Result<Base, StudyError> {
        Base::from_text(path, scene::read(path)?, sets)
    }

    /// The same from the scene's text; `path` names it in messages and resolves relative paths.
    pub fn from_text(path: &Path, text: String, sets: &[String]) -> Result<Base, StudyError> {
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
        })
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
    pub fn run_knobs(&self, cell: &[(&Knob, KnobValue)]) -> Result<CellRun, StudyError> {
        let m = knob::setup(&self.scene, cell)?;
        self.simulate(m)
    }

    /// Runs the scene with extra overrides, summary and reported quantities only (no history,
    /// events or energy).
    pub fn run(&self, extra: &[String]) -> Result<CellRun, StudyError> {
        self.simulate(self.model(extra)?)
    }

    /// A sweep's cell with these knobs set ([`Base::run_knobs`]), or why it has no result.
    pub(super) fn knobs_cell(&self, cell: &[(&Knob, KnobValue)]) -> Result<CellRun, CellFailure> {
        self.cell(knob::setup(&self.scene, cell).map_err(|e| e.to_string())?)
    }

    /// A sweep's cell with extra overrides ([`Base::run`]), or why it has no result.
    pub(super) fn sets_cell(&self, extra: &[String]) -> Result<CellRun, CellFailure> {
        self.cell(self.model(extra).map_err(|e| e.to_string())?)
    }

    /// The scene with the overrides and `extra` ones, built.
    pub fn model(&self, extra: &[String]) -> Result<Setup, SceneError> {
        let mut sets = self.sets.clone();
        sets.extend_from_slice(extra);
        setup::build(&self.parsed.load(&sets)?)
    }

    pub(super) fn simulate(&self, m: Setup) -> Result<CellRun, StudyError> {
        self.cell(m).map_err(StudyError::Cell)
    }

    /// A cell's run, or why it has no result: a run whose mass matrix became singular left the
    /// model's validity (its own class, [`CellClass::BeyondModel`]); any other error is a failure.
    pub(super) fn cell(&self, mut m: Setup) -> Result<CellRun, CellFailure> {
        m.options.history = History::None;
        m.options.event_log = false;
        m.options.energy = false;
        m.options.stop_when_known = true;
        // A cell keeps its class, max θ/α and impacts, and the reported quantities: it tracks
        // the forces (a kernel per step) only for a quantity that needs them, searches inside
        // steps only for the extremes reported, and tracks max |u| only where it is reported.
        m.options.forces = self.report.iter().any(|k| report::needs_forces(k));
        m.options.force_extremes = report::force_extremes(&self.report);
        m.options.ground_extremes = report::ground_extremes(&self.report);
        m.options.max_deflection = self.report.iter().any(|k| report::needs_deflection(k));
        let path = self.path.display();
        let run = |options: &rocking::Options| {
            report::run_setup(&m, options).map_err(|e| match e {
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
        let q = report::quantities(&summary, twin.as_ref(), report::si_scale(&m))
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
            .collect::<Result<Vec<Option<f64>>, _>>()?;
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
