//! Gather records: what a camera path leaves for the light pass to find. Spectra live once per
//! pass in a [`ThroughputTable`](super::throughput::ThroughputTable); records hold an index into
//! it and only the scalars that vary per record.

use glam::{Vec2, Vec3};

use super::oct::Oct;

/// Classes of forward light a volume collects (method note 6): C = direct, caustic and
/// medium-scattered only; D = reflected by a diffuse surface at least once.
pub const CLASS_C: u8 = 1;
pub const CLASS_D: u8 = 2;
pub const CLASS_ALL: u8 = CLASS_C | CLASS_D;

/// An integration sphere on a diffuse surface (the surface engine's estimator). Its weight is
/// `throughput * scale` (scale = 1 / the diffuse-part probability). The material is the
/// shape's.
#[derive(Clone, Copy, Debug)]
pub struct SurfaceRecord {
    pub p: Vec3,
    pub pixel: u32,
    /// Shading normal on the side the camera path arrived from.
    pub n: Oct,
    /// Direction back towards the camera.
    pub wo: Oct,
    pub shape: u32,
    pub uv: Vec2,
    pub throughput: u32,
    pub scale: f32,
}

/// Shape of an integration volume in a medium.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(u8)]
pub enum VolumeShape {
    /// Sphere at distance `s` on the segment; weight = throughput * the sphere's per-bin factor
    /// `sigma_s,l e^{-(st_l - st_min) s} * scale` (method notes 2/3, `walk_scaled`).
    Sphere,
    /// Cylinder over the segment's first `s` metres with deterministic transmittance (eq. 2);
    /// weight = camera throughput.
    Cylinder,
    /// Cylinder ending at the sampled extinction (note 5b); weight = throughput, and the
    /// channel probabilities P are the camera mixture's, recomputed from the throughput.
    Truncated,
    /// Paper eq. 3; weight = camera throughput.
    Long,
}

/// One camera segment in a medium that left at least one integration volume: what all its
/// volumes share.
#[derive(Clone, Copy, Debug)]
pub struct SegmentRecord {
    pub origin: Vec3,
    pub pixel: u32,
    /// Camera ray direction (from the camera into the scene).
    pub dir: Vec3,
    /// Camera throughput at the segment's start (index into the pass's throughput table).
    pub throughput: u32,
    pub medium: u16,
    pub shape: VolumeShape,
    /// Bit mask of CLASS_C / CLASS_D.
    pub classes: u8,
}

/// One integration volume: a sphere at `origin + dir * s`, or a cylinder over `[0, s]` of its
/// segment.
#[derive(Clone, Copy, Debug)]
pub struct VolumeRecord {
    pub segment: u32,
    /// Distance along the segment (spheres) or length (cylinders).
    pub s: f32,
    /// Spheres: `q / pdf_mix(s)`, scaled as `MixEval`; cylinders: unused (1).
    pub scale: f32,
}

impl SegmentRecord {
    /// Centre of a sphere `s` along the segment (the camera pass's own arithmetic, so the same
    /// bits).
    #[inline]
    pub fn at(&self, s: f32) -> Vec3 {
        self.origin + self.dir * s
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn record_sizes() {
        assert_eq!(std::mem::size_of::<SegmentRecord>(), 36);
        assert_eq!(std::mem::size_of::<VolumeRecord>(), 12);
        assert_eq!(std::mem::size_of::<SurfaceRecord>(), 44);
    }
}
