//! The film: per-pixel spectral accumulation, statistics across passes, the film file and
//! what identifies a render, and image output.

mod accum;
pub mod atomic;
pub mod checkpoint;
mod chunk;
#[cfg(test)]
mod extras_tests;
mod identity;
mod image;
mod layer;
pub mod output;
mod pass;
mod sensor;
mod stored;

pub use accum::{Film, MAX_SAMPLE, MergeError};
pub use checkpoint::{FilmFile, FilmFileError, FilmHeader};
pub use chunk::ChunkSplats;
pub use identity::{Difference, FilmId, IdentityError, Mismatch, PER_RUN_KEYS, Sampling};
pub use image::SpectralImage;
pub use layer::{LAYERS, Layer};
pub use pass::PassBuffer;
pub use sensor::{FilmExtras, RELIABLE_PASSES, Sensor, SensorKind, SensorReading};
