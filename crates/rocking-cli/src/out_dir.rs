//! Outputs: atomic file writes and a command's output directory, built aside and swapped in
//! whole; the summary, history and event tables themselves come from `rocking_study::run_report`
//! (shared with the Python package).

use std::path::{Path, PathBuf};

use crate::plot;

use rocking_scene::SceneError;

/// Writes `bytes` to `path` atomically ([`rocking_spectra::write_atomic`]).
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<(), SceneError> {
    rocking_spectra::write_atomic(path, bytes)
        .map_err(|e| SceneError::failure(format!("{}: cannot write: {e}", path.display())))
}

/// What an output directory holds: the files its command writes, and the command's name. An
/// existing directory holding anything else is not replaced (it is not this command's).
#[derive(Clone, Copy)]
pub struct OutKind {
    /// Whether a file of this name is one the command may write (all of them: a command rewrites
    /// its own previous outputs, whichever options wrote them).
    pub writes: fn(&str) -> bool,
    /// The command, for messages.
    pub command: &'static str,
}

/// The outputs of `rocking run` (with --animate, plots in every format).
pub const RUN_OUT: OutKind = OutKind {
    writes: |n| {
        ["summary.json", "history.csv", "events.csv", "animation.gif"].contains(&n)
            || plot::is_figure_file(n, "plot")
    },
    command: "rocking run",
};

/// The outputs of `rocking ida` (IDA or stripes).
pub const IDA_OUT: OutKind = OutKind {
    writes: |n| {
        [
            "records.csv",
            "ida.csv",
            "stripes.csv",
            "fragility.json",
            "timing.json",
        ]
        .contains(&n)
            || ["ida", "fragility-fit"]
                .iter()
                .any(|figure| plot::is_figure_file(n, figure))
    },
    command: "rocking ida",
};

/// The outputs of `rocking merge`: a spectrum's (any number of axes, with its reference) or a
/// record suite's.
pub const MERGE_OUT: OutKind = OutKind {
    writes: |n| {
        [
            "cells.csv",
            "meta.json",
            "reference.csv",
            "runs.csv",
            "fragility.csv",
        ]
        .contains(&n)
            || plot::is_sweep_figure(n)
    },
    command: "rocking merge",
};

/// The output directory of one command, built aside and swapped in whole: the directory always
/// holds exactly one run's files, whether the run is killed while writing (the old directory
/// stays), killed while swapping (the old directory or the new one is in place, never neither),
/// runs in parallel into the same `--out` (the last to finish wins, never a mix), or writes fewer
/// files than the previous run (no stale ones). An `--out` that is a symbolic link keeps its link:
/// the directory it points to is replaced. The swap happens under a lock file beside the
/// directory; what killed runs left beside it is removed by the next run, which first puts back
/// a previous directory that a kill left aside (see [`OutDir::commit`]).
pub struct OutDir {
    /// The directory replaced (an `--out` symlink resolved).
    target: PathBuf,
    /// `--out` as given, for messages and the paths printed.
    shown: PathBuf,
    staging: tempfile::TempDir,
    _lock: std::fs::File,
    kind: OutKind,
}

fn io_error(what: &str, p: &Path, e: std::io::Error) -> SceneError {
    SceneError::failure(format!("{}: cannot {what}: {e}", p.display()))
}

/// The directory `--out` names: itself, or where it links to. A link to nowhere is refused
/// (there is no directory to replace, and creating one through the link is not what was asked).
fn resolve(out: &Path) -> Result<PathBuf, SceneError> {
    match std::fs::symlink_metadata(out) {
        Ok(m) if m.file_type().is_symlink() => std::fs::canonicalize(out).map_err(|e| {
            let to = std::fs::read_link(out).unwrap_or_default();
            SceneError::input(format!(
                "{}: --out is a symbolic link to {}, which cannot be used ({e}); give a \
                 directory, or a link to one",
                out.display(),
                to.display()
            ))
        }),
        _ => Ok(out.to_path_buf()),
    }
}

/// `.NAME.rocking-`: the prefix of the staging and set-aside directories beside `NAME`.
fn leftover_prefix(name: &str) -> String {
    format!(".{name}.rocking-")
}

/// The prefix of a previous directory set aside by a swap of two renames.
fn old_prefix(name: &str) -> String {
    format!("{}old-", leftover_prefix(name))
}

