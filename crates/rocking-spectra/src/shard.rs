//! Shards: a deterministic share of a sweep's cells, for one task of a cluster job array.
//!
//! Shard `K/N` owns the cells whose index is `K` modulo `N` (interleaved, so neighbouring cells
//! of a spectrum, which cost alike, spread over all shards and the shards balance). A shard runs
//! like a whole sweep, with its own resumable journal whose header names the shard, so a shard
//! directory is never resumed as another shard or as the whole sweep. [`merge`] reads the
//! journals of all N shards back into the [`Outcome`] of the whole sweep, refusing a duplicate
//! or missing shard and a journal that lacks any of its cells (never a partial result).

use std::collections::BTreeMap;
use std::fmt;
use std::path::{Path, PathBuf};
use std::time::Duration;

use crate::{read_journal, split_notes, Outcome, Sweep, SweepError, JOURNAL};

/// The most shards a sweep may be split into (far more than a job array has tasks).
pub const MAX_SHARDS: usize = 100_000;

/// Shard `k` of `n`: the cells whose index is `k` modulo `n`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Shard {
    /// This shard's number, 0 ≤ k < n.
    pub k: usize,
    /// The number of shards, 1 ≤ n ≤ [`MAX_SHARDS`].
    pub n: usize,
}

impl Shard {
    /// `K/N` with 0 ≤ K < N ≤ [`MAX_SHARDS`].
    pub fn parse(text: &str) -> Result<Shard, String> {
        let bad = |why: String| format!("--shard `{text}`: {why}");
        let (k, n) = text
            .split_once('/')
            .ok_or_else(|| bad("expected K/N, e.g. 0/4 (shard K of N, counted from 0)".into()))?;
        let int = |s: &str, name: &str| {
            s.trim()
                .parse::<usize>()
                .map_err(|_| bad(format!("{name} `{s}` is not a whole number ≥ 0")))
        };
        let (k, n) = (int(k, "K")?, int(n, "N")?);
        if !(1..=MAX_SHARDS).contains(&n) {
            return Err(bad(format!("N = {n} is not allowed: 1 ≤ N ≤ {MAX_SHARDS}")));
        }
        if k >= n {
            return Err(bad(format!("K = {k} is not allowed: 0 ≤ K < N = {n}")));
        }
        Ok(Shard { k, n })
    }

    /// Whether this shard runs cell `index`.
    pub fn owns(&self, index: usize) -> bool {
        index % self.n == self.k
    }

    /// The shard of `n` that runs cell `index`.
    pub fn owner(index: usize, n: usize) -> Shard {
        Shard { k: index % n, n }
    }

    /// The number of this shard's cells in a sweep of `len` cells.
    pub fn len(&self, len: usize) -> usize {
        len / self.n + usize::from(len % self.n > self.k)
    }

    /// Whether this shard has no cell in a sweep of `len` cells.
    pub fn is_empty(&self, len: usize) -> bool {
        self.len(len) == 0
    }

    /// The journal header of this shard of `sweep`.
    pub(crate) fn header(&self, sweep: &Sweep) -> String {
        format!("# rocking sweep {} shard {self}\n", sweep.fingerprint)
    }
}

impl fmt::Display for Shard {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}/{}", self.k, self.n)
    }
}

/// Whether `dir` may run (or resume) shard `shard` of `sweep`: it holds no journal, an empty
/// one, or this shard's. [`crate::run_shard`] starts with the same check; a caller that writes
/// anything beside the journal (a description of the shard) checks first, so that a refused run
/// changes nothing.
pub fn check_dir(sweep: &Sweep, shard: Shard, dir: &Path) -> Result<(), SweepError> {
    read_journal(&dir.join(JOURNAL), &shard.header(sweep), sweep.len()).map(|_| ())
}

/// Why shards cannot be merged.
#[derive(Debug)]
pub enum MergeError {
    /// A shard's journal could not be read, or belongs to another sweep or shard.
    Journal(SweepError),
    /// The set of shards is not one whole sweep (wrong count, duplicate, missing, incomplete).
    Shards(String),
}

impl fmt::Display for MergeError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            MergeError::Journal(e) => e.fmt(f),
            MergeError::Shards(m) => f.write_str(m),
        }
    }
}

