use std::path::PathBuf;

use thiserror::Error;

/// Invalid medium or estimator parameters (they come from the scene file, so they are errors,
/// not panics).
#[derive(Debug, Clone, PartialEq, Error)]
pub enum MediumError {
    #[error("Henyey-Greenstein g must be finite and in (-1, 1), got {0}")]
    /// Henyey–Greenstein g out of range.
    PhaseG(f32),
    /// Another phase-function parameter out of its range.
    #[error("phase function {what} must be in {range}, got {value}")]
    PhaseParameter {
        what: &'static str,
        value: f32,
        range: &'static str,
    },
    /// A phase table that cannot be normalised or sampled.
    #[error("phase table: {0}")]
    PhaseTable(String),
    /// A fault in a phase table file, at a 1-based line.
    #[error("{}:{line}: {message}", file.display())]
    PhaseFile {
        file: PathBuf,
        line: usize,
        message: String,
    },
    /// A data file that cannot be read.
    #[error("{}: cannot read: {message}", file.display())]
    Read { file: PathBuf, message: String },
    /// Droplet (Lorenz–Mie) parameters or results that cannot be used.
    #[error("{0}")]
    Droplets(String),
    #[error("bin count must be in 1..={max}, got {n}")]
    BinCount { n: usize, max: usize },
    #[error("{what} must be finite and >= 0 in every bin (bin {bin} is {value})")]
    Coefficient {
        what: &'static str,
        bin: usize,
        value: f32,
    },
    #[error(
        "power law needs lambda0 > 0 nm, a finite exponent and a grid above 0 nm (lambda0 = {lambda0}, p = {p})"
    )]
    PowerLaw { lambda0: f32, p: f32 },
    #[error("the multi-sphere control parameter q must be in (0, 1], got {0}")]
    Q(f32),
    #[error("a phase table with {lanes} spectral lanes does not fit a medium of {n} bins")]
    PhaseLanes { lanes: usize, n: usize },
}
