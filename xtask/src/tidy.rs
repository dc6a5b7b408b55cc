//! Tidy: the layout rules of issue 43, kept true by tests (rust-analyzer's `tidy.rs` pattern).
//!
//! Over the hand-written Rust sources (`crates/*/src`, `xtask/src`, the generated crate's files
//! without the `@generated` mark), each file read up to its test module:
//!
//! - no file over [`MAX_LINES`] lines without a reason in [`LONG_FILES`] (at most
//!   [`MAX_LONG_FILES`] of them, none over [`HARD_MAX`]);
//! - no import circle between files of a crate (a module may use its own submodules: declaring
//!   them is not an import);
//! - no error variant in a library that carries only a `String`;
//! - no command-line flag (`--out`, `--set`, …) in a library's messages: the flags are the CLI's.
//!
//! What breaks a rule today is listed in the `PENDING_*` tables, each entry with its current
//! size. The tables may only shrink: a listed file that grows, a new entry, or an entry whose
//! defect is gone (remove it) fails the tests.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// The largest hand-written source file, in lines before its test module.
const MAX_LINES: usize = 600;
/// No file above this, whatever the reason.
const HARD_MAX: usize = 900;
/// At most this many files above [`MAX_LINES`], each with its reason.
const MAX_LONG_FILES: usize = 4;

/// Files allowed above [`MAX_LINES`], their ceiling, and why they are one concept.
const LONG_FILES: &[(&str, usize, &str)] = &[];

/// Files issue 43 still has to split, with the length they may not exceed.
const PENDING_SPLITS: &[(&str, usize)] = &[];

/// Import circles issue 43 still has to open, each as its files in sorted order.
const PENDING_CIRCLES: &[&[&str]] = &[];

/// String-only error variants still to be typed: (file, variant).
const PENDING_STRING_ERRORS: &[(&str, &str)] = &[];

/// Library files whose messages still name a CLI flag: (file, flag).
const PENDING_FLAGS: &[(&str, &str)] = &[];

/// A hand-written source file: its path from the root, its text before the test module, and
/// whether it belongs to a library crate.
struct Source {
    path: String,
    code: String,
    library: bool,
    /// The crate's directory (`crates/rocking`, `xtask`, `generated`).
    krate: String,
}

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("xtask sits in the workspace")
        .to_path_buf()
}

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    let mut entries: Vec<PathBuf> = entries.flatten().map(|e| e.path()).collect();
    entries.sort();
    for p in entries {
        if p.is_dir() {
            rust_files(&p, out);
        } else if p.extension().is_some_and(|e| e == "rs") {
            out.push(p);
        }
    }
}

/// The text before the file's `#[cfg(test)]` module.
fn before_tests(text: &str) -> String {
    let mut code = String::new();
    for line in text.lines() {
        if line.starts_with("#[cfg(test)]") {
            break;
        }
        code.push_str(line);
        code.push('\n');
    }
    code
}

fn sources() -> Vec<Source> {
    let root = root();
    let mut crates: Vec<PathBuf> = std::fs::read_dir(root.join("crates"))
        .expect("crates/")
        .flatten()
        .map(|e| e.path())
        .collect();
    crates.sort();
    crates.push(root.join("xtask"));
    crates.push(root.join("generated"));
    let mut out = Vec::new();
    for krate in crates {
        let library = krate.join("src/lib.rs").exists();
        let mut files = Vec::new();
        rust_files(&krate.join("src"), &mut files);
        for file in files {
            let text = std::fs::read_to_string(&file).expect("readable source");
            if text.lines().take(3).any(|l| l.contains("@generated")) {
                continue;
            }
            let rel = |p: &Path| p.strip_prefix(&root).unwrap().display().to_string();
            out.push(Source {
                path: rel(&file),
                code: before_tests(&text),
                library,
                krate: rel(&krate),
            });
        }
    }
    assert!(
        out.len() > 50,
        "the sources are found ({} files)",
        out.len()
    );
    out
}

