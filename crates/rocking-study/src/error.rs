//! Why a study could not be done: the input's fault (the scene crate's [`SceneError`]), or a
//! run, a sweep or a fit that failed, each with its source. Callers decide what a kind means to
//! their user (the command's exit codes, Python's exceptions); the words here name no flag.

use std::fmt;
use std::path::PathBuf;

use rocking::SimError;
use rocking_scene::SceneError;
use rocking_spectra::{CellFailure, SweepError};

/// Why a study could not be done.
#[derive(Debug)]
pub enum StudyError {
    /// Invalid input: a scene, a record, an axis, a setting the user can fix.
    Input(SceneError),
    /// A run of `scene` failed though its input was valid.
    Simulation {
        /// The scene that ran.
        scene: PathBuf,
        /// The solver's error.
        source: SimError,
    },
    /// A run produced a non-finite output quantity: none of its results is written.
    NonFinite {
        /// The quantity (a field path).
        quantity: String,
        /// Its value or why it is not finite.
        detail: String,
    },
    /// A sweep's cell has no result: its class and the reason the sweep keeps.
    Cell(CellFailure),
    /// The sweep engine could not read or write its journal.
    Sweep(SweepError),
    /// No record was given, nor listed in the scene's `[table]`.
    NoRecords {
        /// The scene.
        scene: PathBuf,
        /// The table that may list them (`sweep`, `ida`).
        table: &'static str,
    },
    /// An axis a caller gave cannot be swept.
    Axis {
        /// The scene.
        scene: PathBuf,
        /// The axis as given, when one alone is refused.
        given: Option<String>,
        /// Why not.
        refusal: AxisRefusal,
    },
    /// A study's own invariant does not hold: a defect of the program, not of the input.
    Internal(Invariant),
    /// What a failure happened in (a record, an intensity level), before it.
    Context {
        /// Where, as the user reads it.
        what: String,
        /// The failure.
        source: Box<StudyError>,
    },
}

/// Why an axis a caller gave cannot be swept.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum AxisRefusal {
    /// It does not parse: the parser's words after "axis" (`` `SPEC`: why``).
    Syntax {
        /// Why.
        why: String,
    },
    /// A batch sets `key` itself from `source` (its records, its scale factors).
    SetByBatch {
        /// The key.
        key: String,
        /// Where the batch takes its values from.
        source: &'static str,
    },
    /// Another axis is on `key`.
    Twice {
        /// The key.
        key: String,
    },
}

/// An argument a caller gives a study: the command names it as a flag, Python as a parameter.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Argument {
    /// Record files or folders.
    Records,
    /// One axis of a sweep.
    Axis,
    /// A value `KEY=VALUE` set on top of the scene file.
    Set,
}

/// How a caller names its [`Argument`]s in messages (`--records FILE|DIR`, `records=[...]`).
pub type ArgumentNames = fn(Argument) -> &'static str;

/// The names this crate's own `Display` uses.
fn plain(a: Argument) -> &'static str {
    match a {
        Argument::Records => "record files",
        Argument::Axis => "axis",
        Argument::Set => "override",
    }
}

/// Invariants a study relies on; one failing is a defect to report.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Invariant {
    /// Every scene's record path and scale are knobs.
    RecordKnobs,
    /// A run on compliant ground records its ground columns.
    GroundColumns,
    /// The `[ida]` settings that passed the study's checks pass the hunt's.
    HuntSettings,
    /// A batch's plan carries its records.
    BatchRecords,
}

impl StudyError {
    /// Whether the user can fix it by changing the input (a scene, a record, an argument, an
    /// output directory that holds another study's journal).
    pub fn is_input(&self) -> bool {
        match self {
            StudyError::Input(_) | StudyError::NoRecords { .. } | StudyError::Axis { .. } => true,
            StudyError::Sweep(e) => {
                matches!(e, SweepError::Mismatch(_) | SweepError::NotJournal(..))
            }
            StudyError::Context { source, .. } => source.is_input(),
            _ => false,
        }
    }

    /// The same error with `what` it happened in before its message ("WHAT: MESSAGE"); an input
    /// error stays one, with its fields.
    pub fn context(self, what: impl fmt::Display) -> Self {
        match self {
            StudyError::Input(e) => StudyError::Input(e.context(what)),
            source => StudyError::Context {
                what: what.to_string(),
                source: Box::new(source),
            },
        }
    }
}

impl From<SceneError> for StudyError {
    fn from(e: SceneError) -> Self {
        StudyError::Input(e)
    }
}

impl From<SweepError> for StudyError {
    fn from(e: SweepError) -> Self {
        StudyError::Sweep(e)
    }
}

impl StudyError {
    /// The message, with the caller's names for its arguments.
    pub fn describe(&self, names: ArgumentNames) -> String {
        Described(self, names).to_string()
    }
}

impl fmt::Display for StudyError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        Described(self, plain).fmt(f)
    }
}

/// An error written with a caller's names for its arguments.
struct Described<'a>(&'a StudyError, ArgumentNames);

