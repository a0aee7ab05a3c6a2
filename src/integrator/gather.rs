//! The gather structure: 8-wide compressed BVHs (obvhs PLOC then CWBVH, rebuilt every pass)
//! over the pass's integration spheres on surfaces and integration volumes in media.
//!
//! Memory per volume: a 12-byte record (segment, distance, scalar weight), the BVH (about 10
//! bytes), and shares of its 36-byte segment record and of the throughput table. Records are
//! stored in the BVH's leaf order, so the BVH needs no primitive index array and a query reads
//! neighbouring records from neighbouring memory.

use glam::{Vec3, Vec3A};
use obvhs::aabb::Aabb;
use obvhs::cwbvh::CwBvh;
use obvhs::cwbvh::bvh2_to_cwbvh::bvh2_to_cwbvh;
use obvhs::ploc::{PlocBuilder, PlocSearchDistance, SortPrecision};
use obvhs::ray::Ray as BvhRay;

use super::camera_pass::CameraOutput;
use super::exp::exp_nonpositive;
use super::record::{SegmentRecord, SurfaceRecord, VolumeRecord, VolumeShape};
use crate::medium::{HomogeneousMedium, relative_extinction};
use crate::spectrum::Spectrum;

/// CWBVH bytes per primitive, an upper bound of what fog scenes and benches/gather.rs measure
/// (8-wide nodes of 80 bytes, up to 3 primitives per leaf).
pub const BVH_BYTES_PER_PRIM: usize = 16;
/// Transient bytes per primitive while building: boxes (32), the binary BVH (2N nodes of 48),
/// its index array and PLOC's sort keys.
pub const BUILD_BYTES_PER_PRIM: usize = 160;

/// Records of one camera pass and the acceleration structures over them.
pub struct Gather {
    pub radius: f32,
    /// Surface spheres, in BVH leaf order.
    pub surfaces: Vec<SurfaceRecord>,
    pub segments: Vec<SegmentRecord>,
    /// Volumes, in BVH leaf order.
    pub volumes: Vec<VolumeRecord>,
    /// Throughput spectra of `bins` floats, addressed by the records' `throughput` indices.
    pub throughputs: Vec<f32>,
    pub bins: usize,
    /// Per medium: `st - st_min` (see `relative_extinction`), None when grey (all factors 1).
    extinction: Vec<Option<Spectrum>>,
    surface_bvh: Option<CwBvh>,
    /// Segment queries are long rays through dense clouds of volumes: the 8-wide compressed BVH
    /// traverses them several times faster than the binary one.
    volume_bvh: Option<CwBvh>,
}

/// obvhs' wide traversal skips nodes that end within this distance of the ray origin; segment
/// queries start this far behind their origin so that no volume near it is missed.
const CWBVH_EPSILON: f32 = 2e-4;
/// Half-length of the short ray that stands in for a point query (the CWBVH has none): any box
/// that contains the point meets it, and the exact sphere test removes the rest.
const POINT_RAY: f32 = 1e-3;

/// Builds the wide BVH over `aabbs` (through a binary PLOC BVH).
fn build_cwbvh(aabbs: &[Aabb]) -> Option<CwBvh> {
    if aabbs.is_empty() {
        return None;
    }
    let indices = (0..aabbs.len() as u32).collect();
    let bvh2 = PlocBuilder::new().build(
        PlocSearchDistance::VeryLow,
        aabbs,
        indices,
        SortPrecision::U64,
        0,
    );
    Some(bvh2_to_cwbvh(&bvh2, 3, true, false))
}

/// Puts `records` in the BVH's leaf order and drops the BVH's index array: the traversal's
/// primitive ids then address the records directly.
fn leaf_order<T: Copy>(bvh: &mut Option<CwBvh>, records: &mut Vec<T>) {
    if let Some(b) = bvh {
        *records = b
            .primitive_indices
            .iter()
            .map(|&i| records[i as usize])
            .collect();
        b.primitive_indices = Vec::new();
    }
}

