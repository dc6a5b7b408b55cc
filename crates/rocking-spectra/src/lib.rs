//! The generic sweep engine: parallel, journaled, resumable, sharded sweeps of simulations.
//!
//! It owns cells, journals, shards and their merge; it knows a run only by its
//! [`rocking::Summary`] and must not know scenes, records or what a cell's axes mean (the
//! scene-aware studies are `rocking-study`'s).
//!
//! A sweep is a list of [`Axis`] (named by scene key paths, e.g. `excitation.amplitude`) whose
//! cartesian product gives the cells, in a fixed order (the last axis varies fastest). Every cell
//! is one simulation, run by a caller-supplied function, and is classified ([`CellClass`]) from
//! its summary. Cells run in parallel (rayon); each finished cell is appended to a journal in the
//! output directory, so an interrupted sweep (killed, Ctrl-C) resumes where it stopped when run
//! again with the same directory. The journal's first line is a fingerprint of the sweep (scene
//! and axes); a different sweep in the same directory is refused instead of mixing results. A
//! torn last line (the process died mid-write) fails its checksum and is simply recomputed.
//! Results do not depend on the number of threads: cells are independent and written out in
//! cell order.

#![warn(missing_docs)]

use std::collections::BTreeMap;
use std::fmt;
use std::fs::{self, OpenOptions};
use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::Mutex;
use std::time::{Duration, Instant};

use rayon::prelude::*;

mod axis;
mod cell;
mod journal;
pub mod shard;

pub use axis::{Axis, MAX_AXIS_VALUES, MAX_CELLS};
pub use cell::{Cell, CellClass, CellFailure, CellRun};
pub use journal::fnv1a;
pub(crate) use journal::{journal_line, parse_journal_line, JOURNAL};
pub use shard::Shard;

/// Why a sweep failed. The messages state what is wrong with the directory; what to do about it
/// (another output directory, or deleting it) is the caller's to say, in its own words.
#[derive(Debug)]
pub enum SweepError {
    /// Reading or writing the output directory failed.
    Io(PathBuf, std::io::Error),
    /// The output directory holds a different sweep.
    Mismatch(PathBuf),
    /// The journal file is not a sweep journal (a directory, binary data, another file).
    NotJournal(PathBuf, &'static str),
}

impl fmt::Display for SweepError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SweepError::Io(p, e) => write!(f, "{}: {e}", p.display()),
            SweepError::Mismatch(p) => write!(
                f,
                "{}: this output directory holds the cells of a different sweep (scene, record \
                 contents, axes or program changed)",
                p.display()
            ),
            SweepError::NotJournal(p, why) => {
                write!(
                    f,
                    "{}: not a journal of rocking sweeps ({why})",
                    p.display()
                )
            }
        }
    }
}

impl std::error::Error for SweepError {}

/// A sweep: axes and a fingerprint of everything that determines its cells.
#[derive(Clone, Debug)]
pub struct Sweep {
    /// The axes; the last varies fastest.
    pub axes: Vec<Axis>,
    /// Identifies the sweep (for example a hash of the scene text and the axes).
    pub fingerprint: String,
    /// The quantities each cell reports besides its class, max θ/α and impacts (the names of
    /// their columns in cells.csv; the caller's run of a cell gives their values, in order).
    pub reported: Vec<String>,
}

impl Sweep {
    /// The number of cells of `axes`, or an error when it exceeds [`MAX_CELLS`] (checked before
    /// anything is allocated for them; the product is formed without overflow).
    pub fn checked_len(axes: &[Axis]) -> Result<usize, String> {
        let mut n: usize = 1;
        for a in axes {
            n = n.saturating_mul(a.values.len());
        }
        if n > MAX_CELLS {
            let sizes: Vec<String> = axes.iter().map(|a| a.values.len().to_string()).collect();
            return Err(format!(
                "{} cells ({}) are too many: a sweep has at most {MAX_CELLS} cells",
                if n == usize::MAX {
                    "so many".to_string()
                } else {
                    n.to_string()
                },
                sizes.join(" x ")
            ));
        }
        Ok(n)
    }

