//! `rocking convergence`: a scene run with each model of a list, and per quantity where its
//! value stops changing (rocking-study's `convergence`); writes convergence.csv and
//! convergence.json, prints the table.

use std::path::{Path, PathBuf};

use rocking_scene::SceneError;
use rocking_study::convergence;

use crate::out_dir::{sweep_error, write_atomic};
use crate::sweep::{failed_runs, out_dir, threads_pool};

/// What the command was asked.
pub struct Args<'a> {
    pub scene: &'a Path,
    pub sets: &'a [String],
    pub models: &'a [String],
    pub quantities: &'a [String],
    pub tolerance: f64,
    pub out: Option<PathBuf>,
    pub threads: Option<usize>,
}

pub fn convergence(a: Args) -> Result<(), SceneError> {
    let text = rocking_scene::scene::read(a.scene)?;
    let study = convergence::plan(a.scene, text, a.sets, a.models, a.quantities, a.tolerance)?;
    let dir = out_dir(a.scene, a.out, "convergence");
    crate::out_dir::refuse_a_file(&dir)?;
    let pool = threads_pool(a.threads)?;
    let outcome = pool
        .install(|| rocking_spectra::run_in_memory(&study.plan.sweep, |v| study.plan.run_cell(v)))
        .map_err(sweep_error)?;
    let report = study.report(&outcome);
    std::fs::create_dir_all(&dir).map_err(|e| {
        SceneError::failure(format!(
            "{}: cannot create the directory: {e}",
            dir.display()
        ))
    })?;
    let csv = dir.join("convergence.csv");
    write_atomic(&csv, report.csv().as_bytes())?;
    let json = dir.join("convergence.json");
    let text = serde_json::to_string_pretty(&report.json()).unwrap_or_default() + "\n";
    write_atomic(&json, text.as_bytes())?;
    out!("{}", a.scene.display());
    out!("{}", report.text().trim_end());
    out!("  wrote:");
    out!("    {}", csv.display());
    out!("    {}", json.display());
    failed_runs(&outcome, "models", "convergence.csv")
}