/// Renumbers the segments in the order the (leaf-ordered) volumes first use them, so that a
/// query's volumes read neighbouring segments too.
fn segment_order(segments: &mut Vec<SegmentRecord>, volumes: &mut [VolumeRecord]) {
    let mut new_index = vec![u32::MAX; segments.len()];
    let mut ordered = Vec::with_capacity(segments.len());
    for v in volumes.iter_mut() {
        let i = v.segment as usize;
        if new_index[i] == u32::MAX {
            new_index[i] = ordered.len() as u32;
            ordered.push(segments[i]);
        }
        v.segment = new_index[i];
    }
    // A segment without volumes (the camera pass records none) would be dropped here.
    *segments = ordered;
}

/// Bounds of a volume: a sphere, or the capsule around a cylinder's axis.
pub fn volume_aabb(seg: &SegmentRecord, v: &VolumeRecord, radius: f32) -> Aabb {
    let r = Vec3A::splat(radius);
    let a = Vec3A::from(seg.origin);
    let b = Vec3A::from(seg.at(v.s));
    let (a, b) = match seg.shape {
        VolumeShape::Sphere => (b, b),
        _ => (a, b),
    };
    Aabb::new(a.min(b) - r, a.max(b) + r)
}

/// obvhs mishandles -0.0 direction components: use +0.0.
fn positive_zero(d: Vec3) -> Vec3A {
    Vec3A::from(d).map(|c| if c == 0.0 { 0.0 } else { c })
}

impl Gather {
    /// Builds the BVHs over the records; `throughputs` holds spectra of `bins` floats; `media`
    /// are the scene's (the records' medium indices point into it).
    pub fn new(
        media: &[HomogeneousMedium],
        radius: f32,
        mut surfaces: Vec<SurfaceRecord>,
        mut segments: Vec<SegmentRecord>,
        mut volumes: Vec<VolumeRecord>,
        throughputs: Vec<f32>,
        bins: usize,
    ) -> Self {
        let r = Vec3A::splat(radius);
        let (mut surface_bvh, mut volume_bvh) = rayon::join(
            || {
                let aabbs: Vec<Aabb> = surfaces
                    .iter()
                    .map(|s| Aabb::new(Vec3A::from(s.p) - r, Vec3A::from(s.p) + r))
                    .collect();
                build_cwbvh(&aabbs)
            },
            || {
                let aabbs: Vec<Aabb> = volumes
                    .iter()
                    .map(|v| volume_aabb(&segments[v.segment as usize], v, radius))
                    .collect();
                build_cwbvh(&aabbs)
            },
        );
        let extinction = media
            .iter()
            .map(|m| (!m.grey).then(|| relative_extinction(m)))
            .collect();
        leaf_order(&mut surface_bvh, &mut surfaces);
        leaf_order(&mut volume_bvh, &mut volumes);
        segment_order(&mut segments, &mut volumes);
        Self {
            radius,
            surfaces,
            segments,
            volumes,
            throughputs,
            bins,
            extinction,
            surface_bvh,
            volume_bvh,
        }
    }

    /// Builds the gather from a camera pass's records, leaving its direct radiance and counts.
    pub fn from_output(media: &[HomogeneousMedium], radius: f32, out: &mut CameraOutput) -> Self {
        let bins = out.throughputs.bins();
        let table = std::mem::take(&mut out.throughputs);
        Self::new(
            media,
            radius,
            std::mem::take(&mut out.surfaces),
            std::mem::take(&mut out.segments),
            std::mem::take(&mut out.volumes),
            table.into_data(),
            bins,
        )
    }

    /// Throughput spectrum `i` (`bins` floats).
    #[inline]
    pub fn throughput(&self, i: u32) -> &[f32] {
        let a = i as usize * self.bins;
        &self.throughputs[a..a + self.bins]
    }

