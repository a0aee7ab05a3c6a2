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

/// Largest scene file read: scenes are kilobytes (meshes and tables live in their own files);
/// the bound keeps `/dev/zero` or a huge file named by mistake from filling the memory.
pub const MAX_SCENE_BYTES: u64 = 16 << 20;

/// Read, override and validate a scene file.
pub fn load(file: &Path, sets: &[String]) -> Result<LoadedScene, SceneError> {
    let text = read_scene(file).map_err(|message| SceneError::Read {
        file: file.to_path_buf(),
        message,
    })?;
    load_str(&text, file, sets)
}

/// The text of a scene file, or why it is not one: a folder, too large, not UTF-8 text (a pipe
/// such as `<(generate-scene)` is read like a file, up to the bound).
fn read_scene(file: &Path) -> Result<String, String> {
    use std::io::Read;
    let meta = std::fs::metadata(file).map_err(|e| e.to_string())?;
    if meta.is_dir() {
        return Err("is a folder, not a scene file".into());
    }
    let f = std::fs::File::open(file).map_err(|e| e.to_string())?;
    let mut bytes = Vec::new();
    f.take(MAX_SCENE_BYTES + 1)
        .read_to_end(&mut bytes)
        .map_err(|e| e.to_string())?;
    if bytes.len() as u64 > MAX_SCENE_BYTES {
        return Err(format!(
            "larger than {} MiB: not a scene file (scenes are TOML text of a few kilobytes)",
            MAX_SCENE_BYTES >> 20
        ));
    }
    // The bytes are not shown: a file named by mistake must not be echoed.
    String::from_utf8(bytes).map_err(|_| "not UTF-8 text: not a scene file".to_string())
}

/// Whether a scene text holds no keys at all (empty, or only comments and blank lines).
fn is_empty_scene(text: &str) -> bool {
    text.parse::<toml::Table>().is_ok_and(|t| t.is_empty())
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

    if is_empty_scene(text) {
        // Every key has a default, so an empty file would render a black image and succeed.
        return Err(SceneError::Invalid {
            origin: Origin::File {
                file: file.to_path_buf(),
                line: None,
            },
            key: KeyText(String::new()),
            message: "the scene file is empty (no keys, only blank lines or comments): a scene \
                      needs at least a light and something to see (docs/scene-format.md)"
                .into(),
        });
    }
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
        imports: Vec::new(),
        warnings: Vec::new(),
    };
    if let Some(problem) = validate::validate(&loaded).into_iter().next() {
        return Err(loaded.source().invalid(&problem.key, problem.message));
    }
    let mut loaded = loaded;
    super::gltf::expand(&mut loaded)?;
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
        let bad = |message| SceneError::BadAssignment {
            assignment: a.text.clone(),
            message,
        };
        match media_off(a) {
            Some(which) => remove_media(&mut root, which).map_err(bad)?,
            None => set_path(&mut root, &a.path, a.value.clone()).map_err(bad)?,
        }
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

/// `media=none` (every medium: `Some(None)`) or `media.NAME=none` (`Some(Some(NAME))`).
fn media_off(a: &Assignment) -> Option<Option<&str>> {
    if a.value.as_str() != Some("none") {
        return None;
    }
    match a.path.as_slice() {
        [Seg::Key(m)] if m == "media" => Some(None),
        [Seg::Key(m), Seg::Key(name)] if m == "media" => Some(Some(name)),
        _ => None,
    }
}

/// Switches media off: removes `which` (all when None) from `[media]`, and every reference to
/// it (the top-level `medium`, the shapes' `interior` and `exterior`), so that the scene stays
/// valid: a shape that only bounded the fog becomes an empty index-matched boundary.
fn remove_media(root: &mut toml::Value, which: Option<&str>) -> Result<(), String> {
    let Some(table) = root.as_table_mut() else {
        return Err("the scene is not a table".into());
    };
    let names: Vec<String> = table
        .get("media")
        .and_then(|m| m.as_table())
        .map(|m| m.keys().cloned().collect())
        .unwrap_or_default();
    if let Some(name) = which
        && !names.iter().any(|n| n == name)
    {
        return Err(format!(
            "the scene has no medium `{name}` (its media: {})",
            if names.is_empty() {
                "none".to_string()
            } else {
                names.join(", ")
            }
        ));
    }
    let gone = |v: &toml::Value| v.as_str().is_some_and(|m| which.is_none_or(|w| w == m));
    if let Some(media) = table.get_mut("media").and_then(|m| m.as_table_mut()) {
        media.retain(|name, _| which.is_some_and(|w| w != name));
    }
    if table.get("medium").is_some_and(gone) {
        table.remove("medium");
    }
    if let Some(shapes) = table.get_mut("shapes").and_then(|s| s.as_array_mut()) {
        for shape in shapes.iter_mut().filter_map(|s| s.as_table_mut()) {
            for side in ["interior", "exterior"] {
                if shape.get(side).is_some_and(gone) {
                    shape.remove(side);
                }
            }
        }
    }
    Ok(())
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