    /// Number of cells.
    pub fn len(&self) -> usize {
        self.axes.iter().map(|a| a.values.len()).product()
    }

    /// Whether the sweep has no cell.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The axis values of cell `index`.
    pub fn values(&self, mut index: usize) -> Vec<f64> {
        let mut out = vec![0.0; self.axes.len()];
        for (k, axis) in self.axes.iter().enumerate().rev() {
            let n = axis.values.len();
            out[k] = axis.values[index % n];
            index /= n;
        }
        out
    }
}

/// The cells (and failure messages) of the journal at `path` when it belongs to this sweep;
/// nothing when there is no journal or it is empty (a sweep killed before its first write).
pub(crate) fn read_journal(
    path: &Path,
    header: &str,
    len: usize,
) -> Result<BTreeMap<usize, (Cell, Option<String>)>, SweepError> {
    let mut done = BTreeMap::new();
    let meta = match fs::metadata(path) {
        Ok(m) => m,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(done),
        Err(e) => return Err(SweepError::Io(path.to_path_buf(), e)),
    };
    if meta.is_dir() {
        return Err(SweepError::NotJournal(
            path.to_path_buf(),
            "it is a directory",
        ));
    }
    let bytes = fs::read(path).map_err(|e| SweepError::Io(path.to_path_buf(), e))?;
    if bytes.is_empty() {
        return Ok(done);
    }
    let Ok(text) = std::str::from_utf8(&bytes) else {
        return Err(SweepError::NotJournal(path.to_path_buf(), "it is not text"));
    };
    let mut lines = text.lines();
    let first = lines.next().unwrap_or_default();
    if !first.starts_with("# rocking sweep ") {
        return Err(SweepError::NotJournal(
            path.to_path_buf(),
            "its first line is not a sweep header",
        ));
    }
    if format!("{first}\n") != header {
        return Err(SweepError::Mismatch(path.to_path_buf()));
    }
    for line in lines {
        if let Some((c, m)) = parse_journal_line(line) {
            if c.index < len {
                done.insert(c.index, (c, m));
            }
        }
    }
    Ok(done)
}

/// Progress display.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Progress {
    /// A bar with rate and ETA when stderr is a terminal and `CI` is not set.
    Auto,
    /// Nothing.
    Quiet,
}

/// The finished sweep.
#[derive(Clone, Debug)]
pub struct Outcome {
    /// Every cell, in cell order.
    pub cells: Vec<Cell>,
    /// Every failed cell with its error message, whether it failed in this invocation or in an
    /// earlier one that this one resumed (failures are never dropped on resume).
    pub failures: Messages,
    /// Every cell beyond the model's validity ([`CellClass::BeyondModel`]) with its message,
    /// kept on resume like the failures.
    pub beyond_model: Messages,
    /// Cells computed in this invocation (the rest came from the journal).
    pub computed: usize,
    /// Wall time of this invocation.
    pub elapsed: Duration,
}

/// Runs (or resumes) a sweep in `out_dir`. `run_cell` gets the cell's axis values and returns
/// the summary of its simulation. Finished cells are journaled as they complete.
pub fn run<F, R, E>(
    sweep: &Sweep,
    out_dir: &Path,
    progress: Progress,
    run_cell: F,
) -> Result<Outcome, SweepError>
where
    F: Fn(&[f64]) -> Result<R, E> + Sync,
    R: Into<CellRun>,
    E: Into<CellFailure>,
{
    let header = format!("# rocking sweep {}\n", sweep.fingerprint);
    run_cells(sweep, &header, |_| true, out_dir, progress, run_cell)
}

/// Runs (or resumes) one shard of a sweep in `out_dir`, with the shard's own journal: the
/// outcome holds only the shard's cells. [`shard::merge`] joins the shards' journals.
pub fn run_shard<F, R, E>(
    sweep: &Sweep,
    shard: Shard,
    out_dir: &Path,
    progress: Progress,
    run_cell: F,
) -> Result<Outcome, SweepError>
where
    F: Fn(&[f64]) -> Result<R, E> + Sync,
    R: Into<CellRun>,
    E: Into<CellFailure>,
{
    let header = shard.header(sweep);
    run_cells(
        sweep,
        &header,
        |i| shard.owns(i),
        out_dir,
        progress,
        run_cell,
    )
}