    /// `st_l - st_min` of medium `m` over its bins, or None for a grey medium: a sphere's
    /// per-bin factor is `e^{-x_l s}` times its scalars.
    #[inline]
    pub fn relative_extinction(&self, m: u16) -> Option<&Spectrum> {
        self.extinction.get(m as usize).and_then(|x| x.as_ref())
    }

    /// A sphere's weight without the camera throughput, times `k`: what `MultiSphereWalk::walk`
    /// reported for it (`sigma_s,l e^{-(st_l - st_min) s} q / pdf_mix(s)`), recomputed from the
    /// distance and the scalar the record keeps. One exp per bin, none in grey media.
    #[inline]
    pub fn sphere_weight(
        &self,
        med: &HomogeneousMedium,
        seg: &SegmentRecord,
        rec: &VolumeRecord,
        k: f32,
    ) -> Spectrum {
        let mut w = med.sigma_s * (k * rec.scale);
        if let Some(x) = self.relative_extinction(seg.medium) {
            // The walk's `atten(x, s)` for the finite distances spheres have, in fixed blocks of
            // 8 bins that the compiler vectorises (lanes past `bins` multiply zeros by 1).
            let blocks = self.bins.div_ceil(8) * 8;
            for (wb, xb) in w.0[..blocks]
                .chunks_exact_mut(8)
                .zip(x.0[..blocks].chunks_exact(8))
            {
                for (w, x) in wb.iter_mut().zip(xb) {
                    *w *= exp_nonpositive(-x * rec.s);
                }
            }
        }
        w
    }

    /// Calls `f` for every surface record whose sphere contains `p`.
    #[inline]
    pub fn surfaces_at(&self, p: Vec3, mut f: impl FnMut(&SurfaceRecord)) {
        let Some(bvh) = &self.surface_bvh else { return };
        let r2 = self.radius * self.radius;
        // Any direction does; a diagonal one avoids zero components.
        let d = Vec3A::splat(0.577_350_26);
        let ray = BvhRay::new(Vec3A::from(p) - d * POINT_RAY, d, 0.0, 2.0 * POINT_RAY);
        bvh.ray_traverse_anyhit(ray, |_, i| {
            let rec = &self.surfaces[i];
            if rec.p.distance_squared(p) < r2 {
                f(rec);
            }
        });
    }

    /// Calls `f` for every volume whose bounds the segment `[o, o + d * len]` meets, with its
    /// segment record.
    #[inline]
    pub fn volumes_along(
        &self,
        o: Vec3,
        d: Vec3,
        len: f32,
        mut f: impl FnMut(&SegmentRecord, &VolumeRecord),
    ) {
        let Some(bvh) = &self.volume_bvh else { return };
        let d = positive_zero(d);
        let start = Vec3A::from(o) - d * CWBVH_EPSILON;
        let ray = BvhRay::new(start, d, 0.0, len + CWBVH_EPSILON);
        bvh.ray_traverse_anyhit(ray, |_, i| {
            let v = &self.volumes[i];
            f(&self.segments[v.segment as usize], v);
        });
    }

    /// Number of BVH nodes (surface, volume), for reports.
    pub fn bvh_nodes(&self) -> (usize, usize) {
        let nodes = |b: &Option<CwBvh>| b.as_ref().map_or(0, |b| b.nodes.len());
        (nodes(&self.surface_bvh), nodes(&self.volume_bvh))
    }

