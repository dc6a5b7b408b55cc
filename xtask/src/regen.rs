//! `cargo xtask regen`: derive, render, and write or check the generated files.

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::io::Write as _;
use std::path::Path;
use std::process::{Command, Stdio};

use rocking_codegen::{render_all, GROUND_IR, IR_DIR, KERNELS_DIR, TAYLOR_DIR};

use crate::Result;

/// Where the derivation's errata go, relative to the repository root.
const ERRATA: &str = "docs/errata.md";
/// Lines of diff printed per file before eliding the rest.
const DIFF_LINES_PER_FILE: usize = 200;
/// The final message of a failed `--check`.
pub const STALE_MESSAGE: &str =
    "generated code is stale: run `cargo xtask regen` and commit the result";

/// Command-line options of `regen`.
#[derive(Debug, Default, Clone, Copy, PartialEq, Eq)]
pub struct Options {
    /// Write nothing; report differences and fail if there are any.
    pub check: bool,
    /// Render the checked-in `generated/ir` instead of deriving afresh.
    pub skip_derive: bool,
}

impl Options {
    /// Parses the arguments following `regen`.
    pub fn parse(args: &[String]) -> Result<Options, String> {
        let mut opts = Options::default();
        for arg in args {
            match arg.as_str() {
                "--check" => opts.check = true,
                "--skip-derive" => opts.skip_derive = true,
                other => return Err(format!("unknown argument {other:?} for regen")),
            }
        }
        Ok(opts)
    }
}

/// Wanted file contents keyed by repository-relative path.
pub type Files = BTreeMap<String, Vec<u8>>;
/// `(directory, extension)` pairs whose files `regen` owns.
pub type Owned = Vec<(&'static str, &'static str)>;

/// What has to happen to one owned file.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Change {
    /// Path relative to the repository root, `/`-separated.
    pub path: String,
    /// Current contents (`None`: missing).
    pub old: Option<Vec<u8>>,
    /// Wanted contents (`None`: stale, to be deleted).
    pub new: Option<Vec<u8>>,
}

impl Change {
    fn kind(&self) -> &'static str {
        match (&self.old, &self.new) {
            (None, _) => "missing",
            (_, None) => "stale",
            _ => "changed",
        }
    }
}

/// Runs the derivation into `out` (which receives `ir/*.json` and `errata.md`).
fn derive(root: &Path, python: &Path, out: &Path) -> Result<()> {
    let mut cmd = Command::new(python);
    cmd.args(["-m", "rocking_derive", "--out"])
        .arg(out)
        .current_dir(root)
        .env("PYTHONPATH", root.join("derive"))
        .stdin(Stdio::null())
        .stdout(Stdio::inherit())
        .stderr(Stdio::piped());
    println!(
        "xtask: deriving: {} -m rocking_derive --out {}",
        python.display(),
        out.display()
    );
    let output = cmd
        .output()
        .map_err(|e| format!("cannot run {}: {e}", python.display()))?;
    let stderr = String::from_utf8_lossy(&output.stderr);
    if !output.status.success() {
        return Err(format!(
            "the derivation (python -m rocking_derive) failed with {}:\n{stderr}",
            output.status
        )
        .into());
    }
    if !stderr.trim().is_empty() {
        eprint!("{stderr}");
    }
    Ok(())
}

fn read_opt(path: &Path) -> Result<Option<Vec<u8>>> {
    match std::fs::read(path) {
        Ok(b) => Ok(Some(b)),
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => Ok(None),
        Err(e) => Err(format!("{}: {e}", path.display()).into()),
    }
}

/// Files of `dir` (relative to `root`) with extension `ext`, as `/`-separated
/// paths relative to `root`, sorted.
fn list_owned(root: &Path, dir: &str, ext: &str) -> Result<Vec<String>> {
    let abs = root.join(dir);
    let mut out = Vec::new();
    let entries = match std::fs::read_dir(&abs) {
        Ok(entries) => entries,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(out),
        Err(e) => return Err(format!("{}: {e}", abs.display()).into()),
    };
    for entry in entries {
        let entry = entry.map_err(|e| format!("{}: {e}", abs.display()))?;
        let path = entry.path();
        if path.is_file() && path.extension().is_some_and(|x| x == ext) {
            let name = entry.file_name().to_string_lossy().into_owned();
            out.push(format!("{dir}/{name}"));
        }
    }
    out.sort();
    Ok(out)
}

/// Computes every difference between the wanted files and the working tree.
///
/// `desired` maps repository-relative paths to contents; `owned` lists the
/// `(directory, extension)` pairs whose other files are stale.
pub fn changes(
    root: &Path,
    desired: &BTreeMap<String, Vec<u8>>,
    owned: &[(&str, &str)],
) -> Result<Vec<Change>> {
    let mut out = Vec::new();
    for (path, new) in desired {
        let old = read_opt(&root.join(path))?;
        if old.as_ref() != Some(new) {
            out.push(Change {
                path: path.clone(),
                old,
                new: Some(new.clone()),
            });
        }
    }
    for (dir, ext) in owned {
        for path in list_owned(root, dir, ext)? {
            if !desired.contains_key(&path) {
                let old = read_opt(&root.join(&path))?;
                out.push(Change {
                    path,
                    old,
                    new: None,
                });
            }
        }
    }
    out.sort_by(|a, b| a.path.cmp(&b.path));
    Ok(out)
}

