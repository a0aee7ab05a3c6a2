//! The module dependency graph and function lengths, from code with comments and strings
//! blanked (see `code_only`).

use std::collections::{BTreeMap, BTreeSet};

use super::Source;

/// Per folder ("" for `src/`, "scene", "#bin/cli"), the dependencies between its children.
pub type Deps = BTreeMap<String, BTreeMap<String, BTreeSet<String>>>;

fn is_ident(c: char) -> bool {
    c.is_alphanumeric() || c == '_'
}

/// The text of code before its `#[cfg(test)]` module: tests may use anything.
fn without_tests(code: &str) -> &str {
    code.find("#[cfg(test)]\nmod tests")
        .or_else(|| code.find("#[cfg(test)]\n    mod tests"))
        .map_or(code, |i| &code[..i])
}

/// The use tree starting at `at` (`a::b::{c, d::e}`), as text.
fn tree_at(code: &str, at: usize) -> &str {
    let mut depth = 0usize;
    for (i, c) in code[at..].char_indices() {
        match c {
            '{' => depth += 1,
            '}' if depth == 0 => return &code[at..at + i],
            '}' => depth -= 1,
            ',' | ';' | ')' | ']' | '>' | '(' | '<' | '=' if depth == 0 => {
                return &code[at..at + i];
            }
            c if depth == 0
                && c.is_whitespace()
                && !code[at + i..].trim_start().starts_with("::") =>
            {
                return &code[at..at + i];
            }
            _ => {}
        }
    }
    &code[at..]
}

/// Expands a use tree into paths, each with the name it is known by (`as` renames).
fn expand(tree: &str) -> Vec<(Vec<String>, String)> {
    let tree: String = tree
        .chars()
        .filter(|c| !c.is_whitespace() || *c == ' ')
        .collect();
    let tree = tree.trim();
    if let Some(open) = tree.find('{') {
        let prefix: Vec<String> = split_path(&tree[..open]);
        let inner = &tree[open + 1..tree.rfind('}').unwrap_or(tree.len())];
        let mut out = Vec::new();
        for part in split_top(inner) {
            for (mut p, name) in expand(part) {
                if p == ["self"] {
                    p.clear();
                }
                let mut full = prefix.clone();
                full.extend(p);
                let name = if name == "self" {
                    full.last().cloned().unwrap_or_default()
                } else {
                    name
                };
                out.push((full, name));
            }
        }
        return out;
    }
    let (path, alias) = match tree.split_once(" as ") {
        Some((p, a)) => (p, Some(a.trim().to_string())),
        None => (tree, None),
    };
    let p = split_path(path);
    let name = alias.unwrap_or_else(|| p.last().cloned().unwrap_or_default());
    vec![(p, name)]
}

fn split_path(s: &str) -> Vec<String> {
    s.split("::")
        .map(|x| x.trim().to_string())
        .filter(|x| !x.is_empty())
        .collect()
}

/// Splits at commas outside braces.
fn split_top(s: &str) -> Vec<&str> {
    let (mut depth, mut start, mut out) = (0usize, 0, Vec::new());
    for (i, c) in s.char_indices() {
        match c {
            '{' => depth += 1,
            '}' => depth = depth.saturating_sub(1),
            ',' if depth == 0 => {
                out.push(&s[start..i]);
                start = i + 1;
            }
            _ => {}
        }
    }
    out.push(&s[start..]);
    out.into_iter().filter(|p| !p.trim().is_empty()).collect()
}

/// Every path in `code` that starts at a module root (`crate`, `super`, `self`, `brume`),
/// made absolute for a file of module `module`.
fn paths(code: &str, module: &[String]) -> Vec<Vec<String>> {
    let mut out = Vec::new();
    for root in ["crate::", "super::", "self::", "brume::"] {
        for (at, _) in code.match_indices(root) {
            let before = code[..at].chars().next_back();
            if before.is_some_and(|c| is_ident(c) || c == ':') {
                continue;
            }
            for (p, _) in expand(tree_at(code, at)) {
                if let Some(abs) = absolute(&p, module) {
                    out.push(abs);
                }
            }
        }
    }
    out
}

fn absolute(p: &[String], module: &[String]) -> Option<Vec<String>> {
    let bin = module.first().is_some_and(|m| m == "#bin");
    let (mut base, rest): (Vec<String>, &[String]) = match p.first()?.as_str() {
        "crate" if bin => (vec!["#bin".into()], &p[1..]),
        "crate" | "brume" => (Vec::new(), &p[1..]),
        "self" => (module.to_vec(), &p[1..]),
        "super" => {
            let ups = p.iter().take_while(|s| *s == "super").count();
            let keep = module.len().checked_sub(ups)?;
            (module[..keep].to_vec(), &p[ups..])
        }
        _ => return None,
    };
    base.extend(rest.iter().cloned());
    Some(base)
}