/// The rule of a ratchet table: what is found equals what is listed.
fn ratchet<T: Ord + std::fmt::Debug + Clone>(rule: &str, found: &[T], listed: &[T]) {
    let found: BTreeSet<T> = found.iter().cloned().collect();
    let listed: BTreeSet<T> = listed.iter().cloned().collect();
    let new: Vec<_> = found.difference(&listed).collect();
    let gone: Vec<_> = listed.difference(&found).collect();
    assert!(
        new.is_empty() && gone.is_empty(),
        "{rule}: new {new:?} (fix them); gone {gone:?} (remove them from the table in xtask/src/tidy.rs)"
    );
}

#[test]
fn files_stay_short() {
    assert!(LONG_FILES.len() <= MAX_LONG_FILES);
    let mut over = Vec::new();
    for s in sources() {
        let lines = s.code.lines().count();
        if lines <= MAX_LINES {
            continue;
        }
        let ceiling = LONG_FILES
            .iter()
            .map(|&(p, n, _)| (p, n))
            .chain(PENDING_SPLITS.iter().copied())
            .find(|&(p, _)| p == s.path)
            .map(|(_, n)| n);
        match ceiling {
            None => panic!(
                "{}: {lines} lines before its tests, over {MAX_LINES}: split it by concept",
                s.path
            ),
            Some(n) => assert!(
                lines <= n,
                "{}: {lines} lines, more than the {n} it is held to",
                s.path
            ),
        }
        over.push(s.path);
    }
    for &(p, n, why) in LONG_FILES {
        assert!(n <= HARD_MAX && !why.is_empty(), "{p}: {n} lines, {why:?}");
    }
    let listed: Vec<String> = LONG_FILES
        .iter()
        .map(|e| e.0)
        .chain(PENDING_SPLITS.iter().map(|e| e.0))
        .map(String::from)
        .collect();
    ratchet("files over the limit", &over, &listed);
}

/// The module a file is, `a::b` for `src/a/b.rs` and `src/a/b/mod.rs`, `` for the crate root.
fn module_of(krate: &str, path: &str) -> String {
    let rel = path
        .strip_prefix(&format!("{krate}/src/"))
        .expect("a file of its crate");
    let rel = rel.strip_suffix(".rs").unwrap();
    let rel = rel.strip_suffix("/mod").unwrap_or(rel);
    match rel {
        "lib" | "main" => String::new(),
        r => r.replace('/', "::"),
    }
}

/// Every path a file names from its crate (`crate::…`, `super::…`, `self::…`, in `use`
/// declarations with their braces and inline), resolved to absolute module paths.
fn named_paths(code: &str, module: &str) -> Vec<Vec<String>> {
    let code: String = code
        .lines()
        .map(|l| l.split("//").next().unwrap_or(""))
        .collect::<Vec<_>>()
        .join("\n");
    let mut out = Vec::new();
    let bytes = code.as_bytes();
    let ident = |c: u8| c.is_ascii_alphanumeric() || c == b'_';
    for start in ["crate::", "super::", "self::"] {
        let mut from = 0;
        while let Some(i) = code[from..].find(start) {
            let at = from + i;
            from = at + start.len();
            if at > 0 && (ident(bytes[at - 1]) || bytes[at - 1] == b':') {
                continue;
            }
            let mut base: Vec<String> = match start {
                "crate::" => Vec::new(),
                _ => module
                    .split("::")
                    .filter(|s| !s.is_empty())
                    .map(String::from)
                    .collect(),
            };
            let mut rest = &code[at..];
            // Leading `super::` segments climb; the first `self::` stays.
            loop {
                if let Some(r) = rest.strip_prefix("super::") {
                    base.pop();
                    rest = r;
                } else if let Some(r) = rest.strip_prefix("self::") {
                    rest = r;
                } else if let Some(r) = rest.strip_prefix("crate::") {
                    rest = r;
                } else {
                    break;
                }
            }
            expand(rest, &base, &mut out);
        }
    }
    out
}

