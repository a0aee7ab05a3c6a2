//! Spectral bins and the spectral value type carried through light transport.

mod grid;
mod value;

pub use grid::SpectralGrid;
pub use value::{MAX_BINS, Spectrum};
