//! Spectral bins, the spectral value type carried through light transport, spectral data
//! (CSV tables and built-ins) reduced exactly to bins, and RGB -> spectrum upsampling.

mod analytic;
mod builtin;
mod error;
mod grid;
pub mod rgb;
mod table;
mod value;

pub use analytic::{constant, power_law};
pub use builtin::{builtin_names, builtin_table, resolve};
pub use error::SpectrumError;
pub use grid::SpectralGrid;
pub use rgb::{RgbKind, rgb_to_spectrum};
pub use table::{Extrapolation, PiecewiseLinear, SpectralTable};
pub use value::{MAX_BINS, Spectrum};
