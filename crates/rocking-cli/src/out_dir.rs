//! Outputs: atomic file writes and a command's output directory, built aside and swapped in
//! whole; the summary, history and event tables themselves come from `rocking_study::report`
//! (shared with the Python package).

use std::path::{Path, PathBuf};

use rocking_plot::figure as plot;

use crate::error::CliError;
use rocking_scene::SceneError;

pub use rocking_plot::figure::write_atomic;

/// What an output directory holds: the files its command writes, and the command's name. An
/// existing directory holding anything else is not replaced (it is not this command's).
#[derive(Clone, Copy)]
pub struct OutKind {
    /// Whether a file of this name is one the command may write (all of them: a command rewrites
    /// its own previous outputs, whichever options wrote them).
    pub writes: fn(&str) -> bool,
    /// The command, for messages.
    pub command: &'static str,
    /// Whether the previous directory's files that this run does not rewrite stay (`figure`:
    /// each run adds its figures to a folder of figures); otherwise the run's files replace the
    /// directory's whole content.
    pub keeps_others: bool,
}

/// The outputs of `rocking run` (with --animate, plots in every format).
pub const RUN_OUT: OutKind = OutKind {
    writes: |n| {
        ["summary.json", "history.csv", "events.csv", "animation.gif"].contains(&n)
            || plot::is_figure_file(n, "plot")
    },
    command: "rocking run",
    keeps_others: false,
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
    keeps_others: false,
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
    keeps_others: false,
};

/// The outputs of `rocking figure`: each figure file's SVG, PNG and PDF, named after the file.
/// A run replaces the figures it draws, all three formats together, and keeps the others.
pub const FIGURE_OUT: OutKind = OutKind {
    writes: |n| {
        let caption = format!(".{}", plot::CAPTION_EXT);
        n.strip_suffix(caption.as_str())
            .or_else(|| n.rsplit_once('.').map(|(stem, _)| stem))
            .is_some_and(|stem| !stem.is_empty() && plot::is_figure_file(n, stem))
    },
    command: "rocking figure",
    keeps_others: true,
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
    _lock: Lock,
    kind: OutKind,
}

/// The lock beside `--out`, held while a run stages and swaps, and removed when released: the
/// file is deleted while still locked, and a run that locked a file no longer at its path
/// (deleted by the run before it) opens the path again. So no lock file stays behind.
struct Lock {
    _file: std::fs::File,
    path: PathBuf,
}

impl Lock {
    fn acquire(path: &Path) -> Result<Lock, CliError> {
        use fs4::fs_std::FileExt as _;
        loop {
            let file = std::fs::OpenOptions::new()
                .create(true)
                .truncate(false)
                .write(true)
                .open(path)
                .map_err(|e| io_error("open", path, e))?;
            file.lock_exclusive()
                .map_err(|e| io_error("lock", path, e))?;
            if still_at(&file, path) {
                return Ok(Lock {
                    _file: file,
                    path: path.to_path_buf(),
                });
            }
        }
    }
}

/// Whether the open `file` is still the one at `path` (a released lock's file is deleted).
#[cfg(unix)]
fn still_at(file: &std::fs::File, path: &Path) -> bool {
    use std::os::unix::fs::MetadataExt as _;
    match (file.metadata(), std::fs::metadata(path)) {
        (Ok(a), Ok(b)) => (a.dev(), a.ino()) == (b.dev(), b.ino()),
        _ => false,
    }
}

/// Elsewhere a lock file is never deleted ([`Lock`]'s drop), so the one locked is the one there.
#[cfg(not(unix))]
fn still_at(_: &std::fs::File, _: &Path) -> bool {
    true
}

impl Drop for Lock {
    fn drop(&mut self) {
        // `self._file` is closed (unlocked) after this, once the path is gone.
        if cfg!(unix) {
            let _ = std::fs::remove_file(&self.path);
        }
    }
}

/// The longest `--out` name used as is in the names of the lock and the staging directories
/// beside it (`.NAME.rocking-old-XXXXXX` adds 21 bytes; a file name has at most 255).
const KEY_BYTES: usize = 200;

/// The part of the lock's and staging directories' names that stands for `name`: the name, or
/// for a longer one its first bytes and a digest of the whole, so that they never grow past
/// what the file system allows.
fn sibling_key(name: &str) -> String {
    if name.len() <= KEY_BYTES {
        return name.to_string();
    }
    let mut end = KEY_BYTES - 17;
    while !name.is_char_boundary(end) {
        end -= 1;
    }
    format!(
        "{}~{:016x}",
        &name[..end],
        rocking_spectra::fnv1a(name.as_bytes())
    )
}

fn io_error(what: &'static str, p: &Path, e: std::io::Error) -> CliError {
    CliError::io(what, p, e)
}

/// The directory `--out` names: itself, or where it links to. A link to nowhere is refused
/// (there is no directory to replace, and creating one through the link is not what was asked).
fn resolve(out: &Path) -> Result<PathBuf, CliError> {
    match std::fs::symlink_metadata(out) {
        Ok(m) if m.file_type().is_symlink() => std::fs::canonicalize(out).map_err(|e| {
            let to = std::fs::read_link(out).unwrap_or_default();
            SceneError::input(format!(
                "{}: --out is a symbolic link to {}, which cannot be used ({e}); give a \
                 directory, or a link to one",
                out.display(),
                to.display()
            ))
            .into()
        }),
        _ => Ok(out.to_path_buf()),
    }
}

/// `.NAME.rocking-`: the prefix of the staging and set-aside directories beside `NAME`.
fn leftover_prefix(name: &str) -> String {
    format!(".{}.rocking-", sibling_key(name))
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
    pub fn begin(out: &Path, kind: OutKind) -> Result<OutDir, CliError> {
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
        let lock = Lock::acquire(&parent.join(format!(".{}.lock", sibling_key(&name))))?;
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
    pub fn commit(self) -> Result<(), CliError> {
        let fail = |e: std::io::Error| CliError::io("replace", &self.shown, e);
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
            if self.kind.keeps_others {
                self.carry_over().map_err(fail)?;
            }
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

impl OutDir {
    /// Copies (links, where it can) into the staging directory the previous directory's files
    /// this run does not rewrite, so that the swap keeps them ([`OutKind::keeps_others`]).
    fn carry_over(&self) -> std::io::Result<()> {
        for e in std::fs::read_dir(&self.target)? {
            let e = e?;
            let n = e.file_name();
            let to = self.staging.path().join(&n);
            if !(self.kind.writes)(&n.to_string_lossy()) || to.exists() {
                continue;
            }
            if std::fs::hard_link(e.path(), &to).is_err() {
                std::fs::copy(e.path(), &to)?;
            }
        }
        Ok(())
    }
}

/// `--out` named an existing file that is not a directory: the one message of every command.
pub fn refuse_a_file(out: &Path) -> Result<(), CliError> {
    match std::fs::metadata(out) {
        Ok(m) if !m.is_dir() => Err(not_a_directory(out).into()),
        _ => Ok(()),
    }
}

fn not_a_directory(shown: &Path) -> SceneError {
    SceneError::input(format!(
        "{}: --out exists and is not a directory",
        shown.display()
    ))
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
fn check_is_run_dir(target: &Path, shown: &Path, kind: OutKind) -> Result<(), CliError> {
    if !target.is_dir() {
        return Err(not_a_directory(shown).into());
    }
    let entries = std::fs::read_dir(target).map_err(|e| CliError::io("read", shown, e))?;
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
            ))
            .into());
        }
    }
    Ok(())
}