impl fmt::Display for Described<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let names = self.1;
        match self.0 {
            StudyError::NoRecords { scene, table } => write!(
                f,
                "{}: no records: give {} or `records = [...]` in [{table}] ({})",
                scene.display(),
                names(Argument::Records),
                rocking_motion::formats::FOLDER_RULE
            ),
            StudyError::Axis {
                scene,
                given,
                refusal,
            } => {
                let axis = names(Argument::Axis);
                write!(f, "{}: ", scene.display())?;
                if let AxisRefusal::Syntax { why } = refusal {
                    return write!(f, "{axis} {why}");
                }
                if let Some(given) = given {
                    write!(f, "{axis} `{given}`: ")?;
                }
                match refusal {
                    AxisRefusal::Syntax { .. } => Ok(()),
                    AxisRefusal::SetByBatch { key, source } => write!(
                        f,
                        "a batch sets `{key}` itself from {source}: give its values there (an \
                         axis may be any other numeric or text key of the scene)"
                    ),
                    AxisRefusal::Twice { key } => write!(
                        f,
                        "two axes on `{key}`: each key may have one axis (list its values in one \
                         {axis})"
                    ),
                }
            }
            StudyError::Context { what, source } => {
                write!(f, "{what}: {}", Described(source, names))
            }
            StudyError::Input(e) => f.write_str(&e.describe(names(Argument::Set))),
            StudyError::Simulation { scene, source } if source.is_guard() => {
                let d = rocking::Options::default();
                write!(
                    f,
                    "{}: simulation stopped: {source}; both limits are scene settings: \
                     `max_steps` and `max_events` in [solver] (defaults {} and {})",
                    scene.display(),
                    rocking_scene::limits::short(d.max_steps as f64),
                    rocking_scene::limits::short(d.max_events as f64)
                )
            }
            StudyError::Simulation { scene, source } => {
                write!(f, "{}: simulation failed: {source}", scene.display())
            }
            StudyError::NonFinite { quantity, detail } => write!(
                f,
                "the run produced a non-finite {quantity} ({detail}); no results written"
            ),
            StudyError::Cell(c) => f.write_str(&c.message),
            StudyError::Sweep(e) => e.fmt(f),
            StudyError::Internal(Invariant::RecordKnobs) => {
                f.write_str("record path and scale are not knobs")
            }
            StudyError::Internal(Invariant::GroundColumns) => {
                f.write_str("a run on compliant ground without its ground columns")
            }
            StudyError::Internal(Invariant::BatchRecords) => {
                f.write_str("a batch plan without records")
            }
            StudyError::Internal(Invariant::HuntSettings) => {
                f.write_str("the [ida] settings passed their checks but the hunt refused them")
            }
        }
    }
}

impl std::error::Error for StudyError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            StudyError::Input(e) => Some(e),
            StudyError::Simulation { source, .. } => Some(source),
            StudyError::Sweep(e) => Some(e),
            StudyError::Context { source, .. } => Some(source.as_ref()),
            _ => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A failure keeps its kind through the context a caller adds, and an input error its
    /// fields; the kind decides the exit code and the Python exception.
    #[test]
    fn context_keeps_the_kind_and_the_fields() {
        let input =
            SceneError::input("s.toml:3:1: `alpha` = 2 is not allowed").with_value(2, "0 < alpha");
        let e = StudyError::from(input).context("record A.AT2");
        assert!(e.is_input());
        let fields = match &e {
            StudyError::Input(s) => s.fields(),
            other => panic!("an input error, not {other:?}"),
        };
        assert_eq!(fields.value.as_deref(), Some("2"));
        assert_eq!(
            e.to_string(),
            "record A.AT2: s.toml:3:1: `alpha` = 2 is not allowed"
        );

        let guard = SimError::TooManySteps {
            max_steps: 50,
            tau: 1.0,
        };
        let e = StudyError::Simulation {
            scene: PathBuf::from("s.toml"),
            source: guard,
        }
        .context("the analysis at PGA = 1 m/s²");
        assert!(!e.is_input());
        assert!(matches!(&e, StudyError::Context { source, .. }
            if matches!(**source, StudyError::Simulation { .. })));
        let text = e.to_string();
        assert!(
            text.starts_with("the analysis at PGA = 1 m/s²: s.toml: simulation stopped: "),
            "{text}"
        );
        assert!(
            text.contains("`max_steps` and `max_events` in [solver]"),
            "{text}"
        );
        assert!(std::error::Error::source(&e).is_some());
    }

    /// An output directory holding another sweep's journal is the user's to fix; a journal that
    /// cannot be written is not.
    #[test]
    fn a_foreign_journal_is_input_and_a_failed_write_is_not() {
        let foreign = StudyError::from(SweepError::Mismatch(PathBuf::from("out")));
        assert!(foreign.is_input());
        let io = std::io::Error::new(std::io::ErrorKind::PermissionDenied, "denied");
        let failed = StudyError::from(SweepError::Io(PathBuf::from("out/j"), io));
        assert!(!failed.is_input());
    }
}
