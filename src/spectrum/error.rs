use std::path::PathBuf;

/// Errors from reading or resolving spectral data. Every variant names the file (or built-in
/// name) it came from, and parse errors the 1-based line, so a user can go straight to the fault.
#[derive(Debug, thiserror::Error)]
pub enum SpectrumError {
    #[error("{file}:{line}: {message}")]
    Parse {
        file: String,
        line: usize,
        message: String,
    },
    #[error("{file}: {message}")]
    Data { file: String, message: String },
    #[error("{path}: {source}")]
    Io {
        path: PathBuf,
        source: std::io::Error,
    },
    #[error("{file}: no column {column:?} (columns: {available})")]
    NoColumn {
        file: String,
        column: String,
        available: String,
    },
    #[error("{0:?} is neither a built-in spectrum ({1}) nor a readable file")]
    Unknown(String, String),
}
