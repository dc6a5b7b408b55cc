//! The library's errors as Python exceptions, a small hierarchy: invalid input is a
//! `ValueError` (it names the file and the key, as the command's message does), a run that failed
//! though its input was valid is `rocking.SimulationError` (a `RuntimeError`), a file that could
//! not be read or written is an `OSError`, and anything else (a defect) a `RuntimeError`.

use pyo3::create_exception;
use pyo3::exceptions::{PyOSError, PyRuntimeError, PyValueError};
use pyo3::PyErr;
use rocking_plot::FigureError;
use rocking_scene::SceneError;
use rocking_spectra::SweepError;
use rocking_study::{Argument, StudyError};

create_exception!(
    rocking,
    SimulationError,
    PyRuntimeError,
    "A run failed though its input was valid: the integrator, a guard (`max_steps`, \
     `max_events` in [solver]) or a non-finite result. The message names the scene."
);

/// An error of the library crates, as the Python exception of its kind.
pub(crate) trait ToPyErr {
    fn to_py_err(self) -> PyErr;
}

/// `e` as its Python exception (for `map_err`).
pub(crate) fn py_err(e: impl ToPyErr) -> PyErr {
    e.to_py_err()
}

impl ToPyErr for SceneError {
    fn to_py_err(self) -> PyErr {
        PyValueError::new_err(self.describe(parameter(Argument::Set)))
    }
}

/// A study's arguments as this package's parameters.
fn parameter(a: Argument) -> &'static str {
    match a {
        Argument::Records => "records=[FILE|DIR, ...]",
        Argument::Axis => "axes entry",
        Argument::Set => "set entry",
    }
}

impl ToPyErr for StudyError {
    fn to_py_err(self) -> PyErr {
        let message = self.describe(parameter);
        if self.is_input() {
            return PyValueError::new_err(message);
        }
        match kind(&self) {
            Kind::Simulation => SimulationError::new_err(message),
            Kind::Io => PyOSError::new_err(message),
            Kind::Other => PyRuntimeError::new_err(message),
        }
    }
}

impl ToPyErr for FigureError {
    fn to_py_err(self) -> PyErr {
        match self {
            FigureError::Study(e) => e.to_py_err(),
            e @ FigureError::Write { .. } => PyOSError::new_err(e.to_string()),
            e @ FigureError::Draw { .. } => PyRuntimeError::new_err(e.to_string()),
        }
    }
}

enum Kind {
    Simulation,
    Io,
    Other,
}

/// What a study's failure (not its input) is to a Python caller.
fn kind(e: &StudyError) -> Kind {
    match e {
        StudyError::Simulation { .. } | StudyError::NonFinite { .. } | StudyError::Cell(_) => {
            Kind::Simulation
        }
        StudyError::Sweep(SweepError::Io(..)) => Kind::Io,
        StudyError::Context { source, .. } => kind(source),
        _ => Kind::Other,
    }
}
