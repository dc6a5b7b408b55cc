//! Why a command stopped, and its exit code: 2 when the user can fix the input (a scene, a
//! record, an argument, an output directory holding something else), 1 for a failure that is not
//! the input's fault. The libraries' errors carry the data; the words about this command's flags
//! are added here.

use std::fmt;
use std::path::PathBuf;

use rocking_plot::FigureError;
use rocking_scene::SceneError;
use rocking_spectra::SweepError;
use rocking_study::{Argument, StudyError};

/// Why a command stopped.
#[derive(Debug)]
pub enum CliError {
    /// A study (a run, a sweep, an IDA) or its input.
    Study(StudyError),
    /// A figure: its file, the studies it runs, the drawing or the writing.
    Figure(FigureError),
    /// A file or directory could not be read, written, created or replaced.
    Io {
        /// The file or directory, as the user named it.
        path: PathBuf,
        /// What could not be done ("write", "create the directory", ...).
        action: &'static str,
        /// Why.
        source: std::io::Error,
    },
    /// Standard output could not be written (closed or full).
    Stdout(std::io::Error),
    /// The worker threads could not start.
    ThreadPool(rayon::ThreadPoolBuildError),
    /// A table could not be written.
    Table {
        /// Its file name.
        name: &'static str,
        /// Why.
        source: csv::Error,
    },
    /// A JSON file could not be serialised.
    Json {
        /// Its file name.
        name: &'static str,
        /// Why.
        source: serde_json::Error,
    },
    /// The animation of a run could not be drawn.
    Animation {
        /// The file it was to be.
        path: PathBuf,
        /// The drawing's words.
        detail: String,
    },
    /// Some cells of a sweep have no result: everything else is written, those cells marked.
    FailedCells {
        /// How many failed.
        failed: usize,
        /// Of how many.
        total: usize,
        /// What a cell is ("runs", "cells").
        what: &'static str,
        /// The table that marks them.
        table: &'static str,
        /// The first failure's message.
        first: String,
    },
}

impl CliError {
    /// A failed read or write of `path`.
    pub fn io(action: &'static str, path: impl Into<PathBuf>, source: std::io::Error) -> Self {
        CliError::Io {
            path: path.into(),
            action,
            source,
        }
    }

    /// The process exit code: 2 for input the user can fix, 1 else.
    pub fn exit_code(&self) -> u8 {
        let input = match self {
            CliError::Study(e) => e.is_input(),
            CliError::Figure(e) => e.is_input(),
            _ => false,
        };
        if input {
            2
        } else {
            1
        }
    }
}

/// A study's arguments as this command's flags.
fn flag(a: Argument) -> &'static str {
    match a {
        Argument::Records => "--records FILE|DIR",
        Argument::Axis => "--axis",
        Argument::Set => "--set",
    }
}

/// A sweep engine's error in the command's words: a directory holding another sweep or no
/// journal gets the advice about `--out` (the engine names no flag).
pub fn sweep_message(e: &SweepError) -> String {
    match e {
        SweepError::Mismatch(_) => format!("{e}; use another --out directory or delete it"),
        SweepError::NotJournal(..) => format!("{e}; delete it or use another --out directory"),
        SweepError::Io(..) => e.to_string(),
    }
}

impl From<StudyError> for CliError {
    fn from(e: StudyError) -> Self {
        CliError::Study(e)
    }
}

impl From<SceneError> for CliError {
    fn from(e: SceneError) -> Self {
        CliError::Study(e.into())
    }
}

impl From<SweepError> for CliError {
    fn from(e: SweepError) -> Self {
        CliError::Study(e.into())
    }
}

impl From<FigureError> for CliError {
    fn from(e: FigureError) -> Self {
        match e {
            FigureError::Study(e) => CliError::Study(e),
            e => CliError::Figure(e),
        }
    }
}

impl fmt::Display for CliError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            CliError::Study(StudyError::Sweep(e)) => f.write_str(&sweep_message(e)),
            CliError::Study(e) => f.write_str(&e.describe(flag)),
            CliError::Figure(e) => e.fmt(f),
            CliError::Io {
                path,
                action,
                source,
            } => write!(f, "{}: cannot {action}: {source}", path.display()),
            CliError::Stdout(e) => write!(f, "cannot write to standard output: {e}"),
            CliError::ThreadPool(e) => write!(f, "cannot start the thread pool: {e}"),
            CliError::Table { name, source } => write!(f, "cannot write {name}: {source}"),
            CliError::Json { name, source } => write!(f, "cannot write {name}: {source}"),
            CliError::Animation { path, detail } => {
                write!(f, "{}: cannot draw the animation: {detail}", path.display())
            }
            CliError::FailedCells {
                failed,
                total,
                what,
                table,
                first,
            } => write!(
                f,
                "{failed} of {total} {what} failed (marked `failed` in {table}, messages in \
                 meta.json); first: {first}"
            ),
        }
    }
}

impl std::error::Error for CliError {}