/// The paths of `rest` (segments, or a brace group of them) below `base`.
fn expand(rest: &str, base: &[String], out: &mut Vec<Vec<String>>) {
    let mut path = base.to_vec();
    let mut s = rest;
    loop {
        if let Some(inner) = s.strip_prefix('{') {
            let mut depth = 1;
            let mut end = 0;
            for (i, c) in inner.char_indices() {
                match c {
                    '{' => depth += 1,
                    '}' => depth -= 1,
                    _ => {}
                }
                if depth == 0 {
                    end = i;
                    break;
                }
            }
            let mut depth = 0;
            let mut piece = 0;
            let group = &inner[..end];
            for (i, c) in group.char_indices().chain([(group.len(), ',')]) {
                match c {
                    '{' => depth += 1,
                    '}' => depth -= 1,
                    ',' if depth == 0 => {
                        expand(group[piece..i].trim(), &path, out);
                        piece = i + 1;
                    }
                    _ => {}
                }
            }
            return;
        }
        let len = s
            .find(|c: char| !(c.is_alphanumeric() || c == '_'))
            .unwrap_or(s.len());
        if len == 0 {
            break;
        }
        path.push(s[..len].to_string());
        match s[len..].strip_prefix("::") {
            Some(r) => s = r,
            None => break,
        }
    }
    out.push(path);
}

/// The import graph of a crate's files: file → files it names, leaving out a module's own
/// submodules.
fn import_graph(files: &[&Source]) -> BTreeMap<String, BTreeSet<String>> {
    let modules: BTreeMap<String, String> = files
        .iter()
        .map(|s| (module_of(&s.krate, &s.path), s.path.clone()))
        .collect();
    let mut graph = BTreeMap::new();
    for s in files {
        let me = module_of(&s.krate, &s.path);
        let mut edges = BTreeSet::new();
        for path in named_paths(&s.code, &me) {
            // The longest prefix of the path that is a file's module.
            let target = (0..=path.len())
                .rev()
                .map(|n| path[..n].join("::"))
                .find(|m| modules.contains_key(m));
            let Some(target) = target else { continue };
            let own_submodule = if me.is_empty() {
                !target.is_empty()
            } else {
                target.starts_with(&format!("{me}::"))
            };
            if target != me && !own_submodule {
                edges.insert(modules[&target].clone());
            }
        }
        graph.insert(s.path.clone(), edges);
    }
    graph
}

/// The cycles of a graph: its strongly connected components of more than one file.
fn circles(graph: &BTreeMap<String, BTreeSet<String>>) -> Vec<Vec<String>> {
    let reach = |from: &String| {
        let mut seen = BTreeSet::new();
        let mut stack = vec![from.clone()];
        while let Some(n) = stack.pop() {
            for m in graph.get(&n).into_iter().flatten() {
                if seen.insert(m.clone()) {
                    stack.push(m.clone());
                }
            }
        }
        seen
    };
    let reached: BTreeMap<&String, BTreeSet<String>> =
        graph.keys().map(|k| (k, reach(k))).collect();
    let mut out: BTreeSet<Vec<String>> = BTreeSet::new();
    for a in graph.keys() {
        let component: Vec<String> = graph
            .keys()
            .filter(|b| *b == a || (reached[a].contains(*b) && reached[*b].contains(a)))
            .cloned()
            .collect();
        if component.len() > 1 {
            out.insert(component);
        }
    }
    out.into_iter().collect()
}

