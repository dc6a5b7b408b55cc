//! Why a figure could not be made: its file or a study it runs ([`StudyError`], which holds the
//! input errors), the drawing, or the writing of its files.

use std::fmt;
use std::path::PathBuf;

use rocking_scene::SceneError;
use rocking_study::StudyError;

/// Why a figure could not be made.
#[derive(Debug)]
pub enum FigureError {
    /// The figure file, a scene it names, or a run or sweep it needs.
    Study(StudyError),
    /// The drawing backend refused the figure `name` (its words).
    Draw {
        /// The directory the figure was to be written into.
        dir: PathBuf,
        /// The figure's name.
        name: String,
        /// The backend's message.
        detail: String,
    },
    /// A figure's file could not be written.
    Write {
        /// The file.
        path: PathBuf,
        /// Why.
        source: std::io::Error,
    },
}

impl FigureError {
    /// Whether the user can fix it by changing the input.
    pub fn is_input(&self) -> bool {
        matches!(self, FigureError::Study(e) if e.is_input())
    }
}

impl From<StudyError> for FigureError {
    fn from(e: StudyError) -> Self {
        FigureError::Study(e)
    }
}

impl From<SceneError> for FigureError {
    fn from(e: SceneError) -> Self {
        FigureError::Study(e.into())
    }
}

impl fmt::Display for FigureError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            FigureError::Study(e) => e.fmt(f),
            FigureError::Draw { dir, name, detail } => {
                write!(f, "{}: cannot draw {name}: {detail}", dir.display())
            }
            FigureError::Write { path, source } => {
                write!(f, "{}: cannot write: {source}", path.display())
            }
        }
    }
}

impl std::error::Error for FigureError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            FigureError::Study(e) => Some(e),
            FigureError::Write { source, .. } => Some(source),
            FigureError::Draw { .. } => None,
        }
    }
}