impl OutDir {
    /// Locks `out`'s name, puts back a directory a killed swap left aside, removes what killed
    /// runs left, and creates the staging directory; an existing `out` may hold only files that
    /// `kind` writes. Called before the command's work, so that an `--out` it could not replace
    /// is refused before anything is computed.
    pub fn begin(out: &Path, kind: OutKind) -> Result<OutDir, SceneError> {
        use fs4::fs_std::FileExt as _;
        let target = resolve(out)?;
        let name = target
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .ok_or_else(|| {
                SceneError::input(format!("{}: not a directory name for --out", out.display()))
            })?;
        let parent = match target.parent() {
            Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
            _ => PathBuf::from("."),
        };
        if target.exists() {
            check_is_run_dir(&target, out, kind)?;
        }
        std::fs::create_dir_all(&parent).map_err(|e| io_error("create", &parent, e))?;
        let lock_path = parent.join(format!(".{name}.lock"));
        let lock = std::fs::OpenOptions::new()
            .create(true)
            .truncate(false)
            .write(true)
            .open(&lock_path)
            .map_err(|e| io_error("open", &lock_path, e))?;
        lock.lock_exclusive()
            .map_err(|e| io_error("lock", &lock_path, e))?;
        // Under the lock no other run is staging or swapping: every directory beside `target`
        // with the prefix is a leftover of a killed run. A previous directory set aside by a
        // swap killed between its two renames is the only copy: it goes back first.
        let leftovers: Vec<PathBuf> = std::fs::read_dir(&parent)
            .map(|entries| {
                entries
                    .flatten()
                    .filter(|e| {
                        e.file_name()
                            .to_string_lossy()
                            .starts_with(&leftover_prefix(&name))
                    })
                    .map(|e| e.path())
                    .collect()
            })
            .unwrap_or_default();
        if std::fs::symlink_metadata(&target).is_err() {
            let set_aside = leftovers.iter().find(|p| {
                p.file_name()
                    .is_some_and(|n| n.to_string_lossy().starts_with(&old_prefix(&name)))
            });
            if let Some(old) = set_aside {
                std::fs::rename(old, &target).map_err(|e| io_error("restore", old, e))?;
                eprintln!(
                    "note: {}: put back the previous outputs, which a run killed while replacing \
                     them had left in {}",
                    out.display(),
                    old.display()
                );
                check_is_run_dir(&target, out, kind)?;
            }
        }
        for p in leftovers.iter().filter(|p| p.exists()) {
            let _ = std::fs::remove_dir_all(p);
        }
        let staging = tempfile::Builder::new()
            .prefix(&leftover_prefix(&name))
            .tempdir_in(&parent)
            .map_err(|e| io_error("create a directory in", &parent, e))?;
        Ok(OutDir {
            target,
            shown: out.to_path_buf(),
            staging,
            _lock: lock,
            kind,
        })
    }

    /// Where the files are written before the swap.
    pub fn path(&self) -> &Path {
        self.staging.path()
    }

    /// The final path of a file written into [`OutDir::path`], as `--out` was given.
    pub fn final_path(&self, staged: &Path) -> PathBuf {
        staged
            .file_name()
            .map_or_else(|| self.shown.clone(), |n| self.shown.join(n))
    }

    /// Swaps the staged directory in for the target and removes the old one. On Linux the two
    /// directories are exchanged by one `renameat2(RENAME_EXCHANGE)`, so a kill at any moment
    /// leaves the old directory or the new one in place. Elsewhere, or on a filesystem without
    /// the exchange, the old directory is first renamed aside (`.NAME.rocking-old-*`) and the new
    /// one into place; a kill between the two renames leaves the old one aside, and the next run
    /// puts it back before anything else ([`OutDir::begin`]).
    pub fn commit(self) -> Result<(), SceneError> {
        let fail = |e: std::io::Error| {
            SceneError::failure(format!("{}: cannot replace: {e}", self.shown.display()))
        };
        if cfg!(debug_assertions) {
            for e in std::fs::read_dir(self.staging.path()).into_iter().flatten() {
                let n = e.map(|e| e.file_name().to_string_lossy().into_owned());
                let n = n.unwrap_or_default();
                assert!(
                    (self.kind.writes)(&n),
                    "`{}` wrote `{n}`, which is not in its OutKind: the next run would refuse \
                     the directory",
                    self.kind.command
                );
            }
        }
        let had_target = std::fs::symlink_metadata(&self.target).is_ok();
        if had_target {
            check_is_run_dir(&self.target, &self.shown, self.kind)?;
        }
        let staged = self.staging.keep();
        test_hook::crash_point("staged");
        if !had_target {
            return std::fs::rename(&staged, &self.target).map_err(|e| {
                let _ = std::fs::remove_dir_all(&staged);
                fail(e)
            });
        }
        if exchange(&staged, &self.target).map_err(fail)? {
            test_hook::crash_point("swapped");
            // `staged` now holds the previous run's files.
            let _ = std::fs::remove_dir_all(&staged);
            return Ok(());
        }
        let parent = staged.parent().unwrap_or(Path::new("."));
        let name = self
            .target
            .file_name()
            .unwrap_or_default()
            .to_string_lossy();
        // rename() replaces an empty directory: the old run moves into the (empty) `old`.
        let old = tempfile::Builder::new()
            .prefix(&old_prefix(&name))
            .tempdir_in(parent)
            .map_err(fail)?
            .keep();
        if let Err(e) = std::fs::rename(&self.target, &old) {
            let _ = std::fs::remove_dir(&old);
            let _ = std::fs::remove_dir_all(&staged);
            return Err(fail(e));
        }
        test_hook::crash_point("old-moved");
        if let Err(e) = std::fs::rename(&staged, &self.target) {
            // The old directory goes back: never neither.
            let _ = std::fs::rename(&old, &self.target);
            let _ = std::fs::remove_dir_all(&staged);
            return Err(fail(e));
        }
        test_hook::crash_point("swapped");
        let _ = std::fs::remove_dir_all(&old);
        Ok(())
    }
}

