//! `rocking.figure`: a figure file drawn as `rocking figure` draws it
//! ([`rocking_plot::figure_file`]), returned as bytes instead of written into a folder.

use std::path::PathBuf;

use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict};
use rocking_plot::figure_file::{self, Loader};

use rocking_plot::FigureError;

use crate::error::py_err;

/// The figure of the figure file `path`: `{extension: bytes}` for "svg", "png", "pdf" and (at
/// print size, not a `draft`) "caption.md", byte for byte what `rocking figure` writes. Sweeps
/// are journaled in `cache` (as the command's `--cache`), `cells` caps each ranged axis (`--cells`).
#[pyfunction]
#[pyo3(signature = (path, cache, cells = None, draft = false, quiet = true))]
pub fn figure<'py>(
    py: Python<'py>,
    path: PathBuf,
    cache: PathBuf,
    cells: Option<usize>,
    draft: bool,
    quiet: bool,
) -> PyResult<Bound<'py, PyDict>> {
    let files = py
        .detach(|| {
            let spec = figure_file::read(&path)?;
            let mut loader = Loader::new(&cache, quiet);
            let figure = figure_file::draw(&path, &spec, &mut loader, cells, draft)?;
            figure.files().map_err(|detail| FigureError::Draw {
                dir: path.clone(),
                name: "the figure".to_string(),
                detail,
            })
        })
        .map_err(py_err)?;
    let out = PyDict::new(py);
    for (ext, bytes) in files {
        out.set_item(ext, PyBytes::new(py, &bytes))?;
    }
    Ok(out)
}
