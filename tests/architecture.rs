//! Architecture rules of docs/architecture.md, checked on the source text of `src/`:
//! - no import cycles, between top-level modules and between sibling modules of one folder;
//! - no file over 500 lines and no function over 80 lines.
//!
//! Dependencies are read from `use crate::..`, `use super::..`, inline `crate::a::b` paths and
//! the binary's `brume::a` paths (test modules excluded); an item re-exported by a module's
//! `mod.rs` counts as a dependency on the child module that defines it. Exceptions are listed
//! below, each with its reason; the list may only shrink.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// Dependencies allowed to close a cycle, as (folder, from, to), each with its reason. None.
const CYCLE_ALLOW: &[(&str, &str, &str)] = &[];

/// Files allowed over 500 lines, each with its reason. None.
const LONG_FILES: &[&str] = &[];

/// Functions allowed over 80 lines, as (file, function), each with its reason. None.
const LONG_FNS: &[(&str, &str)] = &[];

const MAX_FILE_LINES: usize = 500;
const MAX_FN_LINES: usize = 80;

fn src() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("src")
}

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for e in std::fs::read_dir(dir).expect("src readable").flatten() {
        let p = e.path();
        if p.is_dir() {
            rust_files(&p, out);
        } else if p.extension().is_some_and(|x| x == "rs") {
            out.push(p);
        }
    }
}

/// Source text with comments, strings and char literals blanked (newlines kept), so that
/// braces and paths are only those of the code.
fn code_only(text: &str) -> String {
    let b = text.as_bytes();
    let mut out = Vec::with_capacity(b.len());
    let mut i = 0;
    let blank = |out: &mut Vec<u8>, c: u8| out.push(if c == b'\n' { b'\n' } else { b' ' });
    while i < b.len() {
        let rest = &b[i..];
        if rest.starts_with(b"//") {
            while i < b.len() && b[i] != b'\n' {
                blank(&mut out, b[i]);
                i += 1;
            }
        } else if rest.starts_with(b"/*") {
            while i < b.len() && !b[i..].starts_with(b"*/") {
                blank(&mut out, b[i]);
                i += 1;
            }
            out.extend_from_slice(b"  ");
            i += 2;
        } else if rest.starts_with(b"r#\"") || rest.starts_with(b"r\"") {
            let hashes = rest[1..].iter().take_while(|c| **c == b'#').count();
            let close: Vec<u8> = std::iter::once(b'"').chain(vec![b'#'; hashes]).collect();
            let start = i + 2 + hashes;
            let end = b[start..]
                .windows(close.len())
                .position(|w| w == close.as_slice())
                .map_or(b.len(), |p| start + p + close.len());
            b[i..end].iter().for_each(|c| blank(&mut out, *c));
            i = end;
        } else if b[i] == b'"' {
            blank(&mut out, b[i]);
            i += 1;
            while i < b.len() && b[i] != b'"' {
                let n = if b[i] == b'\\' { 2 } else { 1 };
                b[i..(i + n).min(b.len())]
                    .iter()
                    .for_each(|c| blank(&mut out, *c));
                i += n;
            }
            out.push(b' ');
            i += 1;
        } else if b[i] == b'\'' && char_literal_len(rest).is_some() {
            let n = char_literal_len(rest).unwrap_or(1);
            out.extend(std::iter::repeat_n(b' ', n));
            i += n;
        } else {
            out.push(b[i]);
            i += 1;
        }
    }
    String::from_utf8_lossy(&out).into_owned()
}

/// Length of a char literal at the start of `s` (`'x'`, `'\n'`, `'\u{..}'`), not a lifetime.
fn char_literal_len(s: &[u8]) -> Option<usize> {
    if s.get(1) == Some(&b'\\') {
        let end = s[2..].iter().position(|c| *c == b'\'')?;
        return Some(end + 3);
    }
    let c = std::str::from_utf8(&s[1..s.len().min(6)])
        .ok()
        .or_else(|| {
            // A multi-byte character may be cut by the window: decode what is whole.
            (2..s.len().min(6))
                .rev()
                .find_map(|e| std::str::from_utf8(&s[1..e]).ok())
        })?;
    let ch = c.chars().next()?;
    (s.get(1 + ch.len_utf8()) == Some(&b'\'')).then_some(2 + ch.len_utf8())
}

/// Module path of a file: `film/checkpoint.rs` -> [film, checkpoint]; the binary (main.rs and
/// cli/) is rooted at `#bin`.
fn module_of(rel: &Path) -> Vec<String> {
    let mut parts: Vec<String> = rel
        .iter()
        .map(|s| s.to_string_lossy().trim_end_matches(".rs").to_string())
        .collect();
    if parts.last().is_some_and(|l| l == "mod" || l == "lib") {
        parts.pop();
    }
    if parts == ["main"] {
        return vec!["#bin".into()];
    }
    if parts.first().is_some_and(|p| p == "cli") {
        parts.insert(0, "#bin".into());
    }
    parts
}

struct Source {
    rel: String,
    module: Vec<String>,
    code: String,
}

