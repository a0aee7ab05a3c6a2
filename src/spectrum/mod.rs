//! Spectral bins, the spectral value type carried through light transport, and spectral data
//! (CSV tables and built-ins) reduced exactly to bins. RGB -> spectrum upsampling needs the
//! observer and an RGB space, so it lives in `colour::rgb` (spectrum depends on nothing above it).

mod analytic;
mod builtin;
mod error;
mod grid;
mod table;
mod value;

pub use analytic::{constant, lines, power_law};
pub use builtin::{builtin_names, builtin_table, resolve};
pub use error::SpectrumError;
pub use grid::{Bin, GridError, LINE_WIDTH, MIN_LINE_SEPARATION, SpectralGrid};
pub use table::{Extrapolation, PiecewiseLinear, SpectralTable};
pub use value::{MAX_BINS, Spectrum};
