//! Sharded sweeps: `rocking spectrum|batch --shard K/N` runs one shard of a study into its own
//! directory (its journal and `shard.json`, the study's description), and `rocking merge OUT
//! SHARD_DIR...` joins the shards into the outputs of the whole study, byte for byte those of a
//! run on one machine: the study is planned again from `shard.json` (the scene text as the
//! shards read it, the overrides, axes, records and scales) and the outputs are written by the
//! same functions as `rocking spectrum` and `rocking batch`.

use std::path::{Path, PathBuf};

use rocking_spectra::plan::{program_digest, Base, Plan};
use rocking_spectra::shard::MergeError;
use rocking_spectra::{Outcome, Progress, Shard, SweepError};
use serde::{Deserialize, Serialize};

use crate::report::{write_atomic, OutDir, OutKind};
use crate::scene::CliError;
use crate::sweep;

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
struct Manifest {
    kind: Kind,
    shard: String,
    program: String,
    fingerprint: String,
    scene: String,
    directory: String,
    scene_text: String,
    set: Vec<String>,
    /// `key=v1,v2,...`, each value printed to read back as the same f64 (a JSON number need
    /// not: serde_json's default parser is not correctly rounded).
    axes: Vec<String>,
    records: Vec<String>,
    /// The same for the scale factors.
    scales: Vec<String>,
}

/// A value as text that reads back as the same f64.
fn exact(v: &f64) -> String {
    format!("{v:?}")
}

const MANIFEST: &str = "shard.json";

/// The fields of `shard.json` that must agree between the shards of one study, with what they
/// mean (for the message naming a shard of another study).
const SAME: [(&str, &str); 10] = [
    ("kind", "the command (spectrum or batch)"),
    ("program", "the program build"),
    ("scene", "the scene path"),
    ("directory", "the working directory"),
    ("scene_text", "the scene text"),
    ("set", "the --set overrides"),
    ("axes", "the axes"),
    ("records", "the records"),
    ("scales", "the scale factors"),
    ("fingerprint", "the record contents"),
];

fn io(path: &Path, what: &str, e: impl std::fmt::Display) -> CliError {
    CliError::Internal(format!("{}: cannot {what}: {e}", path.display()))
}

/// Runs (or resumes) shard `shard` of `plan` into `dir`: `shard.json` first (so that a shard
/// killed before its first cell is still named by the merge), then the shard's cells, journaled.
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
        axes: match kind {
            Kind::Spectrum => plan
                .sweep
                .axes
                .iter()
                .map(|a| {
                    let v: Vec<String> = a.values.iter().map(exact).collect();
                    format!("{}={}", a.key, v.join(","))
                })
                .collect(),
            Kind::Batch => Vec::new(),
        },
        records,
        scales,
    };
    std::fs::create_dir_all(dir).map_err(|e| io(dir, "create", e))?;
    let text = serde_json::to_string_pretty(&manifest)
        .map_err(|e| CliError::Internal(format!("cannot serialise {MANIFEST}: {e}")))?;
    write_atomic(&dir.join(MANIFEST), (text + "\n").as_bytes())?;
    let outcome = pool
        .install(|| {
            rocking_spectra::run_shard(&plan.sweep, shard, dir, progress, |v| {
                plan.run_cell(v).map_err(|e| e.to_string())
            })
        })
        .map_err(sweep::sweep_error)?;
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

fn read_manifest(dir: &Path) -> Result<(serde_json::Value, Manifest), CliError> {
    let path = dir.join(MANIFEST);
    let text = std::fs::read_to_string(&path).map_err(|e| {
        CliError::Input(format!(
            "{}: not a shard directory: cannot read {MANIFEST} ({e}); give the --out directories \
             of `rocking spectrum|batch --shard K/N`",
            dir.display()
        ))
    })?;
    let bad = |e: serde_json::Error| {
        CliError::Input(format!(
            "{}: not a shard description of this program: {e}",
            path.display()
        ))
    };
    let value: serde_json::Value = serde_json::from_str(&text).map_err(bad)?;
    let manifest = serde_json::from_value(value.clone()).map_err(bad)?;
    Ok((value, manifest))
}

/// Which files a merge writes into OUT (the outputs of a spectrum or of a record suite).
fn merge_writes(name: &str) -> bool {
    [
        "cells.csv",
        "meta.json",
        "runs.csv",
        "fragility.csv",
        "fragility.png",
        "fragility.svg",
    ]
    .contains(&name)
        || (name.starts_with("spectrum") && (name.ends_with(".png") || name.ends_with(".svg")))
}