    /// Bytes held by the records, the throughput table and the BVHs.
    pub fn bytes(&self) -> usize {
        let cwbvh = |b: &Option<CwBvh>| {
            b.as_ref().map_or(0, |b| {
                b.nodes.len() * std::mem::size_of::<obvhs::cwbvh::node::CwBvhNode>()
                    + b.primitive_indices.len() * 4
            })
        };
        self.surfaces.len() * std::mem::size_of::<SurfaceRecord>()
            + self.segments.len() * std::mem::size_of::<SegmentRecord>()
            + self.volumes.len() * std::mem::size_of::<VolumeRecord>()
            + self.throughputs.len() * 4
            + cwbvh(&self.surface_bvh)
            + cwbvh(&self.volume_bvh)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::integrator::throughput::ThroughputTable;
    use crate::medium::{ChannelPick, Mixture, MultiSphereWalk};
    use rand::SeedableRng;

    /// The stored layout (segment, distance, scalar) gives back the weight the walk computed
    /// for every sphere, in a chromatic medium where the per-bin factors differ by orders of
    /// magnitude along the segment.
    #[test]
    fn recomputed_sphere_weights_equal_the_walks() {
        let n = 16;
        let st: Vec<f32> = (0..n).map(|l| 0.2 + 0.25 * l as f32).collect();
        let albedo: Vec<f32> = (0..n).map(|l| 0.3 + 0.04 * l as f32).collect();
        let med = HomogeneousMedium::from_extinction_albedo(&st, &albedo, 0.3).unwrap();
        assert!(!med.grey);
        let mut w = Spectrum::ZERO;
        for l in 0..n {
            w.0[l] = 0.5 + ((l * 7) % 5) as f32 * 0.3;
        }
        let mix = Mixture::new(ChannelPick::Throughput, &w, &med, 0.1);
        for q in [1.0, 0.3] {
            let walk = MultiSphereWalk::new(q).unwrap();
            let mut table = ThroughputTable::new(n);
            let (mut segments, mut volumes, mut expected) = (Vec::new(), Vec::new(), Vec::new());
            for i in 0..400u64 {
                let seg_len = 1.0 + (i % 7) as f32 * 2.0;
                let mut rng = rand_pcg::Pcg64Mcg::seed_from_u64(i);
                walk.walk(&med, &mix, seg_len, &mut rng, |s, ws| {
                    expected.push((s, w * *ws))
                });
                let mut rng = rand_pcg::Pcg64Mcg::seed_from_u64(i);
                let segment = segments.len() as u32;
                segments.push(SegmentRecord {
                    origin: Vec3::new(i as f32, 0.0, 0.0),
                    pixel: i as u32,
                    dir: Vec3::Z,
                    throughput: table.insert(w.as_slice(n)),
                    medium: 0,
                    shape: VolumeShape::Sphere,
                    classes: 3,
                });
                walk.walk_scaled(&med, &mix, seg_len, &mut rng, |s, scale| {
                    volumes.push(VolumeRecord { segment, s, scale })
                });
            }
            assert_eq!(volumes.len(), expected.len());
            assert!(volumes.len() > 300, "{} spheres", volumes.len());
            assert_eq!(table.len(), 1, "one shared throughput");
            let by_key: std::collections::HashMap<(u32, u32), Spectrum> = volumes
                .iter()
                .zip(&expected)
                .map(|(v, &(s, ew))| {
                    assert_eq!(v.s, s);
                    ((segments[v.segment as usize].pixel, s.to_bits()), ew)
                })
                .collect();
            let table = table.into_data();
            let g = Gather::new(&[med], 0.01, Vec::new(), segments, volumes, table, n);
            let mut worst = 0.0f32;
            for rec in &g.volumes {
                let seg = &g.segments[rec.segment as usize];
                let got = Spectrum::from_slice(g.throughput(seg.throughput))
                    * g.sphere_weight(&med, seg, rec, 1.0);
                let want = by_key[&(seg.pixel, rec.s.to_bits())];
                for l in 0..n {
                    let rel = (got.0[l] - want.0[l]).abs() / want.0[l].abs();
                    worst = worst.max(rel);
                }
            }
            eprintln!(
                "q = {q}: {} spheres, worst relative error {worst:e}",
                g.volumes.len()
            );
            assert!(worst < 1e-5, "q = {q}: {worst}");
        }
    }
}
