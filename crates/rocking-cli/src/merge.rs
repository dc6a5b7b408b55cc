//! `rocking merge OUT SHARD_DIR...` joins the shards of a study (see [`crate::shard`]) into the
//! outputs of the whole study, byte for byte those of a run on one machine: the study is planned
//! again from `shard.json` (the scene text as the shards read it, the overrides, axes, records
//! and scales) and the outputs are written by the same functions as `rocking spectrum` and
//! `rocking batch`.

use std::path::{Path, PathBuf};

use rocking_scene::SceneError;
use rocking_spectra::shard::MergeError;
use rocking_spectra::{Outcome, Shard, SweepError};
use rocking_study::plan::{program_digest, Base, Plan};

use crate::error::{sweep_message, CliError};
use crate::out_dir::{OutDir, MERGE_OUT};
use crate::shard::{io, read_manifest, Kind, Manifest, MANIFEST};
use crate::sweep;

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
            .map_err(|e| SceneError::input(format!("{}: {MANIFEST}: {e}", dir.display())))?;
        shards.push((dir.clone(), shard));
        match &first {
            None => first = Some((dir, value, manifest)),
            Some((d0, v0, _)) => {
                if let Some((_, what)) = SAME.iter().find(|(k, _)| value[k] != v0[k]) {
                    return Err(SceneError::input(format!(
                        "{}: a shard of another study than {}: {what} differ",
                        dir.display(),
                        d0.display()
                    ))
                    .into());
                }
            }
        }
    }
    let Some((dir0, _, m)) = first else {
        return Err(SceneError::input("rocking merge: no shard directory given").into());
    };
    if m.program != program_digest() {
        return Err(SceneError::input(format!(
            "{}: the shards were run by another build of rocking ({}) than this one ({}); merge \
             with the program that ran them",
            dir0.display(),
            m.program,
            program_digest()
        ))
        .into());
    }
    let scene = PathBuf::from(&m.scene);
    let cwd = std::env::current_dir().map_err(|e| io(Path::new("."), "read", e))?;
    if scene.is_relative() && Path::new(&m.directory) != cwd {
        return Err(SceneError::input(format!(
            "{}: the scene path `{}` is relative to {}, where the shards ran: run the merge there",
            dir0.display(),
            m.scene,
            m.directory
        ))
        .into());
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
                    SceneError::input(format!("{}: {MANIFEST}: scales: {e}", dir0.display()))
                })?;
            Plan::batch(base, &records, &scales, &m.axes)?
        }
    };
    if plan.sweep.fingerprint != m.fingerprint {
        return Err(SceneError::input(format!(
            "{}: the scene's record contents changed since the shards ran (the study's \
             fingerprint is {}, the shards' {}): run the shards again",
            dir0.display(),
            plan.sweep.fingerprint,
            m.fingerprint
        ))
        .into());
    }
    let outcome = rocking_spectra::shard::merge(&plan.sweep, &shards).map_err(|e| match e {
        MergeError::Journal(e @ (SweepError::Mismatch(_) | SweepError::NotJournal(..))) => {
            SceneError::input(format!(
                "{} (the journal does not belong to the shard its {MANIFEST} describes)",
                sweep_message(&e)
            ))
        }
        e => SceneError::input(e.to_string()),
    })?;
    let staged = OutDir::begin(out, MERGE_OUT)?;
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