/// `rocking merge OUT SHARD_DIR...`: the outputs of the whole study from all its shards. Shards
/// of another study, a duplicate, a missing shard or a shard that lacks cells are refused with
/// exit status 2 and nothing is written; failed cells are reported as by an unsharded run
/// (exit status 1, their messages in meta.json).
pub fn merge(out: &Path, dirs: &[PathBuf]) -> Result<(), CliError> {
    let mut shards = Vec::new();
    let mut first: Option<(&Path, serde_json::Value, Manifest)> = None;
    for dir in dirs {
        let (value, manifest) = read_manifest(dir)?;
        let shard = Shard::parse(&manifest.shard)
            .map_err(|e| CliError::Input(format!("{}: {MANIFEST}: {e}", dir.display())))?;
        shards.push((dir.clone(), shard));
        match &first {
            None => first = Some((dir, value, manifest)),
            Some((d0, v0, _)) => {
                if let Some((_, what)) = SAME.iter().find(|(k, _)| value[k] != v0[k]) {
                    return Err(CliError::Input(format!(
                        "{}: a shard of another study than {}: {what} differ",
                        dir.display(),
                        d0.display()
                    )));
                }
            }
        }
    }
    let Some((dir0, _, m)) = first else {
        return Err(CliError::Input(
            "rocking merge: no shard directory given".into(),
        ));
    };
    if m.program != program_digest() {
        return Err(CliError::Input(format!(
            "{}: the shards were run by another build of rocking ({}) than this one ({}); merge \
             with the program that ran them",
            dir0.display(),
            m.program,
            program_digest()
        )));
    }
    let scene = PathBuf::from(&m.scene);
    let cwd = std::env::current_dir().map_err(|e| io(Path::new("."), "read", e))?;
    if scene.is_relative() && Path::new(&m.directory) != cwd {
        return Err(CliError::Input(format!(
            "{}: the scene path `{}` is relative to {}, where the shards ran: run the merge there",
            dir0.display(),
            m.scene,
            m.directory
        )));
    }
    // The study planned again as the shards planned it: the same cells, the same fingerprint
    // (unless a record's contents changed since), and outputs from the same writers.
    let base = Base::from_text(&scene, m.scene_text.clone(), &m.set)?;
    let plan = match m.kind {
        Kind::Spectrum => Plan::spectrum(base, &m.axes)?,
        Kind::Batch => {
            let records: Vec<PathBuf> = m.records.iter().map(PathBuf::from).collect();
            let scales = m
                .scales
                .iter()
                .map(|s| s.parse::<f64>())
                .collect::<Result<Vec<_>, _>>()
                .map_err(|e| {
                    CliError::Input(format!("{}: {MANIFEST}: scales: {e}", dir0.display()))
                })?;
            Plan::batch(base, &records, &scales)?
        }
    };
    if plan.sweep.fingerprint != m.fingerprint {
        return Err(CliError::Input(format!(
            "{}: the scene's record contents changed since the shards ran (the study's \
             fingerprint is {}, the shards' {}): run the shards again",
            dir0.display(),
            plan.sweep.fingerprint,
            m.fingerprint
        )));
    }
    let outcome = rocking_spectra::shard::merge(&plan.sweep, &shards).map_err(|e| match e {
        MergeError::Shards(_) => CliError::Input(e.to_string()),
        MergeError::Journal(e @ (SweepError::Mismatch(_) | SweepError::NotJournal(..))) => {
            CliError::Input(format!(
                "{e} (the journal does not belong to the shard its {MANIFEST} describes)"
            ))
        }
        MergeError::Journal(e) => CliError::Input(e.to_string()),
    })?;
    let staged = OutDir::begin_for(
        out,
        OutKind {
            writes: merge_writes,
            command: "rocking merge",
        },
    )?;
    let written = write(&plan, m.kind, &outcome, staged.path())?;
    let written: Vec<PathBuf> = written.iter().map(|p| staged.final_path(p)).collect();
    staged.commit()?;
    out!(
        "merged {} shards: {} cells ({} failed)",
        shards.len(),
        outcome.cells.len(),
        outcome.failures.len()
    );
    out!("  wrote:");
    for p in written {
        out!("    {}", p.display());
    }
    match m.kind {
        Kind::Spectrum => sweep::failed_runs(&outcome, "cells", "cells.csv"),
        Kind::Batch => sweep::failed_runs(&outcome, "runs", "runs.csv"),
    }
}

fn write(plan: &Plan, kind: Kind, outcome: &Outcome, dir: &Path) -> Result<Vec<PathBuf>, CliError> {
    match kind {
        Kind::Spectrum => sweep::write_outputs(plan, outcome, dir),
        Kind::Batch => sweep::write_batch_outputs(plan, outcome, dir).map(|(w, _)| w),
    }
}
