use thiserror::Error;

/// Invalid medium or estimator parameters (they come from the scene file, so they are errors,
/// not panics).
#[derive(Debug, Clone, PartialEq, Error)]
pub enum MediumError {
    #[error("Henyey-Greenstein g must be finite and in (-1, 1), got {0}")]
    /// Henyey–Greenstein g out of range.
    PhaseG(f32),
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
}
