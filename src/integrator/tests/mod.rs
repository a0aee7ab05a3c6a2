//! Unit tests of the engine that need whole scenes.

mod gather_bytes;
mod gather_parts;
mod tiles;
