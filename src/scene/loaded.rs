//! A scene description as loaded, with what is needed to place a problem found later (while
//! validating or building) at its line in the file or at the `--set` that caused it.

use std::fmt;
use std::path::PathBuf;

use super::desc::SceneDesc;
use super::error::{KeyText, Origin, SceneError};
use super::path;

/// A scene description read from a file, overrides applied and validated.
#[derive(Clone, Debug)]
pub struct LoadedScene {
    pub desc: SceneDesc,
    /// The scene file.
    pub file: PathBuf,
    /// Folder that relative paths in the scene resolve from.
    pub dir: PathBuf,
    /// The file's text, to find the line of a key.
    pub text: String,
    /// The `--set` overrides applied, in order: (the assignment as given, its dotted key).
    pub sets: Vec<(String, String)>,
}

/// Something in a scene that is allowed but probably not what was meant. Named like an error:
/// file, line and key (or the `--set` responsible).
#[derive(Clone, Debug, PartialEq)]
pub struct SceneWarning {
    pub origin: Origin,
    pub key: KeyText,
    pub message: String,
}

impl fmt::Display for SceneWarning {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}{}{}", self.origin, self.key, self.message)
    }
}

impl LoadedScene {
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
                file: self.file.clone(),
                line: path::span_of(&self.text, &path::parse_path(key))
                    .map(|s| path::line_col(&self.text, s.start)),
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

    /// The warning "`key`: `message`", placed at the key.
    pub fn warning(&self, key: &str, message: impl Into<String>) -> SceneWarning {
        SceneWarning {
            origin: if key.is_empty() {
                Origin::File {
                    file: self.file.clone(),
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
