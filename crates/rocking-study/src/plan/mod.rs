//! Sweeps of a scene file: the scene loaded once with its overrides ([`Base`]), and the two
//! kinds of study built on it, a spectrum over axes of scene values ([`Plan::spectrum`]) and a
//! record suite at scale factors ([`Plan::batch`]). The command line and the Python package
//! both plan here, so a cell means the same thing wherever it is run.

use std::path::{Path, PathBuf};

use rocking_scene::knob::{Knob, KnobValue};
use rocking_scene::SceneError;

use crate::{AxisRefusal, Invariant, StudyError};

use rocking_spectra::{Axis, CellFailure, CellRun, Sweep};

/// The paper's spectrum axes (Figs 6-8), used when neither the command nor the scene names any.
pub const DEFAULT_AXES: [&str; 2] = [
    "excitation.omega_p_over_p=1:10:40",
    "excitation.amplitude=1:20:40",
];

mod base;
mod batch_tables;
mod digest;

pub use base::Base;
pub use batch_tables::{BatchTables, ScaleTally};
pub use digest::{file_digest, program_digest};

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
    ("record", "its records"),
    ("excitation.path", "its records"),
    ("excitation.scale", "its scale factors"),
];

/// The axes of a batch's own (given by its caller), parsed as a spectrum's, one per key and none on a key
/// the batch sets from its records and scales.
fn batch_axes(path: &Path, specs: &[String]) -> Result<Vec<Axis>, StudyError> {
    let mut axes: Vec<Axis> = Vec::new();
    for s in specs {
        let refused = |refusal| StudyError::Axis {
            scene: path.to_path_buf(),
            given: Some(s.clone()),
            refusal,
        };
        let a = Axis::parse(s).map_err(|e| {
            let why = e.strip_prefix("axis ").unwrap_or(&e).to_string();
            refused(AxisRefusal::Syntax { why })
        })?;
        if let Some(&(_, source)) = BATCH_KEYS.iter().find(|(k, _)| *k == a.key) {
            let key = a.key;
            return Err(refused(AxisRefusal::SetByBatch { key, source }));
        }
        if axes.iter().any(|b| b.key == a.key) {
            return Err(refused(AxisRefusal::Twice { key: a.key }));
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
    pub fn spectrum(base: Base, axis_specs: &[String]) -> Result<Plan, StudyError> {
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
            return Err(StudyError::Axis {
                scene: path,
                given: None,
                refusal: AxisRefusal::Twice { key: k.to_string() },
            });
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
    ) -> Result<Plan, StudyError> {
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
            return Err(StudyError::NoRecords {
                scene: path,
                table: "sweep",
            });
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
            ))
            .into());
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
            return Err(StudyError::Internal(Invariant::RecordKnobs));
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
    pub fn reference(&self) -> Result<Option<ReferencePlan>, StudyError> {
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
