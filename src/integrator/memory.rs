//! The memory a render is expected to need per pass, from its settings alone (`brume info`, and
//! the check before a render starts).

use super::gather::BVH_BYTES_PER_PRIM;
use super::record::{SegmentRecord, SurfaceRecord, VolumeRecord};
use super::settings::{IntegratorDesc, VolumeKind};

/// Bytes of one integration volume or surface sphere excluding its segment and throughput:
/// its record and its share of the BVH.
pub const GATHER_RECORD_BYTES: f64 =
    (std::mem::size_of::<VolumeRecord>() + BVH_BYTES_PER_PRIM) as f64;
/// Bytes of the segment record that a path's volumes share.
const PATH_BYTES: f64 = std::mem::size_of::<SegmentRecord>() as f64;
const SURFACE_BYTES: f64 = (std::mem::size_of::<SurfaceRecord>() + BVH_BYTES_PER_PRIM) as f64;

/// What a render of a scene is expected to hold in memory, per pass.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct MemoryEstimate {
    pub gather_volumes: f64,
    pub gather_bytes: f64,
    pub film_bytes: f64,
}

impl MemoryEstimate {
    /// An upper estimate: every camera path reaches a medium segment thick enough to hold its
    /// full expected 1/q spheres (method note 2); surfaces add one sphere per path; no two
    /// paths share a throughput (the worst case). `pixels` of `bins` spectral bins; `media`:
    /// whether the scene has any. `"auto"` budgets count at their starting values, and an
    /// automatic q at the smallest it may choose.
    pub fn new(settings: &IntegratorDesc, pixels: u64, bins: usize, media: bool) -> Self {
        let pixels = pixels as f64;
        let spp = settings
            .camera_samples
            .value()
            .unwrap_or(super::defaults::CAMERA_SAMPLES);
        let paths = pixels * spp as f64;
        let q = settings.q.value().unwrap_or(super::auto::Q_MIN);
        let per_path = if media {
            match settings.volume {
                VolumeKind::Spheres => 1.0 + 1.0 / q as f64,
                VolumeKind::Cylinder | VolumeKind::CylinderTruncated | VolumeKind::CylinderLong => {
                    2.0
                }
            }
        } else {
            1.0
        };
        let gather_volumes = paths * per_path;
        let bins = bins as f64;
        // With media: the path's volumes, its segment with a throughput, and a surface
        // sphere with another throughput (transmission changes it in chromatic media).
        let gather_bytes = if !media {
            paths * (SURFACE_BYTES + 4.0 * bins)
        } else {
            let volumes = per_path - 1.0;
            paths * (volumes * GATHER_RECORD_BYTES + PATH_BYTES + SURFACE_BYTES + 8.0 * bins)
        };
        // Per pixel and bin: exact i128 sums of the two layers and of squares (48 bytes), the
        // pass buffer and the light pass's chunk buffers in flight (f32, two layers each).
        let film_bytes = pixels * bins * (48.0 + 8.0 * 5.0);
        Self {
            gather_volumes,
            gather_bytes,
            film_bytes,
        }
    }

    pub fn total(&self) -> f64 {
        self.gather_bytes + self.film_bytes
    }
}
