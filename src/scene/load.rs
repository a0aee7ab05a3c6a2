//! Reading a scene file into a validated [`SceneDesc`], with `--set` overrides applied.

use std::ops::Range;
use std::path::{Path, PathBuf};

use super::desc::{self, SceneDesc};
use super::error::{KeyText, Origin, SceneError};
use super::loaded::LoadedScene;
use super::path::{self, Seg};
use super::validate;

/// A `KEY=VALUE` override; VALUE is TOML (`0.1`, `"spheres"`, `[1, 2, 3]`), or a bare string.
#[derive(Clone, Debug)]
struct Assignment {
    text: String,
    path: Vec<Seg>,
    value: toml::Value,
}

fn parse_assignment(text: &str) -> Result<Assignment, SceneError> {
    let bad = |message: &str| SceneError::BadAssignment {
        assignment: text.to_string(),
        message: message.to_string(),
    };
    let (key, value) = text
        .split_once('=')
        .ok_or_else(|| bad("expected KEY=VALUE"))?;
    let key = key.trim();
    if key.is_empty() || key.split('.').any(|s| s.is_empty()) {
        return Err(bad("the key must be a dotted path such as integrator.q"));
    }
    let value = value.trim();
    let parsed = format!("v = {value}")
        .parse::<toml::Table>()
        .ok()
        .and_then(|mut t| t.remove("v"))
        .unwrap_or_else(|| toml::Value::String(value.to_string()));
    Ok(Assignment {
        text: text.to_string(),
        path: path::parse_path(key),
        value: parsed,
    })
}

/// Read, override and validate a scene file.
pub fn load(file: &Path, sets: &[String]) -> Result<LoadedScene, SceneError> {
    let text = std::fs::read_to_string(file).map_err(|e| SceneError::Read {
        file: file.to_path_buf(),
        message: e.to_string(),
    })?;
    load_str(&text, file, sets)
}

/// As [`load`], from text already read; `file` names it in messages and anchors relative paths.
pub fn load_str(text: &str, file: &Path, sets: &[String]) -> Result<LoadedScene, SceneError> {
    let assignments = sets
        .iter()
        .map(|s| parse_assignment(s))
        .collect::<Result<Vec<_>, _>>()?;
    let in_file = |key: String, message: String, span: Option<std::ops::Range<usize>>| {
        let span = span.or_else(|| path::span_of(text, &path::parse_path(&key)));
        SceneError::Invalid {
            origin: Origin::File {
                file: file.to_path_buf(),
                line: span.map(|s| path::line_col(text, s.start)),
            },
            key: KeyText(key),
            message,
        }
    };

    let de = toml::Deserializer::parse(text)
        .map_err(|e| in_file(String::new(), e.message().to_string(), e.span()))?;
    let mut desc: SceneDesc = serde_path_to_error::deserialize(de).map_err(|e| {
        let key = clean_path(&e.path().to_string());
        let inner = e.into_inner();
        let (key, message, span) = refine(text, key, inner.message().to_string(), inner.span());
        in_file(key, message, span)
    })?;

    if !assignments.is_empty() {
        desc = apply_assignments(desc, &assignments)?;
    }

    let dir = file
        .parent()
        .map(Path::to_path_buf)
        .unwrap_or_else(|| PathBuf::from("."));
    let loaded = LoadedScene {
        desc,
        file: file.to_path_buf(),
        dir,
        text: text.to_string(),
        sets: assignments
            .iter()
            .map(|a| (a.text.clone(), path::display(&a.path)))
            .collect(),
    };
    if let Some(problem) = validate::validate(&loaded).into_iter().next() {
        return Err(loaded.source().invalid(&problem.key, problem.message));
    }
    Ok(loaded)
}

/// An error serde reports at a whole `[[lights]]`, `[[shapes]]` or `[materials.NAME]` table
/// (their kinds are read by hand, see `tagged.rs`) is placed at its key by reading that table
/// again from the document `text`.
fn refine(
    text: &str,
    key: String,
    message: String,
    span: Option<Range<usize>>,
) -> (String, String, Option<Range<usize>>) {
    let segs = path::parse_path(&key);
    let (Some(Seg::Key(section)), 2) = (segs.first(), segs.len()) else {
        return (key, message, span);
    };
    let fault = path::value_at(text, &segs).and_then(|t| desc::read_kind_table(section, t));
    match fault {
        Some(f) if f.path.is_empty() => (key, f.message, None),
        Some(f) => (format!("{key}.{}", f.path), f.message, f.span),
        None => (key, message, span),
    }
}

/// serde_path_to_error writes "?" for unknown positions and "." at the root.
fn clean_path(p: &str) -> String {
    let p = p.trim_matches('.');
    if p == "?" {
        String::new()
    } else {
        p.replace("[", ".").replace("]", "")
    }
}

fn apply_assignments(desc: SceneDesc, sets: &[Assignment]) -> Result<SceneDesc, SceneError> {
    let internal = |message: String| SceneError::BadAssignment {
        assignment: sets
            .iter()
            .map(|a| a.text.as_str())
            .collect::<Vec<_>>()
            .join(" "),
        message,
    };
    let mut root = toml::Value::try_from(&desc).map_err(|e| internal(e.to_string()))?;
    for a in sets {
        set_path(&mut root, &a.path, a.value.clone()).map_err(|message| {
            SceneError::BadAssignment {
                assignment: a.text.clone(),
                message,
            }
        })?;
        // Check each assignment on its own so the error names the one at fault.
        if let Err(e) = serde_path_to_error::deserialize::<_, SceneDesc>(root.clone()) {
            let key = clean_path(&e.path().to_string());
            let message = e.into_inner().message().to_string();
            // The overridden document as text, to place an error inside a kind's table.
            let text = toml::to_string(&root).unwrap_or_default();
            let (key, message, _) = refine(&text, key, message, None);
            return Err(SceneError::Invalid {
                origin: Origin::Set(a.text.clone()),
                key: KeyText(if key.is_empty() {
                    path::display(&a.path)
                } else {
                    key
                }),
                message,
            });
        }
    }
    serde_path_to_error::deserialize(root).map_err(|e| internal(e.to_string()))
}

fn set_path(root: &mut toml::Value, path: &[Seg], value: toml::Value) -> Result<(), String> {
    let Some((last, parents)) = path.split_last() else {
        return Err("empty key".into());
    };
    let mut cur = root;
    for (depth, seg) in parents.iter().enumerate() {
        let here = || path::display(&path[..=depth]);
        cur = match (seg, cur) {
            (Seg::Key(k), toml::Value::Table(t)) => t
                .entry(k.clone())
                .or_insert_with(|| toml::Value::Table(toml::Table::new())),
            (Seg::Index(i), toml::Value::Array(a)) => {
                let len = a.len();
                a.get_mut(*i)
                    .ok_or_else(|| format!("`{}` is out of range ({len} entries)", here()))?
            }
            _ => return Err(format!("`{}` is not a table or array", here())),
        };
    }
    match (last, cur) {
        (Seg::Key(k), toml::Value::Table(t)) => {
            t.insert(k.clone(), value);
            Ok(())
        }
        (Seg::Index(i), toml::Value::Array(a)) if *i < a.len() => {
            a[*i] = value;
            Ok(())
        }
        _ => Err(format!("`{}` cannot be set", path::display(path))),
    }
}