/// (module, exported name) -> the child module that defines it, from `pub use child::..`.
fn reexports(
    sources: &[Source],
    modules: &BTreeSet<Vec<String>>,
) -> BTreeMap<(Vec<String>, String), String> {
    let mut map = BTreeMap::new();
    for s in sources {
        let code = without_tests(&s.code);
        for (at, _) in code.match_indices("pub use ") {
            let tree = tree_at(code, at + "pub use ".len());
            for (p, name) in expand(tree) {
                let Some(first) = p.first() else { continue };
                let mut child = s.module.clone();
                child.push(first.clone());
                if p.len() > 1 && modules.contains(&child) {
                    map.insert((s.module.clone(), name), first.clone());
                }
            }
        }
    }
    map
}

pub fn dependencies(sources: &[Source]) -> Deps {
    let modules: BTreeSet<Vec<String>> = sources.iter().map(|s| s.module.clone()).collect();
    let exported = reexports(sources, &modules);
    let mut deps = Deps::new();
    // Files of a module named `tests` (unit tests kept in their own file beside the code) are
    // test code, like the inline `mod tests`.
    for s in sources
        .iter()
        .filter(|s| !s.module.iter().any(|p| p == "tests"))
    {
        let m = &s.module;
        for p in paths(without_tests(&s.code), m) {
            let Some(i) = (0..m.len().min(p.len())).find(|&i| m[i] != p[i]) else {
                continue;
            };
            let folder = &m[..i];
            let mut target = folder.to_vec();
            target.push(p[i].clone());
            let to = if modules.contains(&target) {
                p[i].clone()
            } else if let Some(child) = exported.get(&(folder.to_vec(), p[i].clone())) {
                child.clone()
            } else {
                // An item of the parent module itself: not a sibling dependency.
                continue;
            };
            if to != m[i] {
                deps.entry(folder.join("/"))
                    .or_default()
                    .entry(m[i].clone())
                    .or_default()
                    .insert(to);
            }
        }
    }
    deps
}

/// A cycle of the graph, if any, as the list of its nodes (first repeated at the end).
pub fn find_cycle(g: &BTreeMap<&String, BTreeSet<&String>>) -> Option<Vec<String>> {
    fn visit<'a>(
        n: &'a String,
        g: &BTreeMap<&'a String, BTreeSet<&'a String>>,
        state: &mut BTreeMap<&'a String, u8>,
        stack: &mut Vec<&'a String>,
    ) -> Option<Vec<String>> {
        match state.get(n) {
            Some(1) => {
                let from = stack.iter().position(|s| *s == n).unwrap_or(0);
                let mut c: Vec<String> = stack[from..].iter().map(|s| s.to_string()).collect();
                c.push(n.to_string());
                return Some(c);
            }
            Some(_) => return None,
            None => {}
        }
        state.insert(n, 1);
        stack.push(n);
        for next in g.get(n).into_iter().flatten() {
            if let Some(c) = visit(next, g, state, stack) {
                return Some(c);
            }
        }
        stack.pop();
        state.insert(n, 2);
        None
    }
    let mut state = BTreeMap::new();
    g.keys()
        .find_map(|n| visit(n, g, &mut state, &mut Vec::new()))
}

/// Every named function and its length in lines, from `fn` to its closing brace.
pub fn function_lengths(code: &str) -> Vec<(String, usize)> {
    let mut out = Vec::new();
    for (at, _) in code.match_indices("fn ") {
        if code[..at].chars().next_back().is_some_and(is_ident) {
            continue;
        }
        let name: String = code[at + 3..]
            .trim_start()
            .chars()
            .take_while(|c| is_ident(*c))
            .collect();
        if name.is_empty() {
            continue;
        }
        // The body starts at the first `{` before any `;` (a declaration without body).
        let Some(open) = code[at..].find(['{', ';']).map(|i| at + i) else {
            continue;
        };
        if code.as_bytes()[open] == b';' {
            continue;
        }
        let mut depth = 0usize;
        let close = code[open..].char_indices().find_map(|(i, c)| {
            match c {
                '{' => depth += 1,
                '}' => {
                    depth -= 1;
                    if depth == 0 {
                        return Some(open + i);
                    }
                }
                _ => {}
            }
            None
        });
        let close = close.unwrap_or(code.len());
        out.push((name, code[at..close].matches('\n').count() + 1));
    }
    out
}