/// A unified diff of one change, at most [`DIFF_LINES_PER_FILE`] lines.
pub fn diff(change: &Change) -> String {
    let old = change
        .old
        .as_deref()
        .map(String::from_utf8_lossy)
        .unwrap_or_default();
    let new = change
        .new
        .as_deref()
        .map(String::from_utf8_lossy)
        .unwrap_or_default();
    let a = if change.old.is_some() {
        format!("a/{}", change.path)
    } else {
        "/dev/null".to_string()
    };
    let b = if change.new.is_some() {
        format!("b/{}", change.path)
    } else {
        "/dev/null".to_string()
    };
    let text = similar::TextDiff::from_lines(old.as_ref(), new.as_ref())
        .unified_diff()
        .context_radius(3)
        .header(&a, &b)
        .to_string();
    let lines: Vec<&str> = text.lines().collect();
    let mut out = String::new();
    for line in lines.iter().take(DIFF_LINES_PER_FILE) {
        out.push_str(line);
        out.push('\n');
    }
    if lines.len() > DIFF_LINES_PER_FILE {
        let _ = writeln!(
            out,
            "... {} more diff lines for {}",
            lines.len() - DIFF_LINES_PER_FILE,
            change.path
        );
    }
    out
}

/// Writes `contents` to `path` atomically (temporary file in the same directory,
/// then rename).
fn write_atomic(path: &Path, contents: &[u8]) -> Result<()> {
    let dir = path
        .parent()
        .ok_or_else(|| format!("{} has no parent directory", path.display()))?;
    std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    let mut tmp =
        tempfile::NamedTempFile::new_in(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    tmp.write_all(contents)
        .and_then(|()| tmp.flush())
        .map_err(|e| format!("{}: {e}", path.display()))?;
    tmp.persist(path)
        .map_err(|e| format!("{}: {}", path.display(), e.error))?;
    Ok(())
}

/// Applies the changes to the working tree.
pub fn apply(root: &Path, changes: &[Change]) -> Result<()> {
    for change in changes {
        let path = root.join(&change.path);
        match &change.new {
            Some(new) => write_atomic(&path, new)?,
            None => {
                std::fs::remove_file(&path).map_err(|e| format!("{}: {e}", path.display()))?;
            }
        }
    }
    Ok(())
}

/// The wanted contents of the owned files, and the owned directories.
pub fn desired_files(root: &Path, opts: &Options) -> Result<(Files, Owned)> {
    let mut desired = BTreeMap::new();
    let mut owned = vec![(KERNELS_DIR, "rs"), (TAYLOR_DIR, "rs")];
    // Keeps the derivation output alive until rendering is done.
    let tmp;
    let ir_dir = if opts.skip_derive {
        root.join(IR_DIR)
    } else {
        let python = crate::venv::ensure(root)?;
        tmp = tempfile::Builder::new()
            .prefix("rocking-derive-")
            .tempdir()?;
        derive(root, &python, tmp.path())?;
        let fresh_ir = tmp.path().join("ir");
        let mut n = 0;
        for path in list_owned(tmp.path(), "ir", "json")? {
            let name = path.trim_start_matches("ir/");
            let bytes = std::fs::read(tmp.path().join(&path))?;
            desired.insert(format!("{IR_DIR}/{name}"), bytes);
            n += 1;
        }
        if n == 0 {
            return Err(
                format!("the derivation wrote no IR files to {}", fresh_ir.display()).into(),
            );
        }
        if let Some(ground) = read_opt(&fresh_ir.join("ground").join("ground.json"))? {
            desired.insert(GROUND_IR.to_string(), ground);
        }
        if let Some(errata) = read_opt(&tmp.path().join("errata.md"))? {
            desired.insert(ERRATA.to_string(), errata);
        }
        owned.push((IR_DIR, "json"));
        fresh_ir
    };
    if !ir_dir.is_dir() {
        return Err(format!(
            "{} does not exist: run `cargo xtask regen` without --skip-derive",
            ir_dir.display()
        )
        .into());
    }
    for (path, text) in render_all(&ir_dir)? {
        desired.insert(path, text.into_bytes());
    }
    Ok((desired, owned))
}

/// What `regen` would change: the number of generated files and their differences from the
/// working tree.
pub struct Freshness {
    /// Number of files `regen` generates.
    pub files: usize,
    /// Every generated file that differs, is missing or is stale.
    pub changes: Vec<Change>,
}

impl std::fmt::Display for Freshness {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        for change in &self.changes {
            writeln!(f, "{}: {}", change.kind(), change.path)?;
            f.write_str(&diff(change))?;
        }
        Ok(())
    }
}

