//! The components a pass estimate is split into, shared by the pass buffer, the chunk splat
//! logs and the film.

/// The components a pass estimate is split into (the paper compares them separately).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Layer {
    /// The medium's own luminance (gathered by integration volumes).
    Medium = 0,
    /// Surfaces (and emitters) seen directly or through the medium.
    Surface = 1,
}

pub const LAYERS: usize = 2;

/// Whether every bin of the sample `w * f * scale` is finite (branch-free over the bins).
#[inline]
pub(super) fn products_finite(w: &[f32], f: &[f32], scale: f32) -> bool {
    w.iter()
        .zip(f)
        .fold(true, |ok, (w, f)| ok & (w * f * scale).is_finite())
}