/// Runs the cells that `owns` selects, journaled under `header`.
fn run_cells<F, R, E>(
    sweep: &Sweep,
    header: &str,
    owns: impl Fn(usize) -> bool,
    out_dir: &Path,
    progress: Progress,
    run_cell: F,
) -> Result<Outcome, SweepError>
where
    F: Fn(&[f64]) -> Result<R, E> + Sync,
    R: Into<CellRun>,
    E: Into<CellFailure>,
{
    let start = Instant::now();
    Sweep::checked_len(&sweep.axes)
        .map_err(|m| SweepError::Io(out_dir.to_path_buf(), std::io::Error::other(m)))?;
    fs::create_dir_all(out_dir).map_err(|e| SweepError::Io(out_dir.to_path_buf(), e))?;
    let path = out_dir.join(JOURNAL);
    let mut journaled = read_journal(&path, header, sweep.len())?;
    journaled.retain(|&i, _| owns(i));
    let header = header.to_string();
    // Rewrite the journal with only the valid lines, so that a torn line is gone for good.
    let mut text = header.clone();
    for (c, m) in journaled.values() {
        text.push_str(&journal_line(c, m.as_deref()));
    }
    let mut notes: Vec<(usize, CellClass, String)> = journaled
        .values()
        .filter(|(c, _)| !c.class.has_result())
        .map(|(c, m)| {
            let m = m
                .clone()
                .unwrap_or_else(|| "failed in an earlier run".into());
            (c.index, c.class, m)
        })
        .collect();
    let mut done: BTreeMap<usize, Cell> = journaled.into_iter().map(|(i, (c, _))| (i, c)).collect();
    write_atomic(&path, text.as_bytes()).map_err(|e| SweepError::Io(path.clone(), e))?;
    let journal = OpenOptions::new()
        .append(true)
        .open(&path)
        .map_err(|e| SweepError::Io(path.clone(), e))?;
    let journal = Mutex::new(journal);
    let todo: Vec<usize> = (0..sweep.len())
        .filter(|&i| owns(i) && !done.contains_key(&i))
        .collect();
    let bar = match progress {
        Progress::Quiet => indicatif::ProgressBar::hidden(),
        Progress::Auto if std::env::var_os("CI").is_some() => indicatif::ProgressBar::hidden(),
        Progress::Auto => {
            let bar = indicatif::ProgressBar::with_draw_target(
                Some(todo.len() as u64),
                indicatif::ProgressDrawTarget::stderr(),
            );
            bar.set_style(
                indicatif::ProgressStyle::with_template(
                    "{bar:40} {pos}/{len} cells  {per_sec}  ETA {eta}",
                )
                .expect("static template"),
            );
            bar
        }
    };
    let fresh_notes = Mutex::new(Vec::new());
    let fresh: Vec<Cell> = todo
        .par_iter()
        .map(|&index| {
            let (cell, message) = evaluate(sweep, index, &run_cell);
            let line = journal_line(&cell, message.as_deref());
            if let Some(m) = message {
                // As the journal keeps it, so a resumed or merged sweep reports the same text.
                let m = m.replace(['\n', '\r'], " ");
                fresh_notes
                    .lock()
                    .unwrap_or_else(|p| p.into_inner())
                    .push((index, cell.class, m));
            }
            let mut j = journal.lock().unwrap_or_else(|p| p.into_inner());
            j.write_all(line.as_bytes())
                .map_err(|e| SweepError::Io(path.clone(), e))?;
            drop(j);
            bar.inc(1);
            Ok(cell)
        })
        .collect::<Result<_, SweepError>>()?;
    bar.finish_and_clear();
    let computed = fresh.len();
    for c in fresh {
        done.insert(c.index, c);
    }
    notes.extend(fresh_notes.into_inner().unwrap_or_else(|p| p.into_inner()));
    let (failures, beyond_model) = split_notes(notes);
    Ok(Outcome {
        cells: done.into_values().collect(),
        failures,
        beyond_model,
        computed,
        elapsed: start.elapsed(),
    })
}

