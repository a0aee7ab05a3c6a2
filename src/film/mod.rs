//! The film: per-pixel spectral accumulation, statistics across passes, and image output.

mod accum;
mod image;
pub mod output;

pub use accum::{Film, LAYERS, Layer, PassBuffer};
pub use image::SpectralImage;
