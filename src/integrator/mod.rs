//! The bidirectional engine: camera pass -> gather structure -> light pass -> film.

pub mod camera_pass;
mod exp;
pub mod gather;
pub mod light_pass;
mod memory;
pub mod oct;
mod pass;
pub mod record;
pub mod rng;
pub mod throughput;
pub mod volume;

pub use memory::MemoryEstimate;
pub use pass::{Budget, Renderer, Stats, gather_budget, radius_for_pass};