/// Cell indices with their messages, in cell order.
pub type Messages = Vec<(usize, String)>;

/// The messages of the cells without a result, in cell order: the failures' and the cells'
/// beyond the model.
pub(crate) fn split_notes(mut notes: Vec<(usize, CellClass, String)>) -> (Messages, Messages) {
    notes.sort_by_key(|n| n.0);
    let (beyond, failed): (Vec<_>, Vec<_>) = notes
        .into_iter()
        .partition(|n| n.1 == CellClass::BeyondModel);
    let strip =
        |v: Vec<(usize, CellClass, String)>| v.into_iter().map(|(i, _, m)| (i, m)).collect();
    (strip(failed), strip(beyond))
}

/// Runs one cell: its class and numbers, or a class without a result and its message.
fn evaluate<F, R, E>(sweep: &Sweep, index: usize, run_cell: &F) -> (Cell, Option<String>)
where
    F: Fn(&[f64]) -> Result<R, E>,
    R: Into<CellRun>,
    E: Into<CellFailure>,
{
    match run_cell(&sweep.values(index)).map(Into::into) {
        Ok(CellRun { summary, reported }) if reported.len() == sweep.reported.len() => (
            Cell {
                index,
                class: CellClass::of(&summary),
                max_theta_over_alpha: summary.max_theta_over_alpha,
                impacts: summary.impacts,
                reported,
            },
            None,
        ),
        Ok(run) => without_result(
            index,
            format!(
                "the cell gave {} reported values for the sweep's {}",
                run.reported.len(),
                sweep.reported.len()
            )
            .into(),
        ),
        Err(e) => without_result(index, e.into()),
    }
}

/// A cell without a result, of the failure's class (a class with a result is a failure).
fn without_result(index: usize, f: CellFailure) -> (Cell, Option<String>) {
    let class = if f.class.has_result() {
        CellClass::Failed
    } else {
        f.class
    };
    (
        Cell {
            index,
            class,
            max_theta_over_alpha: 0.0,
            impacts: 0,
            reported: Vec::new(),
        },
        Some(f.message),
    )
}

/// Runs every cell of a sweep in parallel, without a journal (nothing is written): for callers
/// that keep the results in memory, such as the Python package.
pub fn run_in_memory<F, R, E>(sweep: &Sweep, run_cell: F) -> Result<Outcome, SweepError>
where
    F: Fn(&[f64]) -> Result<R, E> + Sync,
    R: Into<CellRun>,
    E: Into<CellFailure>,
{
    let start = Instant::now();
    Sweep::checked_len(&sweep.axes)
        .map_err(|m| SweepError::Io(PathBuf::new(), std::io::Error::other(m)))?;
    let results: Vec<(Cell, Option<String>)> = (0..sweep.len())
        .into_par_iter()
        .map(|index| evaluate(sweep, index, &run_cell))
        .collect();
    let (failures, beyond_model) = split_notes(
        results
            .iter()
            .filter_map(|(c, m)| m.clone().map(|m| (c.index, c.class, m)))
            .collect(),
    );
    Ok(Outcome {
        computed: results.len(),
        cells: results.into_iter().map(|(c, _)| c).collect(),
        failures,
        beyond_model,
        elapsed: start.elapsed(),
    })
}

/// Writes `bytes` to `path` atomically: a temporary file in the same directory, synced, then
/// renamed over `path` (a reader sees the old file or the new one, never a part). The file gets
/// the permissions of a file created the usual way (0666 less the umask, where tempfile alone
/// would give 0600: results are meant to be read by others).
pub fn write_atomic(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    let mut builder = tempfile::Builder::new();
    #[cfg(unix)]
    builder.permissions(std::os::unix::fs::PermissionsExt::from_mode(0o666));
    let mut tmp = builder.tempfile_in(dir)?;
    tmp.write_all(bytes)?;
    tmp.as_file().sync_all()?;
    tmp.persist(path).map_err(|e| e.error)?;
    Ok(())
}