/// The one freshness check of the generated code (rust-analyzer's `ensure_file_contents`):
/// `cargo xtask regen --check` prints it, and the test `checked_in_generated_code_is_fresh`
/// asserts it is empty for the checked-in IR.
pub fn freshness(root: &Path, opts: &Options) -> Result<Freshness> {
    let (desired, owned) = desired_files(root, opts)?;
    let changes = changes(root, &desired, &owned)?;
    Ok(Freshness {
        files: desired.len(),
        changes,
    })
}

/// Runs `regen`.
pub fn run(root: &Path, opts: &Options) -> Result<()> {
    let fresh = freshness(root, opts)?;
    let (files, changes) = (fresh.files, &fresh.changes);
    if opts.check {
        if changes.is_empty() {
            println!("xtask: {files} generated files are up to date");
            return Ok(());
        }
        print!("{fresh}");
        println!("xtask: {} file(s) differ", changes.len());
        return Err(STALE_MESSAGE.into());
    }
    apply(root, changes)?;
    let written = changes.iter().filter(|c| c.new.is_some()).count();
    let removed = changes.len() - written;
    for change in changes {
        let what = match change.kind() {
            "missing" => "created",
            "stale" => "removed",
            _ => "updated",
        };
        println!("xtask: {what} {}", change.path);
    }
    println!(
        "xtask: regen done: {files} files checked, {written} written, {removed} removed, {} unchanged",
        files - written
    );
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The freshness check of `cargo xtask regen --check`, without Python: the checked-in IR
    /// renders to exactly the checked-in kernels. Fails on a hand edit of a generated file, a
    /// template change without `cargo xtask regen`, and a stale module.
    #[test]
    fn checked_in_generated_code_is_fresh() {
        let root = crate::repo_root().unwrap();
        let opts = Options {
            check: true,
            skip_derive: true,
        };
        let fresh = freshness(&root, &opts).unwrap();
        assert!(fresh.files > 2, "no generated files found under {IR_DIR}");
        assert!(fresh.changes.is_empty(), "{fresh}\n{STALE_MESSAGE}");
    }

    fn fixture_root() -> tempfile::TempDir {
        let tmp = tempfile::tempdir().unwrap();
        let fixtures = crate::repo_root()
            .unwrap()
            .join("crates/rocking-codegen/tests/fixtures");
        let ir = tmp.path().join(IR_DIR);
        std::fs::create_dir_all(&ir).unwrap();
        for name in ["ops.json", "rigid_block.json"] {
            std::fs::copy(fixtures.join(name), ir.join(name)).unwrap();
        }
        tmp
    }

    #[test]
    fn apply_then_check_round_trip() {
        let tmp = fixture_root();
        let root = tmp.path();
        let opts = Options {
            check: false,
            skip_derive: true,
        };
        let (desired, owned) = desired_files(root, &opts).unwrap();
        let first = changes(root, &desired, &owned).unwrap();
        assert_eq!(
            first.len(),
            6,
            "mod.rs and two variants are missing, each with its Taylor-mode twin"
        );
        assert!(first.iter().all(|c| c.kind() == "missing"));
        apply(root, &first).unwrap();
        assert!(changes(root, &desired, &owned).unwrap().is_empty());

        // A hand edit and a stale file are both detected and then repaired.
        let ops = root.join(KERNELS_DIR).join("ops.rs");
        let mut text = std::fs::read_to_string(&ops).unwrap();
        text = text.replacen("pub const NAME", "// hand edit\npub const NAME", 1);
        std::fs::write(&ops, text).unwrap();
        std::fs::write(root.join(KERNELS_DIR).join("old.rs"), "// stale\n").unwrap();
        std::fs::write(root.join(KERNELS_DIR).join("notes.txt"), "kept").unwrap();
        let found = changes(root, &desired, &owned).unwrap();
        let kinds: Vec<(&str, &str)> = found.iter().map(|c| (c.path.as_str(), c.kind())).collect();
        assert_eq!(
            kinds,
            [
                ("generated/src/kernels/old.rs", "stale"),
                ("generated/src/kernels/ops.rs", "changed"),
            ]
        );
        let d = diff(&found[1]);
        assert!(d.contains("-// hand edit"), "{d}");
        assert!(diff(&found[0]).contains("+++ /dev/null"));
        apply(root, &found).unwrap();
        assert!(changes(root, &desired, &owned).unwrap().is_empty());
        assert!(root.join(KERNELS_DIR).join("notes.txt").exists());
        assert!(!root.join(KERNELS_DIR).join("old.rs").exists());
    }

    #[test]
    fn options() {
        let args = |v: &[&str]| v.iter().map(ToString::to_string).collect::<Vec<_>>();
        assert_eq!(
            Options::parse(&args(&["--check", "--skip-derive"])).unwrap(),
            Options {
                check: true,
                skip_derive: true
            }
        );
        assert!(Options::parse(&args(&["--frobnicate"])).is_err());
    }
}
