use std::fmt;
use std::path::PathBuf;

/// Where a problem in a scene came from: a line of the file, or a `--set` on the command line.
#[derive(Clone, Debug, PartialEq)]
pub enum Origin {
    File {
        file: PathBuf,
        /// 1-based line and column, when the key is present in the file.
        line: Option<(usize, usize)>,
    },
    Set(String),
}

/// A scene that cannot be used. Its message names the file, line, column and key.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum SceneError {
    #[error("{file}: cannot read scene file: {message}")]
    Read { file: PathBuf, message: String },
    #[error("{origin}{key}{message}")]
    Invalid {
        origin: Origin,
        key: KeyText,
        message: String,
    },
    #[error("--set {assignment}: {message}")]
    BadAssignment { assignment: String, message: String },
}

/// Something in a scene that is allowed but probably not what was meant, named like an error:
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

/// A dotted key path shown in messages as "key `a.b`: "; empty at the top level.
#[derive(Clone, Debug, PartialEq)]
pub struct KeyText(pub String);

impl fmt::Display for KeyText {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.0.is_empty() {
            Ok(())
        } else {
            write!(f, "key `{}`: ", self.0)
        }
    }
}

impl fmt::Display for Origin {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Origin::File {
                file,
                line: Some((l, c)),
            } => write!(f, "{}:{l}:{c}: ", file.display()),
            Origin::File { file, line: None } => write!(f, "{}: ", file.display()),
            Origin::Set(a) => write!(f, "--set {a}: "),
        }
    }
}

impl SceneError {
    /// The dotted key the error is about, if any.
    pub fn key(&self) -> Option<&str> {
        match self {
            SceneError::Invalid { key, .. } if !key.0.is_empty() => Some(&key.0),
            _ => None,
        }
    }
}
