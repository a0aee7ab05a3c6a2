//! Gather records: what a camera path leaves for the light pass to find.

use glam::{Vec2, Vec3};

/// Classes of forward light a volume collects (method note 6): C = direct, caustic and
/// medium-scattered only; D = reflected by a diffuse surface at least once.
pub const CLASS_C: u8 = 1;
pub const CLASS_D: u8 = 2;
pub const CLASS_ALL: u8 = CLASS_C | CLASS_D;

/// An integration sphere on a diffuse surface (the surface engine's estimator).
#[derive(Clone, Copy, Debug)]
pub struct SurfaceRecord {
    pub p: Vec3,
    pub pixel: u32,
    /// Shading normal on the side the camera path arrived from.
    pub n: Vec3,
    pub material: u32,
    /// Direction back towards the camera.
    pub wo: Vec3,
    pub shape: u32,
    pub uv: Vec2,
    /// Offset of the record's spectral weight in the pass's weight array.
    pub weight: u32,
}

/// Shape of an integration volume in a medium.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(u8)]
pub enum VolumeShape {
    /// Sphere at `start`; weight = the sphere's per-bin weight (method note 2/3).
    Sphere,
    /// Cylinder over `[start, start + dir * len]` with deterministic transmittance (eq. 2);
    /// weight = camera throughput.
    Cylinder,
    /// Cylinder ending at the sampled extinction (note 5b); weights = throughput, then the
    /// channel probabilities P.
    Truncated,
    /// Paper eq. 3; weight = camera throughput.
    Long,
}

#[derive(Clone, Copy, Debug)]
pub struct VolumeRecord {
    pub start: Vec3,
    pub pixel: u32,
    /// Camera ray direction (from the camera into the scene).
    pub dir: Vec3,
    /// Cylinder length (0 for spheres).
    pub len: f32,
    pub medium: u16,
    pub shape: VolumeShape,
    /// Bit mask of CLASS_C / CLASS_D.
    pub classes: u8,
    pub weight: u32,
}
