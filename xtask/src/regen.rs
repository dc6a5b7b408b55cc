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
#[derive(Debug, Default, Clone, PartialEq, Eq)]
pub struct Options {
    /// Write nothing; report differences and fail if there are any.
    pub check: bool,
    /// Render the checked-in `generated/ir` instead of deriving afresh.
    pub skip_derive: bool,
    /// Derive only these variants (`--only a,b`; `ground` is the ground's IR) and render them
    /// with the checked-in IR of all others, which is kept, as is `docs/errata.md`.
    pub only: Option<Vec<String>>,
}

impl Options {
    /// Parses the arguments following `regen`.
    pub fn parse(args: &[String]) -> Result<Options, String> {
        let mut opts = Options::default();
        let mut args = args.iter();
        while let Some(arg) = args.next() {
            match arg.as_str() {
                "--check" => opts.check = true,
                "--skip-derive" => opts.skip_derive = true,
                "--only" => {
                    let value = args.next().filter(|v| !v.starts_with('-')).ok_or(
                        "--only needs a comma-separated list of variant names (--only full,rigid)",
                    )?;
                    if opts.only.is_some() {
                        return Err("--only given twice: name all variants in one list".into());
                    }
                    opts.only = Some(parse_names(value)?);
                }
                other => return Err(format!("unknown argument {other:?} for regen")),
            }
        }
        if opts.skip_derive && opts.only.is_some() {
            let why = "--only derives the named variants, --skip-derive derives none";
            return Err(format!(
                "--only cannot be combined with --skip-derive: {why}"
            ));
        }
        Ok(opts)
    }
}

