//! One shard of a sweep: `rocking spectrum|batch --shard K/N` runs the cells of shard K into
//! its own directory, with its journal and `shard.json` (the study's description, enough to
//! plan the whole study again at the merge).

use std::path::Path;

use rocking_scene::SceneError;
use rocking_spectra::{Progress, Shard};
use rocking_study::plan::{program_digest, Plan};
use serde::{Deserialize, Serialize};

use crate::error::CliError;
use crate::out_dir::write_atomic;

/// `--shard K/N` as the command reads it (clap's value parser): the library's check, the flag
/// named in the message.
pub fn parse_flag(text: &str) -> Result<Shard, String> {
    Shard::parse(text).map_err(|e| format!("--shard `{}`: {}", e.text, e.problem))
}

/// The kind of study a shard belongs to.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Kind {
    /// `rocking spectrum`.
    Spectrum,
    /// `rocking batch`.
    Batch,
}

/// `shard.json`: what a shard ran, enough to plan the whole study again at the merge.
#[derive(Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Manifest {
    pub kind: Kind,
    pub shard: String,
    pub program: String,
    pub fingerprint: String,
    pub scene: String,
    pub directory: String,
    pub scene_text: String,
    pub set: Vec<String>,
    /// `key=v1,v2,...`, each value printed to read back as the same f64 (a JSON number need
    /// not: serde_json's default parser is not correctly rounded); a text axis's texts. For a
    /// batch, its own axes (`--axis`), after which its records and scales vary slowest.
    pub axes: Vec<String>,
    pub records: Vec<String>,
    /// The same for the scale factors.
    pub scales: Vec<String>,
}

/// A value as text that reads back as the same f64.
fn exact(v: &f64) -> String {
    format!("{v:?}")
}

pub const MANIFEST: &str = "shard.json";

pub fn io(path: &Path, what: &'static str, e: std::io::Error) -> CliError {
    CliError::io(what, path, e)
}

/// Runs (or resumes) shard `shard` of `plan` into `dir`: `shard.json` first (so that a shard
/// killed before its first cell is still named by the merge), then the shard's cells, journaled;
/// a `dir` holding another shard's or study's journal is refused before anything is written.
/// A failed cell is a result here; the merge reports it (exit status 1).
pub fn run_shard(
    plan: &Plan,
    kind: Kind,
    shard: Shard,
    dir: &Path,
    progress: Progress,
    pool: &rayon::ThreadPool,
) -> Result<(), CliError> {
    let base = &plan.base;
    let cwd = std::env::current_dir().map_err(|e| io(Path::new("."), "read", e))?;
    let (records, scales) = match &plan.records {
        Some(r) => (r.paths.clone(), r.scales.iter().map(exact).collect()),
        None => (Vec::new(), Vec::new()),
    };
    let manifest = Manifest {
        kind,
        shard: shard.to_string(),
        program: program_digest().to_string(),
        fingerprint: plan.sweep.fingerprint.clone(),
        scene: base.path().display().to_string(),
        directory: cwd.display().to_string(),
        scene_text: base.text().to_string(),
        set: base.sets().to_vec(),
        // A batch's own axes follow its record and scale axes (none: an empty list, as before).
        axes: match kind {
            Kind::Spectrum => &plan.sweep.axes[..],
            Kind::Batch => &plan.sweep.axes[2..],
        }
        .iter()
        .map(rocking_spectra::Axis::spec)
        .collect(),
        records,
        scales,
    };
    // A directory of another study or shard is refused before shard.json is touched: a refused
    // run changes nothing (a finished shard stays mergeable).
    rocking_spectra::shard::check_dir(&plan.sweep, shard, dir).map_err(CliError::from)?;
    std::fs::create_dir_all(dir).map_err(|e| io(dir, "create", e))?;
    let text = serde_json::to_string_pretty(&manifest).map_err(|source| CliError::Json {
        name: MANIFEST,
        source,
    })?;
    write_atomic(&dir.join(MANIFEST), (text + "\n").as_bytes())?;
    let outcome = pool
        .install(|| {
            rocking_spectra::run_shard(&plan.sweep, shard, dir, progress, |v| plan.run_cell(v))
        })
        .map_err(CliError::from)?;
    out!(
        "{}: shard {shard}: {} of {} cells ({} computed now, {} resumed, {} failed) in {:.2} s on {} threads",
        base.path().display(),
        outcome.cells.len(),
        plan.sweep.len(),
        outcome.computed,
        outcome.cells.len() - outcome.computed,
        outcome.failures.len(),
        outcome.elapsed.as_secs_f64(),
        pool.current_num_threads()
    );
    out!(
        "  wrote {} (join the {} shards with `rocking merge OUT SHARD_DIR...`)",
        dir.display(),
        shard.n
    );
    Ok(())
}

/// `shard.json` of the shard directory `dir`, as JSON and as read.
pub fn read_manifest(dir: &Path) -> Result<(serde_json::Value, Manifest), CliError> {
    let path = dir.join(MANIFEST);
    let text = std::fs::read_to_string(&path).map_err(|e| {
        SceneError::input(format!(
            "{}: not a shard directory: cannot read {MANIFEST} ({e}); give the --out directories \
             of `rocking spectrum|batch --shard K/N`",
            dir.display()
        ))
    })?;
    let bad = |e: serde_json::Error| {
        SceneError::input(format!(
            "{}: not a shard description of this program: {e}",
            path.display()
        ))
    };
    let value: serde_json::Value = serde_json::from_str(&text).map_err(bad)?;
    let manifest = serde_json::from_value(value.clone()).map_err(bad)?;
    Ok((value, manifest))
}
