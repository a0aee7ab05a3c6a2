//! The memory a render is expected to need, from its settings alone: one function for `brume
//! info`, the check before a render starts and the refusal of a gather budget that cannot hold
//! one camera path's records. Figures are in binary units (GiB = 2^30 bytes) everywhere.

use super::boundary::Planes;
use super::gather::{BUILD_BYTES_PER_PRIM, BVH_BYTES_PER_PRIM};
use super::record::{SegmentRecord, SurfaceRecord, VolumeRecord};
use super::settings::{IntegratorDesc, VolumeKind};

/// Peak bytes of one integration volume while its gather is built, excluding its segment and
/// throughput: its record, its share of the wide BVH and the transient build arrays (what
/// `gather::peak_bytes_for`, the tiling rule, counts).
pub const GATHER_RECORD_BYTES: f64 =
    (std::mem::size_of::<VolumeRecord>() + BVH_BYTES_PER_PRIM + BUILD_BYTES_PER_PRIM) as f64;
/// Bytes of the segment record that a path's volumes share, and of its planes (an upper
/// estimate: only segments with a sphere near a plane keep them).
const PATH_BYTES: f64 =
    (std::mem::size_of::<SegmentRecord>() + std::mem::size_of::<(u32, Planes)>()) as f64;
const SURFACE_BYTES: f64 =
    (std::mem::size_of::<SurfaceRecord>() + BVH_BYTES_PER_PRIM + BUILD_BYTES_PER_PRIM) as f64;
/// Film bytes per pixel and bin: exact i128 sums of the two layers and of squares (48), the
/// pass buffer (two f32 layers, 8) and the image written at the end (data, noise and two
/// layers in f32, 16).
const FILM_BYTES_PER_VALUE: f64 = 48.0 + 8.0 + 16.0;
/// More with `radius_indirect = "auto"`, whose passes may carry the blend of two radii
/// (`film::blend`): the sums of the two difference layers, their squares and cross terms (64),
/// and the pass's two radii's layers (16).
const BLEND_BYTES_PER_VALUE: f64 = 64.0 + 16.0;

/// Film bytes per pixel and bin (an upper estimate: the blend's only when the pilots may
/// choose it).
fn film_bytes_per_value(settings: &IntegratorDesc) -> f64 {
    if settings.radius_indirect_auto() {
        FILM_BYTES_PER_VALUE + BLEND_BYTES_PER_VALUE
    } else {
        FILM_BYTES_PER_VALUE
    }
}

/// What a render of a scene is expected to hold in memory, per pass.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct MemoryEstimate {
    /// Integration volumes and surface spheres of a whole pass (upper estimate).
    pub gather_volumes: f64,
    /// Peak bytes of the gather of a whole pass in one piece (building it included).
    pub gather_bytes: f64,
    /// The same for one camera path (a row of them is the smallest tile; a row over the budget
    /// stops the render, see `camera_pass::OverBudget`).
    pub path_gather_bytes: f64,
    /// The gather budget per pass (`integrator.max_gather_bytes`, resolved).
    pub budget: f64,
    pub film_bytes: f64,
}

impl MemoryEstimate {
    /// An upper estimate: every camera path reaches a medium segment thick enough to hold its
    /// full expected 1/q spheres (method note 2); surfaces add one sphere per path; no two
    /// paths share a throughput (the worst case). A `width` x `height` image of `bins` spectral
    /// bins; `media`: whether the scene has any. `"auto"` budgets count at their starting
    /// values, and an automatic q at the smallest it may choose.
    pub fn new(
        settings: &IntegratorDesc,
        (width, height): (u32, u32),
        bins: usize,
        media: bool,
    ) -> Self {
        let row_paths = f64::from(width) * f64::from(samples(settings));
        let per_path = path_bytes(settings, bins, media);
        let pixels = f64::from(width) * f64::from(height);
        Self {
            gather_volumes: row_paths * f64::from(height) * volumes_per_path(settings, media),
            gather_bytes: row_paths * f64::from(height) * per_path,
            path_gather_bytes: per_path,
            budget: settings.gather_budget() as f64,
            film_bytes: pixels * bins as f64 * film_bytes_per_value(settings),
        }
    }

    /// Peak gather bytes of a pass once tiled to the budget.
    pub fn gather_held(&self) -> f64 {
        self.gather_bytes.min(self.budget)
    }

    /// Gather tiles per pass (at least 1).
    pub fn tiles(&self) -> f64 {
        (self.gather_bytes / self.budget).ceil().max(1.0)
    }

