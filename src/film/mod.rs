//! The film: per-pixel spectral accumulation, statistics across passes, the film file and
//! what identifies a render, and image output.

mod accum;
pub mod atomic;
mod blend;
pub mod checkpoint;
mod chunk;
#[cfg(test)]
mod extras_tests;
mod file_io;
mod fixed;
mod identity;
mod image;
mod layer;
pub mod output;
mod pass;
mod sensor;
mod stored;

pub use accum::{Film, MergeError};
pub use blend::{Blend, BlendSums};
pub use checkpoint::{FilmFile, FilmFileError, FilmHeader};
pub use chunk::ChunkSplats;
pub use fixed::MAX_SAMPLE;
pub use identity::{Difference, FilmId, IdentityError, Mismatch, PER_RUN_KEYS, Sampling};
pub use image::SpectralImage;
pub use layer::{LAYERS, Layer};
pub use pass::{BlendRadius, PassBuffer};
pub use sensor::{FilmExtras, RELIABLE_PASSES, Sensor, SensorKind, SensorReading};