/// Exchanges two directories atomically; `Ok(false)` where the system or the filesystem cannot.
#[cfg(target_os = "linux")]
fn exchange(a: &Path, b: &Path) -> std::io::Result<bool> {
    use rustix::fs::{renameat_with, RenameFlags, CWD};
    use rustix::io::Errno;
    if test_hook::forbids_exchange() {
        return Ok(false);
    }
    match renameat_with(CWD, a, CWD, b, RenameFlags::EXCHANGE) {
        Ok(()) => Ok(true),
        Err(Errno::INVAL | Errno::NOSYS | Errno::NOTSUP) => Ok(false),
        Err(e) => Err(e.into()),
    }
}

/// Exchanges two directories atomically; `Ok(false)` where the system or the filesystem cannot.
#[cfg(not(target_os = "linux"))]
fn exchange(_: &Path, _: &Path) -> std::io::Result<bool> {
    Ok(false)
}

/// A test's view of the swap, in debug builds only (the tests' binary): the environment
/// variable `ROCKING_TEST_SWAP` holds `two-renames` (the swap without the atomic exchange) and/or
/// `abort-at=POINT`, which aborts the process at that point of [`OutDir::commit`] (`staged`,
/// `old-moved`, `swapped`) as a SIGKILL would: no destructor runs.
mod test_hook {
    fn words() -> Vec<String> {
        if !cfg!(debug_assertions) {
            return Vec::new();
        }
        std::env::var("ROCKING_TEST_SWAP")
            .map(|v| v.split(',').map(str::to_string).collect())
            .unwrap_or_default()
    }

    pub(super) fn crash_point(point: &str) {
        if words().iter().any(|w| w == &format!("abort-at={point}")) {
            std::process::abort();
        }
    }

    #[cfg_attr(not(target_os = "linux"), allow(dead_code))]
    pub(super) fn forbids_exchange() -> bool {
        words().iter().any(|w| w == "two-renames")
    }
}

/// An existing `--out` must be a directory of the command's outputs only (never a user's folder).
fn check_is_run_dir(target: &Path, shown: &Path, kind: OutKind) -> Result<(), SceneError> {
    if !target.is_dir() {
        return Err(SceneError::input(format!(
            "{}: --out exists and is not a directory",
            shown.display()
        )));
    }
    let entries = std::fs::read_dir(target)
        .map_err(|e| SceneError::failure(format!("{}: cannot read: {e}", shown.display())))?;
    for e in entries.flatten() {
        let n = e.file_name().to_string_lossy().into_owned();
        // `.summary.json.tmp123`: a temporary file an older version left when killed.
        let leftover = n
            .strip_prefix('.')
            .and_then(|m| m.rsplit_once(".tmp"))
            .is_some_and(|(f, _)| (kind.writes)(f));
        if !(kind.writes)(&n) && !leftover {
            return Err(SceneError::input(format!(
                "{}: --out holds `{n}`, which `{}` does not write; the run replaces the \
                 whole directory, so give an --out that holds only a previous run's outputs",
                shown.display(),
                kind.command
            )));
        }
    }
    Ok(())
}