/// `text` as a CSV field: quoted when it holds a quote, a comma or a line break.
fn csv_field(text: &str) -> String {
    if text.contains(['"', ',', '\n', '\r']) {
        format!("\"{}\"", text.replace('"', "\"\""))
    } else {
        text.to_string()
    }
}

/// `cells.csv`: one row per cell with the axis values (columns named by their key paths),
/// the class, max θ/α, the number of impacts and the reported quantities.
pub fn cells_csv(sweep: &Sweep, cells: &[Cell]) -> String {
    let mut out = String::new();
    for a in &sweep.axes {
        out.push_str(&a.key);
        out.push(',');
    }
    out.push_str("class,max_theta_over_alpha,impacts");
    for q in &sweep.reported {
        out.push(',');
        out.push_str(q);
    }
    out.push('\n');
    for c in cells {
        for (a, v) in sweep.axes.iter().zip(sweep.values(c.index)) {
            out.push_str(&csv_field(&a.display(v)));
            out.push(',');
        }
        if !c.class.has_result() {
            // A failed cell has no result: empty fields, not zeros that read as one.
            out.push_str(c.class.as_str());
            out.push_str(",,");
            out.push_str(&",".repeat(sweep.reported.len()));
            out.push('\n');
            continue;
        }
        out.push_str(&format!(
            "{},{},{}",
            c.class.as_str(),
            c.max_theta_over_alpha,
            c.impacts
        ));
        for v in &c.reported {
            // A quantity the cell's run has no value of (an event that did not happen): empty.
            match v {
                Some(v) => out.push_str(&format!(",{v}")),
                None => out.push(','),
            }
        }
        out.push('\n');
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn axis_parsing() {
        let a = Axis::parse("excitation.amplitude=1:20:5").unwrap();
        assert_eq!(a.key, "excitation.amplitude");
        assert_eq!(a.values, vec![1.0, 5.75, 10.5, 15.25, 20.0]);
        assert_eq!(
            Axis::parse("structure.alpha=0.1,0.2").unwrap().values,
            vec![0.1, 0.2]
        );
        for bad in [
            "x",
            "=1:2:3",
            "x=1:2",
            "x=1:2:0",
            "x=a:2:3",
            "x=1:inf:3",
            "x=1,,2",
            "x=1:2:1e11",
            "x=1:2:100000000000",
        ] {
            assert!(Axis::parse(bad).is_err(), "{bad}");
        }
        let e = Axis::parse("x=1:2:100000000000").unwrap_err();
        assert!(e.contains("at most 100000"), "{e}");
        let five: Vec<Axis> = (0..5)
            .map(|k| Axis::parse(&format!("a{k}=1:2:10000")).unwrap())
            .collect();
        let e = Sweep::checked_len(&five).unwrap_err();
        assert!(e.contains("at most 1000000 cells"), "{e}");
        assert_eq!(Sweep::checked_len(&five[..1]), Ok(10_000));
    }

    #[test]
    fn a_list_with_a_text_is_a_text_axis_written_back_as_given() {
        let a = Axis::parse("structure.model= cubic, cantilever_modes2 ,x").unwrap();
        assert!(a.is_text());
        assert_eq!(a.texts, ["cubic", "cantilever_modes2", "x"]);
        assert_eq!(a.values, [0.0, 1.0, 2.0]);
        assert_eq!(a.text(1.0), Some("cantilever_modes2"));
        assert_eq!(a.display(2.0), "x");
        assert_eq!(a.spec(), "structure.model=cubic,cantilever_modes2,x");
        assert_eq!(Axis::parse(&a.spec()).unwrap(), a);
        // A number among texts is a text too (the scene says whether the key takes it).
        assert_eq!(Axis::parse("k=1,a").unwrap().texts, ["1", "a"]);
        let e = Axis::parse("k=a,,b").unwrap_err();
        assert!(e.contains("value 2 is empty"), "{e}");
        let e = Axis::parse("k=vvel,adjex,vvel").unwrap_err();
        assert!(e.contains("`vvel` is given twice"), "{e}");
        // Numeric axes are unchanged, and their spec reads back exactly.
        let n = Axis::parse("k=0.1,1e-3,2").unwrap();
        assert!(!n.is_text());
        assert_eq!(n.values, [0.1, 1e-3, 2.0]);
        assert_eq!(n.display(0.1), "0.1");
        assert_eq!(Axis::parse(&n.spec()).unwrap(), n);
        let r = Axis::parse("k=0.1:0.7:7").unwrap();
        assert_eq!(Axis::parse(&r.spec()).unwrap(), r);
    }

    #[test]
    fn cells_csv_writes_the_texts_of_a_text_axis() {
        let s = Sweep {
            axes: vec![
                Axis::parse("structure.model=cubic,polynomial2").unwrap(),
                Axis::numbers("b", vec![0.5]),
            ],
            fingerprint: "x".into(),
            reported: Vec::new(),
        };
        let cells: Vec<Cell> = (0..2)
            .map(|index| Cell {
                index,
                class: CellClass::Survived,
                max_theta_over_alpha: 0.25,
                impacts: 3,
                reported: Vec::new(),
            })
            .collect();
        assert_eq!(
            cells_csv(&s, &cells),
            "structure.model,b,class,max_theta_over_alpha,impacts\n\
             cubic,0.5,survived,0.25,3\npolynomial2,0.5,survived,0.25,3\n"
        );
    }

    #[test]
    fn cells_csv_leaves_a_quantity_without_a_value_empty() {
        let s = Sweep {
            axes: vec![Axis::numbers("a", vec![1.0, 2.0])],
            fingerprint: "x".into(),
            reported: vec!["first_uplift_time".into(), "max_u_over_ucr".into()],
        };
        let cell = |index, class, reported| Cell {
            index,
            class,
            max_theta_over_alpha: 0.5,
            impacts: 0,
            reported,
        };
        let cells = [
            cell(0, CellClass::NoUplift, vec![None, Some(0.0)]),
            cell(1, CellClass::Survived, vec![Some(1.5), Some(2.0)]),
        ];
        assert_eq!(
            cells_csv(&s, &cells),
            "a,class,max_theta_over_alpha,impacts,first_uplift_time,max_u_over_ucr\n\
             1,no-uplift,0.5,0,,0\n2,survived,0.5,0,1.5,2\n"
        );
    }

    #[test]
    fn cell_order_is_last_axis_fastest() {
        let s = Sweep {
            axes: vec![
                Axis::numbers("a", vec![1.0, 2.0]),
                Axis::numbers("b", vec![10.0, 20.0, 30.0]),
            ],
            fingerprint: "x".into(),
            reported: Vec::new(),
        };
        assert_eq!(s.len(), 6);
        assert_eq!(s.values(0), vec![1.0, 10.0]);
        assert_eq!(s.values(2), vec![1.0, 30.0]);
        assert_eq!(s.values(3), vec![2.0, 10.0]);
    }

    #[test]
    fn journal_lines_round_trip_and_torn_lines_are_rejected() {
        let c = Cell {
            index: 17,
            class: CellClass::OverturnedOneImpact,
            max_theta_over_alpha: 15.707,
            impacts: 1,
            reported: vec![Some(1.25), None, Some(-3e-17)],
        };
        let line = journal_line(&c, None);
        assert_eq!(parse_journal_line(line.trim_end()), Some((c.clone(), None)));
        let failed = Cell {
            class: CellClass::Failed,
            reported: Vec::new(),
            ..c
        };
        let line = journal_line(&failed, Some("singular, at u = 1\nbad"));
        assert_eq!(
            parse_journal_line(line.trim_end()),
            Some((failed, Some("singular, at u = 1 bad".to_string())))
        );
        for cut in 1..line.len() - 1 {
            assert_eq!(parse_journal_line(&line[..cut]), None, "{}", &line[..cut]);
        }
    }
}
