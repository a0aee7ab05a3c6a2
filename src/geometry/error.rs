use std::path::PathBuf;

/// Errors from building geometry; each names what the user has to fix.
#[derive(Debug, thiserror::Error)]
pub enum GeometryError {
    #[error("cannot read OBJ file {path}: {message}")]
    Obj { path: PathBuf, message: String },
    #[error("shape {shape}: {message}")]
    InvalidShape { shape: usize, message: String },
}
