//! The film: per-pixel spectral accumulation, statistics across passes, and image output.

mod accum;
pub mod checkpoint;
mod chunk;
mod image;
pub mod output;

pub use accum::{Film, LAYERS, Layer, MAX_SAMPLE, MergeError, PassBuffer};
pub use checkpoint::{FilmFile, FilmFileError, FilmId};
pub use chunk::ChunkSplats;
pub use image::SpectralImage;
