//! Outputs: atomic file writes and the run's output directory; the summary, history and event
//! tables themselves come from `rocking_study::run_report` (shared with the Python package).

use std::path::{Path, PathBuf};

use rocking_scene::SceneError;

/// Writes `bytes` to `path` atomically ([`rocking_spectra::write_atomic`]).
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<(), SceneError> {
    rocking_spectra::write_atomic(path, bytes)
        .map_err(|e| SceneError::failure(format!("{}: cannot write: {e}", path.display())))
}

/// The files `rocking run` writes; an existing output directory holding anything else is not
/// replaced (it is not a run's directory).
pub const RUN_FILES: [&str; 6] = [
    "summary.json",
    "history.csv",
    "events.csv",
    "plot.png",
    "plot.svg",
    "plot.pdf",
];

/// The files `rocking ida` writes (its --out is replaced whole like a run's).
pub const IDA_FILES: [&str; 9] = [
    "records.csv",
    "ida.csv",
    "fragility.json",
    "ida.svg",
    "ida.png",
    "ida.pdf",
    "fragility-fit.svg",
    "fragility-fit.png",
    "fragility-fit.pdf",
];

/// The output directory of one run, built aside and swapped in whole: the directory always holds
/// exactly one run's files, whether the run is killed while writing (the old directory stays),
/// runs in parallel into the same `--out` (the last to finish wins, never a mix), or writes fewer
/// files than the previous run (no stale ones). The swap happens under a lock file beside the
/// directory; leftovers of killed runs are removed by the next run.
pub struct OutDir {
    target: PathBuf,
    staging: tempfile::TempDir,
    _lock: std::fs::File,
    kind: OutKind,
}

/// What an output directory holds: the files its command writes, and the command's name.
#[derive(Clone, Copy)]
pub struct OutKind {
    /// Whether a file of this name is one the command writes.
    pub writes: fn(&str) -> bool,
    /// The command, for messages.
    pub command: &'static str,
}

/// The outputs of `rocking run`.
pub const RUN_OUT: OutKind = OutKind {
    writes: |n| RUN_FILES.contains(&n),
    command: "rocking run",
};

/// The outputs of `rocking ida`.
pub const IDA_OUT: OutKind = OutKind {
    writes: |n| IDA_FILES.contains(&n),
    command: "rocking ida",
};

impl OutDir {
    /// Locks `target`'s name, removes what killed runs left, and creates the staging directory.
    pub fn begin(target: &Path) -> Result<OutDir, SceneError> {
        OutDir::begin_for(target, RUN_OUT)
    }

    /// [`OutDir::begin`] for the outputs of another command: an existing `target` may hold only
    /// files that `kind` writes.
    pub fn begin_for(target: &Path, kind: OutKind) -> Result<OutDir, SceneError> {
        use fs4::fs_std::FileExt as _;
        let io = |what: &str, p: &Path, e: std::io::Error| {
            SceneError::failure(format!("{}: cannot {what}: {e}", p.display()))
        };
        let name = target
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .ok_or_else(|| {
                SceneError::input(format!(
                    "{}: not a directory name for --out",
                    target.display()
                ))
            })?;
        let parent = match target.parent() {
            Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
            _ => PathBuf::from("."),
        };
        std::fs::create_dir_all(&parent).map_err(|e| io("create", &parent, e))?;
        if target.exists() {
            check_is_run_dir(target, kind)?;
        }
        let lock_path = parent.join(format!(".{name}.lock"));
        let lock = std::fs::OpenOptions::new()
            .create(true)
            .truncate(false)
            .write(true)
            .open(&lock_path)
            .map_err(|e| io("open", &lock_path, e))?;
        lock.lock_exclusive()
            .map_err(|e| io("lock", &lock_path, e))?;
        // Under the lock no other run is staging: whatever staging directory exists is a
        // leftover of a killed run.
        let prefix = format!(".{name}.rocking-");
        if let Ok(entries) = std::fs::read_dir(&parent) {
            for e in entries.flatten() {
                if e.file_name().to_string_lossy().starts_with(&prefix) {
                    let _ = std::fs::remove_dir_all(e.path());
                }
            }
        }
        let staging = tempfile::Builder::new()
            .prefix(&prefix)
            .tempdir_in(&parent)
            .map_err(|e| io("create a directory in", &parent, e))?;
        Ok(OutDir {
            target: target.to_path_buf(),
            staging,
            _lock: lock,
            kind,
        })
    }

    /// Where the files are written before the swap.
    pub fn path(&self) -> &Path {
        self.staging.path()
    }

    /// The final path of a file written into [`OutDir::path`].
    pub fn final_path(&self, staged: &Path) -> PathBuf {
        staged
            .file_name()
            .map_or_else(|| self.target.clone(), |n| self.target.join(n))
    }

    /// Swaps the staged directory in for the target (the old one is removed).
    pub fn commit(self) -> Result<(), SceneError> {
        let fail = |e: std::io::Error| {
            SceneError::failure(format!("{}: cannot replace: {e}", self.target.display()))
        };
        let parent = self.staging.path().parent().unwrap_or(Path::new("."));
        let old = tempfile::Builder::new()
            .prefix(&format!(
                ".{}.rocking-old-",
                self.target
                    .file_name()
                    .unwrap_or_default()
                    .to_string_lossy()
            ))
            .tempdir_in(parent)
            .map_err(fail)?;
        let had_target = self.target.exists();
        if had_target {
            check_is_run_dir(&self.target, self.kind)?;
            // rename() replaces an empty directory: the old run moves into the (empty) `old`.
            std::fs::rename(&self.target, old.path()).map_err(fail)?;
        }
        let staged = self.staging.keep();
        std::fs::rename(&staged, &self.target).map_err(|e| {
            let _ = std::fs::remove_dir_all(&staged);
            fail(e)
        })?;
        drop(old); // removes the previous run's files
        Ok(())
    }
}

/// An existing `--out` must be a directory of run outputs only (never a user's folder).
fn check_is_run_dir(target: &Path, kind: OutKind) -> Result<(), SceneError> {
    if !target.is_dir() {
        return Err(SceneError::input(format!(
            "{}: --out exists and is not a directory",
            target.display()
        )));
    }
    let entries = std::fs::read_dir(target)
        .map_err(|e| SceneError::failure(format!("{}: cannot read: {e}", target.display())))?;
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
                target.display(),
                kind.command
            )));
        }
    }
    Ok(())
}