    /// The render's peak: the film and a pass's tiled gather.
    pub fn total(&self) -> f64 {
        self.film_bytes + self.gather_held()
    }

    /// Why one camera path cannot fit the gather budget (no tile could hold it), or None. The
    /// estimate of a whole row could refuse a camera that sees no medium; one path reaching a
    /// medium with its expected 1/q volumes is what a tiny q means. The message gives the
    /// estimate and what to change.
    pub fn path_over_budget(&self, settings: &IntegratorDesc) -> Option<String> {
        if self.path_gather_bytes <= self.budget {
            return None;
        }
        let q = settings
            .q
            .value()
            .map_or("auto".to_string(), |q| q.to_string());
        Some(format!(
            "with q = {q}, one camera path may leave {} of gather records, more than the gather \
             budget of {} per pass (integrator.max_gather_bytes; a pass is split into tiles of \
             whole rows of camera paths); raise integrator.q or integrator.max_gather_bytes",
            format_bytes(self.path_gather_bytes),
            format_bytes(self.budget)
        ))
    }
}

fn samples(settings: &IntegratorDesc) -> u32 {
    settings
        .camera_samples
        .value()
        .unwrap_or(super::defaults::CAMERA_SAMPLES)
}

/// Volumes and surface spheres per camera path (upper estimate).
fn volumes_per_path(settings: &IntegratorDesc, media: bool) -> f64 {
    if !media {
        return 1.0;
    }
    let q = settings.q.value().unwrap_or(super::auto::Q_MIN);
    match settings.volume {
        VolumeKind::Spheres => 1.0 + 1.0 / f64::from(q),
        VolumeKind::Cylinder | VolumeKind::CylinderTruncated | VolumeKind::CylinderLong => 2.0,
    }
}

/// Peak gather bytes per camera path. With media: the path's volumes, its segment with a
/// throughput, and a surface sphere with another throughput (transmission changes it in
/// chromatic media).
fn path_bytes(settings: &IntegratorDesc, bins: usize, media: bool) -> f64 {
    let bins = bins as f64;
    if !media {
        return SURFACE_BYTES + 4.0 * bins;
    }
    let volumes = volumes_per_path(settings, media) - 1.0;
    volumes * GATHER_RECORD_BYTES + PATH_BYTES + SURFACE_BYTES + 8.0 * bins
}

/// Bytes in binary units, the one spelling of memory figures in brume's messages:
/// `512 bytes`, `3.0 KiB`, `1.5 MiB`, `4.0 GiB`, `25.2 TiB`.
pub fn format_bytes(b: f64) -> String {
    const UNITS: [&str; 5] = ["KiB", "MiB", "GiB", "TiB", "PiB"];
    if b < 1024.0 {
        return format!("{b:.0} bytes");
    }
    let mut v = b / 1024.0;
    let mut unit = 0;
    while v >= 1024.0 && unit + 1 < UNITS.len() {
        v /= 1024.0;
        unit += 1;
    }
    format!("{v:.1} {}", UNITS[unit])
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::integrator::setting::Setting;

    #[test]
    fn bytes_are_spelled_in_binary_units() {
        assert_eq!(format_bytes(512.0), "512 bytes");
        assert_eq!(format_bytes(1536.0), "1.5 KiB");
        assert_eq!(format_bytes(4.0 * (1u64 << 30) as f64), "4.0 GiB");
        assert_eq!(format_bytes(3.0 * (1u64 << 40) as f64), "3.0 TiB");
    }

    /// Issue 31: q = 1e-9 on 32 x 32 pixels was rendered until memory ran out; one of its paths
    /// alone exceeds the default budget, while the shipped q = 1 fits many times over.
    #[test]
    fn a_path_over_the_budget_is_reported() {
        let mut s = IntegratorDesc {
            q: Setting::Value(1e-9),
            camera_samples: Setting::Value(2),
            ..IntegratorDesc::default()
        };
        let e = MemoryEstimate::new(&s, (32, 32), 32, true);
        assert!(e.path_gather_bytes > e.budget);
        let m = e.path_over_budget(&s).unwrap();
        assert!(m.contains("264.5 GiB") && m.contains("4.0 GiB"), "{m}");
        s.q = Setting::Value(1.0);
        let e = MemoryEstimate::new(&s, (32, 32), 32, true);
        assert_eq!(e.path_over_budget(&s), None);
        assert_eq!(e.tiles(), 1.0);
        assert_eq!(e.gather_held(), e.gather_bytes);
    }
}
