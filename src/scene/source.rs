//! Where a scene's keys are: the file, its folder and text, and the `--set` overrides. Checks
//! and builders place a problem found after loading at the key's line, or at the `--set` that
//! gave the key its value.

use std::path::{Path, PathBuf};

use super::error::{KeyText, Origin, SceneError, SceneWarning};
use super::path;

#[derive(Clone, Copy, Debug)]
pub struct Source<'a> {
    pub file: &'a Path,
    /// Folder that relative paths in the scene resolve from.
    pub dir: &'a Path,
    /// The file's text.
    pub text: &'a str,
    /// The `--set` overrides applied, in order: (the assignment as given, its dotted key).
    pub sets: &'a [(String, String)],
}

impl Source<'_> {
    /// A path given in the scene, resolved against the scene file's folder.
    pub fn resolve(&self, rel: &str) -> PathBuf {
        self.dir.join(rel)
    }

    /// Where the value of `key` came from: the last `--set` of it (or of a table holding it),
    /// else its line in the file (or the deepest enclosing key present there).
    pub fn origin(&self, key: &str) -> Origin {
        let set = self
            .sets
            .iter()
            .rev()
            .find(|(_, k)| key == k || key.starts_with(&format!("{k}.")));
        match set {
            Some((text, _)) => Origin::Set(text.clone()),
            None => Origin::File {
                file: self.file.to_path_buf(),
                line: path::span_of(self.text, &path::parse_path(key))
                    .map(|s| path::line_col(self.text, s.start)),
            },
        }
    }

    /// The error "`key`: `message`", placed at the key.
    pub fn invalid(&self, key: &str, message: impl Into<String>) -> SceneError {
        SceneError::Invalid {
            origin: self.origin(key),
            key: KeyText(key.to_string()),
            message: message.into(),
        }
    }

    /// The warning "`key`: `message`", placed at the key (at the file for an empty key).
    pub fn warning(&self, key: &str, message: impl Into<String>) -> SceneWarning {
        SceneWarning {
            origin: if key.is_empty() {
                Origin::File {
                    file: self.file.to_path_buf(),
                    line: None,
                }
            } else {
                self.origin(key)
            },
            key: KeyText(key.to_string()),
            message: message.into(),
        }
    }
}

/// Why `p`, named as a file, cannot be read as one: missing, a folder, a device or pipe
/// (`/dev/zero` would be read forever), or unreadable.
pub fn not_a_file(p: &Path) -> String {
    let what = match std::fs::metadata(p) {
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => "file not found".to_string(),
        Err(e) => format!("cannot read it: {e}"),
        Ok(m) if m.is_dir() => "is a folder, not a file".to_string(),
        Ok(_) => "is not a regular file (a device, pipe or socket)".to_string(),
    };
    format!("{}: {what}", p.display())
}
