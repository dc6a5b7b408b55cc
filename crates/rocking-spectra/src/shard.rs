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
    pub fn parse(text: &str) -> Result<Shard, ShardSpecError> {
        let bad = |problem| ShardSpecError {
            text: text.to_string(),
            problem,
        };
        let (k, n) = text
            .split_once('/')
            .ok_or_else(|| bad(ShardSpecProblem::NotKOverN))?;
        let int = |s: &str, part: &'static str| {
            s.trim().parse::<usize>().map_err(|_| {
                bad(ShardSpecProblem::NotWhole {
                    part,
                    found: s.to_string(),
                })
            })
        };
        let (k, n) = (int(k, "K")?, int(n, "N")?);
        if !(1..=MAX_SHARDS).contains(&n) {
            return Err(bad(ShardSpecProblem::Count { n }));
        }
        if k >= n {
            return Err(bad(ShardSpecProblem::Number { k, n }));
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

/// A shard specification that is not `K/N` with 0 ≤ K < N ≤ [`MAX_SHARDS`]: the text given and
/// what is wrong with it. Its [`Display`](fmt::Display) is `shard `TEXT`: WHY`; a caller that took
/// the text from a flag names the flag with `text` and `problem`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ShardSpecError {
    /// The text given.
    pub text: String,
    /// What is wrong with it.
    pub problem: ShardSpecProblem,
}

/// What is wrong with a shard specification.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum ShardSpecProblem {
    /// No `/` between K and N.
    NotKOverN,
    /// K or N is not a whole number ≥ 0.
    NotWhole {
        /// `K` or `N`.
        part: &'static str,
        /// The text found there.
        found: String,
    },
    /// N is not 1 ≤ N ≤ [`MAX_SHARDS`].
    Count {
        /// The N given.
        n: usize,
    },
    /// K is not 0 ≤ K < N.
    Number {
        /// The K given.
        k: usize,
        /// The N given.
        n: usize,
    },
}

impl fmt::Display for ShardSpecProblem {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ShardSpecProblem::NotKOverN => {
                f.write_str("expected K/N, e.g. 0/4 (shard K of N, counted from 0)")
            }
            ShardSpecProblem::NotWhole { part, found } => {
                write!(f, "{part} `{found}` is not a whole number ≥ 0")
            }
            ShardSpecProblem::Count { n } => {
                write!(f, "N = {n} is not allowed: 1 ≤ N ≤ {MAX_SHARDS}")
            }
            ShardSpecProblem::Number { k, n } => {
                write!(f, "K = {k} is not allowed: 0 ≤ K < N = {n}")
            }
        }
    }
}

impl fmt::Display for ShardSpecError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "shard `{}`: {}", self.text, self.problem)
    }
}

impl std::error::Error for ShardSpecError {}

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
    /// No shard directory was given.
    NoShards,
    /// The shards are of splits into different numbers of shards.
    MixedSplits {
        /// The directory of the shard that differs.
        dir: PathBuf,
        /// Its shard.
        shard: Shard,
        /// The first directory given.
        first_dir: PathBuf,
        /// Its shard.
        first: Shard,
    },
    /// A shard is given twice.
    Duplicate {
        /// The second directory of the shard.
        dir: PathBuf,
        /// The shard.
        shard: Shard,
        /// The first directory of the shard.
        other: PathBuf,
    },
    /// A shard with cells has no journal (it never ran in the directory given).
    NoJournal {
        /// The shard.
        shard: Shard,
        /// The journal looked for.
        path: PathBuf,
    },
    /// The shards do not hold every cell: shards not given (missing) or whose journals lack
    /// cells (incomplete), in shard order. Nothing is merged.
    Incomplete {
        /// Each shard with missing cells.
        gaps: Vec<Gap>,
    },
}

/// A shard's missing cells.
#[derive(Clone, Debug, PartialEq)]
pub struct Gap {
    /// The shard.
    pub shard: Shard,
    /// Its directory, or `None` when the shard was not given.
    pub dir: Option<PathBuf>,
    /// How many of its cells are missing.
    pub missing: usize,
    /// How many cells it has.
    pub cells: usize,
    /// The first missing cells (at most [`LISTED`]), with their axis values.
    pub first: Vec<MissingCell>,
}

/// A missing cell: its index and its axis values.
#[derive(Clone, Debug, PartialEq)]
pub struct MissingCell {
    /// The cell's index in the sweep.
    pub index: usize,
    /// (axis key, value) of each axis (a text axis: the text's index).
    pub values: Vec<(String, f64)>,
}

