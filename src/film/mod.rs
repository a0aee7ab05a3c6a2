//! The film: per-pixel spectral accumulation, statistics across passes, and image output.

mod image;
pub mod output;

pub use image::SpectralImage;
