//! Gather records: what a camera path leaves for the light pass to find. Spectra live once per
//! pass in a [`ThroughputTable`](super::throughput::ThroughputTable); records hold an index into
//! it and only the scalars that vary per record.

use glam::{Vec2, Vec3};

use super::boundary::PlaneTable;
use super::oct::Oct;
use super::throughput::ThroughputTable;
use crate::spectrum::Spectrum;

/// Classes of forward light a volume collects (method note 6): C = direct, caustic and
/// medium-scattered only; D = reflected by a diffuse surface at least once.
pub const CLASS_C: u8 = 1;
pub const CLASS_D: u8 = 2;
pub const CLASS_ALL: u8 = CLASS_C | CLASS_D;
/// Flag (not a class of light) of a camera path's segment before any scattering or non-null
/// surface event: its volumes leave forward rays' direct and caustic light to the splat to the camera
/// when `integrator.splat_to_camera` is on (`camera_splat`).
pub const PRIMARY: u8 = 4;
/// Flag of a segment of one of a pixel's extra camera paths in a nested pass (`nest`): not
/// one of the first paths, whose estimate the pass also forms.
pub const EXTRA: u8 = 8;

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
    /// 1 / (diffuse pick probability x the fraction of the sphere's disc on its surface at the
    /// direct radius); `scale_indirect` the same at the indirect radius (`radius::Radii`).
    pub scale: f32,
    pub scale_indirect: f32,
    /// Whether this is the camera path's first non-null surface event (no scattering before
    /// it): such a sphere leaves forward rays' direct and caustic light to the splat to the camera when
    /// `integrator.splat_to_camera` is on (`camera_splat`).
    pub primary: bool,
    /// Whether the camera path is one of its pixel's extra paths in a nested pass (`nest`).
    pub extra: bool,
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
    /// Bit mask of CLASS_C / CLASS_D, and PRIMARY and EXTRA.
    pub classes: u8,
}

/// One integration volume: a sphere at `origin + dir * s`, or a cylinder piece over
/// `[scale, s]` of its segment, as the render's `Estimator` has it.
#[derive(Clone, Copy, Debug)]
pub struct VolumeRecord {
    pub segment: u32,
    /// Distance along the segment (spheres) or where the piece ends along it (cylinders).
    pub s: f32,
    /// Spheres: `q / pdf_mix(s)` (> 0), scaled as `MixEval` (see `estimator::sphere_weight`),
    /// NEGATED for a sphere within the pass's largest radius of a plane of its segment
    /// (`boundary`; [`VolumeRecord::sphere_scale`], [`VolumeRecord::near_boundary`]): the one
    /// bit the gather reads before it looks the planes up, so that the hot loop touches them
    /// only for such spheres. Cylinders: where the piece starts along the segment (cylinders
    /// are cut into pieces `[scale, s]`, see `estimator::cylinder::leave_pieces`).
    pub scale: f32,
}

impl VolumeRecord {
    /// A sphere's scale without its boundary flag.
    #[inline]
    pub fn sphere_scale(&self) -> f32 {
        self.scale.abs()
    }

    /// Whether a sphere may reach through a plane of its segment (`boundary::Planes`).
    #[inline]
    pub fn near_boundary(&self) -> bool {
        self.scale.is_sign_negative()
    }
}

/// Light a camera path found without the light pass: an emitter it saw, or a next-event
/// estimate.
#[derive(Clone, Copy, Debug)]
pub struct DirectRecord {
    /// The pixel (a sensor's index for sensor paths).
    pub pixel: u32,
    /// The light it came from (its index in the scene's `LightSet`); None when the estimate
    /// sums several lights (no light layers are kept).
    pub light: Option<u32>,
    pub value: Spectrum,
    /// Whether it came from a pixel's extra camera paths in a nested pass (`nest`).
    pub extra: bool,
}

/// What one row (or any batch of pixels) of the camera pass produced: the records the gather
/// structure is built from, and what the camera paths saw directly.
#[derive(Default)]
pub struct CameraOutput {
    pub surfaces: Vec<SurfaceRecord>,
    /// Camera segments in media that left volumes; `volumes` point into it.
    pub segments: Vec<SegmentRecord>,
    /// The bounding planes of the segments with a sphere near one (`boundary`).
    pub planes: PlaneTable,
    pub volumes: Vec<VolumeRecord>,
    /// Distinct camera throughputs, shared by the records.
    pub throughputs: ThroughputTable,
    /// Radiance seen directly (emitters), per pixel of the batch.
    pub direct: Vec<DirectRecord>,
    /// Next-event estimates of direct light summed over a pixel's camera paths, per pixel (and
    /// per light with light layers): scattered by media (the `medium` layer) and reflected by
    /// surfaces (`surface`).
    pub nee_medium: Vec<DirectRecord>,
    pub nee_surface: Vec<DirectRecord>,
    /// Camera paths started.
    pub paths: u64,
    /// Of them, the extra paths of a nested pass (`nest`).
    pub extra_paths: u64,
}

impl CameraOutput {
    /// An empty output for spectra of `n` bins.
    pub fn new(n: usize) -> Self {
        Self {
            throughputs: ThroughputTable::new(n),
            ..Self::default()
        }
    }

    /// Appends `other`, rebasing its segment and throughput indices.
    pub fn append(&mut self, mut other: CameraOutput) {
        let remap = self.throughputs.merge(&other.throughputs);
        let base = self.segments.len() as u32;
        other
            .surfaces
            .iter_mut()
            .for_each(|s| s.throughput = remap[s.throughput as usize]);
        other
            .segments
            .iter_mut()
            .for_each(|s| s.throughput = remap[s.throughput as usize]);
        other.volumes.iter_mut().for_each(|v| v.segment += base);
        self.surfaces.append(&mut other.surfaces);
        self.segments.append(&mut other.segments);
        self.planes.append(std::mem::take(&mut other.planes), base);
        self.volumes.append(&mut other.volumes);
        self.direct.append(&mut other.direct);
        self.nee_medium.append(&mut other.nee_medium);
        self.nee_surface.append(&mut other.nee_surface);
        self.paths += other.paths;
        self.extra_paths += other.extra_paths;
    }
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
        assert_eq!(std::mem::size_of::<SurfaceRecord>(), 52);
    }
}