impl std::error::Error for MergeError {}

/// The most missing cells listed per shard in an error (the count is always given).
const LISTED: usize = 10;

/// Reads the journals of the shards in `dirs` (each with the shard it ran) into the outcome of
/// the whole `sweep`, as if it had run on one machine: every shard of one `N` exactly once, and
/// every cell journaled by the shard that owns it. Missing cells are listed with their owner.
pub fn merge(sweep: &Sweep, dirs: &[(PathBuf, Shard)]) -> Result<Outcome, MergeError> {
    let Some(&(ref first_dir, first)) = dirs.first() else {
        return Err(MergeError::Shards("no shard directory given".into()));
    };
    let n = first.n;
    let mut by_k: BTreeMap<usize, &Path> = BTreeMap::new();
    for (dir, s) in dirs {
        if s.n != n {
            return Err(MergeError::Shards(format!(
                "{}: shard {s} is of a split into {} shards, but {} is shard {first} of {n}",
                dir.display(),
                s.n,
                first_dir.display()
            )));
        }
        if let Some(other) = by_k.insert(s.k, dir) {
            return Err(MergeError::Shards(format!(
                "{}: shard {s} is given twice (also {})",
                dir.display(),
                other.display()
            )));
        }
    }
    let len = sweep.len();
    let mut cells = BTreeMap::new();
    let mut notes = Vec::new();
    let mut missing: Vec<String> = Vec::new();
    for k in 0..n {
        let shard = Shard { k, n };
        let Some(dir) = by_k.get(&k) else {
            if !shard.is_empty(len) {
                missing.push(describe_missing(
                    sweep,
                    shard,
                    "not given",
                    (k..len).step_by(n).collect(),
                ));
            }
            continue;
        };
        let path = dir.join(JOURNAL);
        if !path.exists() && !shard.is_empty(len) {
            return Err(MergeError::Journal(SweepError::Io(
                path,
                std::io::Error::new(
                    std::io::ErrorKind::NotFound,
                    format!("shard {shard} has no journal (it never ran here)"),
                ),
            )));
        }
        let journaled =
            read_journal(&path, &shard.header(sweep), len).map_err(MergeError::Journal)?;
        let lacking: Vec<usize> = (k..len)
            .step_by(n)
            .filter(|i| !journaled.contains_key(i))
            .collect();
        if !lacking.is_empty() {
            let d = dir.display().to_string();
            missing.push(describe_missing(sweep, shard, &d, lacking));
        }
        for (i, (c, m)) in journaled {
            if !shard.owns(i) {
                continue;
            }
            if !c.class.has_result() {
                notes.push((i, c.class, m.unwrap_or_else(|| "failed".into())));
            }
            cells.insert(i, c);
        }
    }
    if !missing.is_empty() {
        return Err(MergeError::Shards(format!(
            "the shards do not hold every cell of the sweep, nothing merged (run or resume the \
             shards named, then merge again):\n  {}",
            missing.join("\n  ")
        )));
    }
    let (failures, beyond_model) = split_notes(notes);
    Ok(Outcome {
        cells: cells.into_values().collect(),
        failures,
        beyond_model,
        computed: 0,
        elapsed: Duration::ZERO,
    })
}

/// One line of a missing-cells error: the owner, where it was looked for, and the first cells
/// with their axis values.
fn describe_missing(sweep: &Sweep, shard: Shard, dir: &str, lacking: Vec<usize>) -> String {
    let listed: Vec<String> = lacking
        .iter()
        .take(LISTED)
        .map(|&i| {
            let values: Vec<String> = sweep
                .axes
                .iter()
                .zip(sweep.values(i))
                .map(|(a, v)| format!("{}={v}", a.key))
                .collect();
            format!("{i} ({})", values.join(", "))
        })
        .collect();
    let more = lacking.len().saturating_sub(LISTED);
    let more = if more > 0 {
        format!(", and {more} more")
    } else {
        String::new()
    };
    format!(
        "shard {shard} ({dir}): {} of its {} cells missing: {}{more}",
        lacking.len(),
        shard.len(sweep.len()),
        listed.join("; ")
    )
}