/// The names of `--only a,b`, without repeats, in their order.
fn parse_names(value: &str) -> Result<Vec<String>, String> {
    let mut names: Vec<String> = Vec::new();
    for name in value.split(',') {
        if name.trim().is_empty() {
            return Err(format!("--only {value:?}: empty variant name"));
        }
        if !names.iter().any(|n| n == name) {
            names.push(name.to_string());
        }
    }
    Ok(names)
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

/// Runs the derivation into `out` (which receives `ir/*.json` and, unless `only` names the
/// variants to derive, `errata.md`).
fn derive(root: &Path, python: &Path, out: &Path, only: Option<&[String]>) -> Result<()> {
    let mut cmd = Command::new(python);
    cmd.args(["-m", "rocking_derive", "--out"]).arg(out);
    let mut shown = format!(
        "{} -m rocking_derive --out {}",
        python.display(),
        out.display()
    );
    if let Some(only) = only {
        let list = only.join(",");
        let _ = write!(shown, " --only {list}");
        cmd.args(["--only", &list]);
    }
    cmd.current_dir(root)
        .env("PYTHONPATH", root.join("derive"))
        .stdin(Stdio::null())
        .stdout(Stdio::inherit())
        .stderr(Stdio::piped());
    println!("xtask: deriving: {shown}");
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
    let mut owned = vec![(KERNELS_DIR, "rs"), (TAYLOR_DIR, "rs")];
    let desired = if opts.skip_derive {
        let ir_dir = root.join(IR_DIR);
        if !ir_dir.is_dir() {
            return Err(format!(
                "{} does not exist: run `cargo xtask regen` without --skip-derive",
                ir_dir.display()
            )
            .into());
        }
        rendered(&ir_dir)?
    } else {
        let python = crate::venv::ensure(root)?;
        let tmp = tempfile::Builder::new()
            .prefix("rocking-derive-")
            .tempdir()?;
        derive(root, &python, tmp.path(), opts.only.as_deref())?;
        owned.push((IR_DIR, "json"));
        derived_files(root, tmp.path(), opts.only.as_deref())?
    };
    Ok((desired, owned))
}

/// Every file rendered from the IR of `ir_dir`.
fn rendered(ir_dir: &Path) -> Result<Files> {
    Ok(render_all(ir_dir)?
        .into_iter()
        .map(|(path, text)| (path, text.into_bytes()))
        .collect())
}

/// The wanted files of a derivation into `out`: its IR, its errata and everything rendered from
/// the IR. With `only` (the variants it derived), the IR of `out` is first completed with the
/// checked-in IR of `root` ([`add_checked_in_ir`]), and the errata are not wanted (the
/// checked-in `docs/errata.md` stays).
fn derived_files(root: &Path, out: &Path, only: Option<&[String]>) -> Result<Files> {
    let ir_dir = out.join("ir");
    if let Some(only) = only {
        add_checked_in_ir(root, &ir_dir, only)?;
    }
    let mut desired = Files::new();
    for path in list_owned(out, "ir", "json")? {
        let name = path.trim_start_matches("ir/");
        let bytes = std::fs::read(out.join(&path))?;
        desired.insert(format!("{IR_DIR}/{name}"), bytes);
    }
    if desired.is_empty() {
        return Err(format!("the derivation wrote no IR files to {}", ir_dir.display()).into());
    }
    if let Some(ground) = read_opt(&ir_dir.join("ground").join("ground.json"))? {
        desired.insert(GROUND_IR.to_string(), ground);
    }
    if only.is_none() {
        if let Some(errata) = read_opt(&out.join("errata.md"))? {
            desired.insert(ERRATA.to_string(), errata);
        }
    }
    desired.extend(rendered(&ir_dir)?);
    Ok(desired)
}

/// Completes `ir_dir`, where the derivation wrote the IR of the variants `only` (`ground`: the
/// ground's), with the checked-in IR under `root` of every other variant and of the ground, so
/// that everything is rendered and no checked-in IR file looks stale. Fails when the IR of a
/// named variant is missing.
fn add_checked_in_ir(root: &Path, ir_dir: &Path, only: &[String]) -> Result<()> {
    let named = |name: &str| only.iter().any(|n| n == name);
    for name in only {
        let path = if name == "ground" {
            ir_dir.join("ground").join("ground.json")
        } else {
            ir_dir.join(format!("{name}.json"))
        };
        if !path.is_file() {
            return Err(format!(
                "the derivation wrote no IR for `{name}` ({})",
                path.display()
            )
            .into());
        }
    }
    let mut kept = 0;
    for path in list_owned(root, IR_DIR, "json")? {
        let file = &path[IR_DIR.len() + 1..];
        if !named(file.trim_end_matches(".json")) {
            let to = ir_dir.join(file);
            std::fs::copy(root.join(&path), &to).map_err(|e| format!("{}: {e}", to.display()))?;
            kept += 1;
        }
    }
    if !named("ground") {
        if let Some(ground) = read_opt(&root.join(GROUND_IR))? {
            let dir = ir_dir.join("ground");
            std::fs::create_dir_all(&dir).map_err(|e| format!("{}: {e}", dir.display()))?;
            std::fs::write(dir.join("ground.json"), ground)?;
            kept += 1;
        }
    }
    println!(
        "xtask: derived {}; rendering every file with the checked-in IR of {kept} other(s)",
        only.join(", ")
    );
    Ok(())
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
            ..Options::default()
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
            ..Options::default()
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

    /// `--only`: a derivation of `ops` alone (here its checked-in IR with one byte more) is
    /// rendered with the checked-in IR of `rigid_block`, which is neither stale nor rewritten, and
    /// its errata are not wanted; a named variant the derivation did not write is an error.
    #[test]
    fn only_renders_the_derived_variants_with_the_checked_in_ir_of_the_others() {
        let tmp = fixture_root();
        let root = tmp.path();
        let skip = Options {
            skip_derive: true,
            ..Options::default()
        };
        let (desired, owned) = desired_files(root, &skip).unwrap();
        apply(root, &changes(root, &desired, &owned).unwrap()).unwrap();

        let out = tempfile::tempdir().unwrap();
        std::fs::create_dir_all(out.path().join("ir")).unwrap();
        let mut ops = std::fs::read(root.join(IR_DIR).join("ops.json")).unwrap();
        ops.push(b'\n');
        std::fs::write(out.path().join("ir/ops.json"), &ops).unwrap();
        std::fs::write(out.path().join("errata.md"), "not wanted").unwrap();
        let only = ["ops".to_string()];
        let desired = derived_files(root, out.path(), Some(&only)).unwrap();
        assert!(!desired.contains_key(ERRATA));
        let owned = [(KERNELS_DIR, "rs"), (TAYLOR_DIR, "rs"), (IR_DIR, "json")];
        let found = changes(root, &desired, &owned).unwrap();
        let kinds: Vec<(&str, &str)> = found.iter().map(|c| (c.path.as_str(), c.kind())).collect();
        assert_eq!(kinds, [("generated/ir/ops.json", "changed")]);
        assert_eq!(found[0].new.as_deref(), Some(ops.as_slice()));
        assert!(desired.contains_key("generated/src/kernels/rigid_block.rs"));

        let out = tempfile::tempdir().unwrap();
        std::fs::create_dir_all(out.path().join("ir")).unwrap();
        let only = ["nosuch".to_string()];
        let err = derived_files(root, out.path(), Some(&only)).unwrap_err();
        assert!(err.to_string().contains("`nosuch`"), "{err}");
    }

    #[test]
    fn options() {
        let args = |v: &[&str]| v.iter().map(ToString::to_string).collect::<Vec<_>>();
        let parse = |v: &[&str]| Options::parse(&args(v));
        assert_eq!(
            parse(&["--check", "--skip-derive"]).unwrap(),
            Options {
                check: true,
                skip_derive: true,
                only: None,
            }
        );
        assert_eq!(
            parse(&["--only", "a,b,a", "--check"]).unwrap(),
            Options {
                check: true,
                skip_derive: false,
                only: Some(args(&["a", "b"])),
            }
        );
        assert!(parse(&["--frobnicate"]).is_err());
        for wrong in [
            &["--only"][..],
            &["--only", "--check"],
            &["--only", ""],
            &["--only", "a,,b"],
            &["--only", "a,"],
            &["--only", "a", "--only", "b"],
        ] {
            assert!(parse(wrong).is_err(), "{wrong:?}");
        }
        let err = parse(&["--only", "a", "--skip-derive"]).unwrap_err();
        assert!(err.contains("--skip-derive"), "{err}");
    }
}