fn sources() -> Vec<Source> {
    let mut files = Vec::new();
    rust_files(&src(), &mut files);
    files.sort();
    files
        .iter()
        .map(|f| {
            let text = std::fs::read_to_string(f).expect("readable");
            let rel = f.strip_prefix(src()).expect("under src");
            Source {
                rel: rel.to_string_lossy().replace('\\', "/"),
                module: module_of(rel),
                code: code_only(&text),
            }
        })
        .collect()
}

#[path = "architecture/graph.rs"]
mod graph;

#[test]
fn no_import_cycles() {
    let sources = sources();
    let edges = graph::dependencies(&sources);
    let mut cycles = Vec::new();
    for (folder, deps) in &edges {
        let kept: BTreeMap<&String, BTreeSet<&String>> = deps
            .iter()
            .map(|(from, tos)| {
                let tos = tos
                    .iter()
                    .filter(|to| !CYCLE_ALLOW.contains(&(folder.as_str(), from, to)))
                    .collect();
                (from, tos)
            })
            .collect();
        if let Some(c) = graph::find_cycle(&kept) {
            cycles.push(format!("in {}: {}", display(folder), c.join(" -> ")));
        }
    }
    assert!(cycles.is_empty(), "import cycles:\n{}", cycles.join("\n"));
    // The allowances must still be needed: a fixed cycle leaves the list.
    for (folder, from, to) in CYCLE_ALLOW {
        let used = edges
            .get(*folder)
            .and_then(|d| d.get(*from))
            .is_some_and(|t| t.contains(*to));
        assert!(
            used,
            "CYCLE_ALLOW entry {folder}: {from} -> {to} is no longer needed"
        );
    }
}

fn display(folder: &str) -> &str {
    if folder.is_empty() { "src" } else { folder }
}

#[test]
fn files_and_functions_are_short() {
    let mut long = Vec::new();
    for s in sources() {
        let lines = s.code.lines().count();
        if lines > MAX_FILE_LINES && !LONG_FILES.contains(&s.rel.as_str()) {
            long.push(format!("{}: {lines} lines", s.rel));
        }
        for (name, n) in graph::function_lengths(&s.code) {
            if n > MAX_FN_LINES && !LONG_FNS.contains(&(s.rel.as_str(), name.as_str())) {
                long.push(format!("{}: fn {name}: {n} lines", s.rel));
            }
        }
    }
    assert!(long.is_empty(), "too long:\n{}", long.join("\n"));
    // The allowances must still be needed.
    let sources = sources();
    for f in LONG_FILES {
        let s = sources.iter().find(|s| s.rel == *f);
        let needed = s.is_some_and(|s| s.code.lines().count() > MAX_FILE_LINES);
        assert!(needed, "LONG_FILES entry {f} is no longer needed");
    }
    for (f, name) in LONG_FNS {
        let s = sources.iter().find(|s| s.rel == *f);
        let needed = s.is_some_and(|s| {
            graph::function_lengths(&s.code)
                .iter()
                .any(|(n, l)| n == name && *l > MAX_FN_LINES)
        });
        assert!(needed, "LONG_FNS entry {f}: {name} is no longer needed");
    }
}

#[test]
fn the_checks_see_what_they_check() {
    // A cycle is found, and a function's braces inside strings and comments do not count.
    let deps: BTreeMap<String, BTreeSet<String>> = [
        ("a".to_string(), BTreeSet::from(["b".to_string()])),
        ("b".to_string(), BTreeSet::from(["a".to_string()])),
    ]
    .into();
    let view = deps.iter().map(|(k, v)| (k, v.iter().collect())).collect();
    assert!(graph::find_cycle(&view).is_some());
    let code =
        code_only("fn f() {\n let s = \"}}}\"; // }\n let c = '}';\n}\nfn g<'a>(x: &'a u8) {}\n");
    let lens = graph::function_lengths(&code);
    assert_eq!(lens, vec![("f".to_string(), 4), ("g".to_string(), 1)]);
    let file = |rel: &str, module: &[&str], code: &str| Source {
        rel: rel.into(),
        module: module.iter().map(|m| m.to_string()).collect(),
        code: code_only(code),
    };
    let edges = graph::dependencies(&[
        file(
            "film/checkpoint.rs",
            &["film", "checkpoint"],
            "use super::{identity::Fnv, Film};\nuse crate::spectrum::SpectralGrid;",
        ),
        file("film/mod.rs", &["film"], "pub use accum::{Film, LAYERS};"),
        file("film/accum.rs", &["film", "accum"], ""),
        file("film/identity.rs", &["film", "identity"], ""),
        file("spectrum/mod.rs", &["spectrum"], ""),
    ]);
    assert_eq!(
        edges["film"]["checkpoint"],
        BTreeSet::from(["identity".to_string(), "accum".to_string()])
    );
    assert!(edges[""]["film"].contains("spectrum"));
}

#[test]
fn clap_is_used_only_by_the_command_line() {
    let outside: Vec<String> = sources()
        .into_iter()
        .filter(|s| s.module.first().is_none_or(|m| m != "#bin"))
        .filter(|s| s.code.contains("clap::") || s.code.contains("clap ::"))
        .map(|s| s.rel)
        .collect();
    assert!(outside.is_empty(), "clap in the library: {outside:?}");
}