impl fmt::Display for MergeError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            MergeError::Journal(e) => e.fmt(f),
            MergeError::NoShards => f.write_str("no shard directory given"),
            MergeError::MixedSplits {
                dir,
                shard,
                first_dir,
                first,
            } => write!(
                f,
                "{}: shard {shard} is of a split into {} shards, but {} is shard {first} of {}",
                dir.display(),
                shard.n,
                first_dir.display(),
                first.n
            ),
            MergeError::Duplicate { dir, shard, other } => write!(
                f,
                "{}: shard {shard} is given twice (also {})",
                dir.display(),
                other.display()
            ),
            MergeError::NoJournal { shard, path } => write!(
                f,
                "{}: shard {shard} has no journal (it never ran here)",
                path.display()
            ),
            MergeError::Incomplete { gaps } => {
                f.write_str(
                    "the shards do not hold every cell of the sweep, nothing merged (run or \
                     resume the shards named, then merge again):",
                )?;
                for g in gaps {
                    write!(f, "\n  {g}")?;
                }
                Ok(())
            }
        }
    }
}

impl fmt::Display for Gap {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let dir = match &self.dir {
            Some(d) => d.display().to_string(),
            None => "not given".to_string(),
        };
        write!(
            f,
            "shard {} ({dir}): {} of its {} cells missing: ",
            self.shard, self.missing, self.cells
        )?;
        for (k, c) in self.first.iter().enumerate() {
            if k > 0 {
                f.write_str("; ")?;
            }
            let values: Vec<String> = c.values.iter().map(|(a, v)| format!("{a}={v}")).collect();
            write!(f, "{} ({})", c.index, values.join(", "))?;
        }
        let more = self.missing.saturating_sub(self.first.len());
        if more > 0 {
            write!(f, ", and {more} more")?;
        }
        Ok(())
    }
}

impl std::error::Error for MergeError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            MergeError::Journal(e) => Some(e),
            _ => None,
        }
    }
}

/// The most missing cells listed per shard in an error (the count is always given).
pub const LISTED: usize = 10;

/// Reads the journals of the shards in `dirs` (each with the shard it ran) into the outcome of
/// the whole `sweep`, as if it had run on one machine: every shard of one `N` exactly once, and
/// every cell journaled by the shard that owns it. Missing cells are listed with their owner.
pub fn merge(sweep: &Sweep, dirs: &[(PathBuf, Shard)]) -> Result<Outcome, MergeError> {
    let Some(&(ref first_dir, first)) = dirs.first() else {
        return Err(MergeError::NoShards);
    };
    let n = first.n;
    let mut by_k: BTreeMap<usize, &Path> = BTreeMap::new();
    for (dir, s) in dirs {
        if s.n != n {
            return Err(MergeError::MixedSplits {
                dir: dir.clone(),
                shard: *s,
                first_dir: first_dir.clone(),
                first,
            });
        }
        if let Some(other) = by_k.insert(s.k, dir) {
            return Err(MergeError::Duplicate {
                dir: dir.clone(),
                shard: *s,
                other: other.to_path_buf(),
            });
        }
    }
    let len = sweep.len();
    let mut cells = BTreeMap::new();
    let mut notes = Vec::new();
    let mut gaps: Vec<Gap> = Vec::new();
    for k in 0..n {
        let shard = Shard { k, n };
        let Some(dir) = by_k.get(&k) else {
            if !shard.is_empty(len) {
                gaps.push(gap(sweep, shard, None, (k..len).step_by(n).collect()));
            }
            continue;
        };
        let path = dir.join(JOURNAL);
        if !path.exists() && !shard.is_empty(len) {
            return Err(MergeError::NoJournal { shard, path });
        }
        let journaled =
            read_journal(&path, &shard.header(sweep), len).map_err(MergeError::Journal)?;
        let lacking: Vec<usize> = (k..len)
            .step_by(n)
            .filter(|i| !journaled.contains_key(i))
            .collect();
        if !lacking.is_empty() {
            gaps.push(gap(sweep, shard, Some(dir.to_path_buf()), lacking));
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
    if !gaps.is_empty() {
        return Err(MergeError::Incomplete { gaps });
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

/// A shard's missing cells (`lacking`, in order), the first with their axis values.
fn gap(sweep: &Sweep, shard: Shard, dir: Option<PathBuf>, lacking: Vec<usize>) -> Gap {
    let first = lacking
        .iter()
        .take(LISTED)
        .map(|&index| MissingCell {
            index,
            values: sweep
                .axes
                .iter()
                .zip(sweep.values(index))
                .map(|(a, v)| (a.key.clone(), v))
                .collect(),
        })
        .collect();
    Gap {
        shard,
        dir,
        missing: lacking.len(),
        cells: shard.len(sweep.len()),
        first,
    }
}