#[test]
fn no_import_circles() {
    let all = sources();
    let mut found = Vec::new();
    let crates: BTreeSet<&str> = all.iter().map(|s| s.krate.as_str()).collect();
    for krate in crates {
        let files: Vec<&Source> = all.iter().filter(|s| s.krate == krate).collect();
        found.extend(circles(&import_graph(&files)));
    }
    let listed: Vec<Vec<String>> = PENDING_CIRCLES
        .iter()
        .map(|c| c.iter().map(|s| s.to_string()).collect())
        .collect();
    ratchet("import circles", &found, &listed);
}

#[test]
fn no_string_only_error_variants_in_libraries() {
    let mut found = Vec::new();
    for s in sources().iter().filter(|s| s.library) {
        let mut in_error = false;
        for line in s.code.lines() {
            let t = line.trim();
            if t.starts_with("pub enum ") || t.starts_with("enum ") {
                in_error = t
                    .split_whitespace()
                    .nth(if t.starts_with("pub") { 2 } else { 1 })
                    .is_some_and(|name| name.trim_end_matches('{').trim().ends_with("Error"));
            } else if in_error && t == "}" {
                in_error = false;
            } else if in_error {
                if let Some(variant) = t.strip_suffix("(String),") {
                    found.push((s.path.clone(), variant.to_string()));
                }
            }
        }
    }
    let listed: Vec<(String, String)> = PENDING_STRING_ERRORS
        .iter()
        .map(|&(p, v)| (p.to_string(), v.to_string()))
        .collect();
    ratchet("string-only error variants", &found, &listed);
}

/// The flags the command defines, as its messages would write them.
const FLAGS: &[&str] = &[
    "--out",
    "--set",
    "--axis",
    "--records",
    "--scales",
    "--shard",
    "--threads",
    "--quiet",
    "--json",
    "--animate",
    "--draft",
    "--check",
    "--update",
];

#[test]
fn no_cli_flags_in_library_messages() {
    let mut found = BTreeSet::new();
    for s in sources().iter().filter(|s| s.library) {
        for line in s.code.lines() {
            let code = line.trim_start();
            if code.starts_with("//") {
                continue;
            }
            // Only inside string literals: the text between quotes.
            for (i, piece) in code.split('"').enumerate() {
                if i % 2 == 0 {
                    continue;
                }
                for flag in FLAGS {
                    let mut at = 0;
                    while let Some(k) = piece[at..].find(flag) {
                        let end = at + k + flag.len();
                        let next = piece[end..].chars().next();
                        if !next.is_some_and(|c| c.is_alphanumeric() || c == '-' || c == '_') {
                            found.insert((s.path.clone(), flag.to_string()));
                        }
                        at = end;
                    }
                }
            }
        }
    }
    let found: Vec<_> = found.into_iter().collect();
    let listed: Vec<(String, String)> = PENDING_FLAGS
        .iter()
        .map(|&(p, f)| (p.to_string(), f.to_string()))
        .collect();
    ratchet("CLI flags in library messages", &found, &listed);
}

/// The rules catch what they are meant to: a circle of two sibling files and a longer one, a
/// module using its own submodule (not a circle), braces in `use`.
#[test]
fn the_import_graph_finds_circles_and_only_them() {
    let file = |path: &str, code: &str| Source {
        path: format!("crates/x/src/{path}"),
        code: code.to_string(),
        library: true,
        krate: "crates/x".to_string(),
    };
    let files = [
        file("lib.rs", "mod a; mod b; mod c; mod d; use crate::d::Thing;"),
        file("a.rs", "use crate::{b::X, c};"),
        file("b.rs", "use super::c::Y;"),
        file("c.rs", "fn f() { crate::a::g() }"),
        file("d/mod.rs", "mod e; use self::e::Z; use e::W;"),
        file("d/e.rs", "use super::super::a;"),
    ];
    let refs: Vec<&Source> = files.iter().collect();
    let found = circles(&import_graph(&refs));
    let abc: Vec<String> = ["a.rs", "b.rs", "c.rs"]
        .iter()
        .map(|f| format!("crates/x/src/{f}"))
        .collect();
    assert_eq!(found, vec![abc]);
}
