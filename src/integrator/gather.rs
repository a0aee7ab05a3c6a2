//! The gather structure: 8-wide compressed BVHs (obvhs PLOC then CWBVH, rebuilt every pass)
//! over the pass's integration spheres on surfaces and integration volumes in media.
//!
//! Memory per volume: a 12-byte record (segment, distance, scalar weight), the BVH (about 10
//! bytes), and shares of its 36-byte segment record and of the throughput table. Records are
//! stored in the BVH's leaf order, so the BVH needs no primitive index array and a query reads
//! neighbouring records from neighbouring memory. The volumes' BVH is one per spatial part
//! (`volume_parts`), so that the parts' serial conversions run side by side.

use rayon::prelude::*;
use std::sync::atomic::{AtomicBool, Ordering};

use glam::{Vec3, Vec3A};
use obvhs::aabb::Aabb;
use obvhs::cwbvh::CwBvh;
use obvhs::cwbvh::bvh2_to_cwbvh::bvh2_to_cwbvh;
use obvhs::ploc::{PlocBuilder, PlocSearchDistance, SortPrecision};
use obvhs::ray::Ray as BvhRay;

use super::Radii;
use super::boundary::PlaneTable;
use super::estimator::Estimator;
use super::record::{CameraOutput, SegmentRecord, SurfaceRecord, VolumeRecord};

/// CWBVH bytes per primitive, an upper bound of what fog scenes and benches/gather.rs measure
/// (8-wide nodes of 80 bytes, up to 3 primitives per leaf).
pub const BVH_BYTES_PER_PRIM: usize = 16;
/// Transient bytes per primitive while building: boxes (32), the binary BVH (2N nodes of 48),
/// its index array, PLOC's sort keys and cluster arrays, and the records' spare capacity. Set
/// from the peak resident memory of fog-cube passes of 1.7, 5.1 and 10.3 million volumes in
/// one piece (64 x 64 pixels, q = 0.003 to 0.0005): 268 bytes per volume at the peak, of which
/// the record and the kept BVH are 28; rounded up.
pub const BUILD_BYTES_PER_PRIM: usize = 256;

/// Records of one camera pass and the acceleration structures over them.
pub struct Gather {
    pub radii: Radii,
    /// Surface spheres, in BVH leaf order.
    pub surfaces: Vec<SurfaceRecord>,
    pub segments: Vec<SegmentRecord>,
    /// The bounding planes of the segments with a sphere near one (`boundary`).
    pub planes: PlaneTable,
    /// Volumes, in BVH leaf order.
    pub volumes: Vec<VolumeRecord>,
    /// Throughput spectra of `bins` floats, addressed by the records' `throughput` indices.
    pub throughputs: Vec<f32>,
    pub bins: usize,
    surface_bvh: Option<CwBvh>,
    /// Segment queries are long rays through dense clouds of volumes: the 8-wide compressed BVH
    /// traverses them several times faster than the binary one. One BVH per spatial part of
    /// the volumes (`volume_parts`), built side by side.
    volume_bvh: Vec<VolumePart>,
}

/// The BVH over one spatial part of the volumes, whose records are `volumes[first..]` in the
/// BVH's leaf order.
struct VolumePart {
    bvh: CwBvh,
    first: usize,
}

/// Volumes per part of the volume BVH, and the most parts. obvhs converts a binary BVH to the
/// wide one on one thread, the longest step of a pass's build: parts of this size convert in
/// parallel, while a query pays one root per part it does not cross. The part count depends
/// on the volumes only (never on the thread count), so the hits' order, and the image's bits,
/// are the same on any machine.
const PART_VOLUMES: usize = 1 << 16;
const MAX_PARTS: usize = 16;

/// Volume candidates of a segment query whose records are read together (`Gather::visit`).
const BATCH: usize = 16;

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
    // obvhs reads a leaf's index as a position in this array: it must be 0..n.
    let indices = (0..aabbs.len() as u32).collect();
    let bvh2 = PlocBuilder::new().build(
        PlocSearchDistance::VeryLow,
        aabbs,
        indices,
        SortPrecision::U64,
        0,
    );
    // Children in any order: a closest-hit traversal wants them front to back per ray octant,
    // but a gather query visits every overlap, and the ordering took a fifth of the build.
    Some(bvh2_to_cwbvh(&bvh2, 3, false, false))
}

/// The BVH's primitives of `records` in its leaf order; drops the BVH's index array: the
/// traversal's primitive ids then address the returned records directly.
fn leaf_order<T: Copy + Send + Sync>(bvh: &mut CwBvh, records: &[T]) -> Vec<T> {
    let leaf = bvh
        .primitive_indices
        .par_iter()
        .map(|&i| records[i as usize])
        .collect();
    bvh.primitive_indices = Vec::new();
    leaf
}

/// The volume BVH's parts over the boxes `aabbs` of `volumes`, and the volumes in the parts'
/// leaf order. The parts halve the volumes at the median of their boxes' centres along the
/// longest axis of those centres' bounds, recursively, ties broken by index: a deterministic
/// split into a power of two of parts of about `PART_VOLUMES`.
fn volume_parts(aabbs: &[Aabb], volumes: &[VolumeRecord]) -> (Vec<VolumePart>, Vec<VolumeRecord>) {
    let parts = aabbs
        .len()
        .div_ceil(PART_VOLUMES)
        .next_power_of_two()
        .min(MAX_PARTS);
    let mut ids: Vec<u32> = (0..aabbs.len() as u32).collect();
    let mut groups: Vec<&mut [u32]> = vec![&mut ids[..]];
    while groups.len() < parts {
        groups = groups.into_iter().flat_map(|g| halve(aabbs, g)).collect();
    }
    // Collected in the groups' order, whichever thread built which part.
    let built: Vec<(CwBvh, Vec<VolumeRecord>)> = groups
        .par_iter()
        .filter_map(|g| {
            let boxes: Vec<Aabb> = g.iter().map(|&i| aabbs[i as usize]).collect();
            let part: Vec<VolumeRecord> = g.iter().map(|&i| volumes[i as usize]).collect();
            build_cwbvh(&boxes).map(|mut bvh| {
                let records = leaf_order(&mut bvh, &part);
                (bvh, records)
            })
        })
        .collect();
    let mut leaf = Vec::with_capacity(volumes.len());
    let mut out = Vec::with_capacity(built.len());
    for (bvh, records) in built {
        out.push(VolumePart {
            bvh,
            first: leaf.len(),
        });
        leaf.extend(records);
    }
    (out, leaf)
}

/// `ids` split in two at the median of their boxes' centres along the longest axis.
fn halve<'a>(aabbs: &[Aabb], ids: &'a mut [u32]) -> [&'a mut [u32]; 2] {
    let centre = |i: u32| aabbs[i as usize].center();
    let (lo, hi) = ids.iter().fold(
        (Vec3A::splat(f32::INFINITY), Vec3A::splat(f32::NEG_INFINITY)),
        |(lo, hi), &i| (lo.min(centre(i)), hi.max(centre(i))),
    );
    let axis = (hi - lo).max_position();
    let mid = ids.len() / 2;
    if mid > 0 {
        ids.select_nth_unstable_by(mid, |&a, &b| {
            centre(a)[axis].total_cmp(&centre(b)[axis]).then(a.cmp(&b))
        });
    }
    let (a, b) = ids.split_at_mut(mid);
    [a, b]
}

/// Renumbers the segments in the order the (leaf-ordered) volumes first use them, so that a
/// query's volumes read neighbouring segments too.
fn segment_order(
    (segments, planes): (&mut Vec<SegmentRecord>, &mut PlaneTable),
    volumes: &mut [VolumeRecord],
) {
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
    planes.renumber(&new_index);
}

/// Memory the gather structure built from `out` will hold (`Gather::bytes()`, with the BVHs at
/// their measured bytes per primitive).
pub fn bytes_for(out: &CameraOutput) -> usize {
    let prims = out.surfaces.len() + out.volumes.len();
    out.surfaces.len() * std::mem::size_of::<SurfaceRecord>()
        + out.segments.len() * std::mem::size_of::<SegmentRecord>()
        + out.planes.bytes()
        + out.volumes.len() * std::mem::size_of::<VolumeRecord>()
        + out.throughputs.data_bytes()
        + prims * BVH_BYTES_PER_PRIM
}

/// Peak memory while the gather is built from `out`: what it keeps, plus the binary BVH and the
/// boxes the wide BVHs are converted from (freed before the light pass).
pub fn peak_bytes_for(out: &CameraOutput) -> usize {
    let prims = out.surfaces.len() + out.volumes.len();
    bytes_for(out) + prims * BUILD_BYTES_PER_PRIM
}

/// Gathers of at least this many spheres and volumes are built on a watched thread
/// (`Gather::from_output_until`): building takes about 2 us per volume on 2 cores (fog-cube,
/// 1.7 to 10 million volumes), so this is a quarter second, above which an interrupt would
/// wait noticeably; a gather at the default budget's limit takes half a minute.
const WATCHED_BUILD: usize = 1 << 17;

/// obvhs mishandles -0.0 direction components: use +0.0.
fn positive_zero(d: Vec3) -> Vec3A {
    Vec3A::from(d).map(|c| if c == 0.0 { 0.0 } else { c })
}

impl Gather {
    /// Builds the BVHs over the records, the volumes bounded as `estimator` shapes them;
    /// `throughputs` holds spectra of `bins` floats.
    pub fn new(
        estimator: &Estimator,
        radii: Radii,
        mut surfaces: Vec<SurfaceRecord>,
        (mut segments, mut planes): (Vec<SegmentRecord>, PlaneTable),
        mut volumes: Vec<VolumeRecord>,
        throughputs: Vec<f32>,
        bins: usize,
    ) -> Self {
        // Bounds hold the larger radius; queries test the one their light needs.
        let radius = radii.bound();
        let r = Vec3A::splat(radius);
        // The boxes and the leaf order are computed in parallel (collected in order: the same
        // bits on any number of threads); the conversion to the wide BVH is serial in obvhs,
        // so the two BVHs are built side by side.
        let (mut surface_bvh, (volume_bvh, leaf_volumes)) = rayon::join(
            || {
                let aabbs: Vec<Aabb> = surfaces
                    .par_iter()
                    .map(|s| Aabb::new(Vec3A::from(s.p) - r, Vec3A::from(s.p) + r))
                    .collect();
                build_cwbvh(&aabbs)
            },
            || {
                let aabbs: Vec<Aabb> = volumes
                    .par_iter()
                    .map(|v| estimator.bounds(&segments[v.segment as usize], v, radius))
                    .collect();
                volume_parts(&aabbs, &volumes)
            },
        );
        if let Some(bvh) = &mut surface_bvh {
            surfaces = leaf_order(bvh, &surfaces);
        }
        volumes = leaf_volumes;
        segment_order((&mut segments, &mut planes), &mut volumes);
        Self {
            radii,
            surfaces,
            segments,
            planes,
            volumes,
            throughputs,
            bins,
            surface_bvh,
            volume_bvh,
        }
    }

    /// Builds the gather from a camera pass's records, leaving its direct radiance and counts.
    pub fn from_output(estimator: &Estimator, radii: Radii, out: &mut CameraOutput) -> Self {
        let bins = out.throughputs.bins();
        let table = std::mem::take(&mut out.throughputs);
        Self::new(
            estimator,
            radii,
            std::mem::take(&mut out.surfaces),
            (
                std::mem::take(&mut out.segments),
                std::mem::take(&mut out.planes),
            ),
            std::mem::take(&mut out.volumes),
            table.into_data(),
            bins,
        )
    }

    /// Whether `from_output_until` builds the gather of `out` on a thread of its own.
    pub fn builds_apart(out: &CameraOutput) -> bool {
        out.surfaces.len() + out.volumes.len() >= WATCHED_BUILD
    }

    /// `from_output`, abandoned (None) once `stop` is set. obvhs cannot be interrupted and a
    /// gather at the budget's limit takes seconds to build, so a large one is built on a thread
    /// of its own (in a pool of the caller's size) while this one watches `stop`; an abandoned
    /// build finishes in the background and is dropped.
    pub fn from_output_until(
        estimator: &Estimator,
        radii: Radii,
        out: &mut CameraOutput,
        stop: &AtomicBool,
    ) -> Option<Self> {
        if !Self::builds_apart(out) {
            return Some(Self::from_output(estimator, radii, out));
        }
        let records = CameraOutput {
            surfaces: std::mem::take(&mut out.surfaces),
            segments: std::mem::take(&mut out.segments),
            planes: std::mem::take(&mut out.planes),
            volumes: std::mem::take(&mut out.volumes),
            throughputs: std::mem::take(&mut out.throughputs),
            ..CameraOutput::default()
        };
        let estimator = estimator.clone();
        let threads = rayon::current_num_threads();
        let build = std::thread::spawn(move || {
            let build = move || {
                let mut records = records;
                Self::from_output(&estimator, radii, &mut records)
            };
            match rayon::ThreadPoolBuilder::new().num_threads(threads).build() {
                Ok(pool) => pool.install(build),
                // No threads to spare: rayon's global pool builds it.
                Err(_) => build(),
            }
        });
        while !build.is_finished() {
            if stop.load(Ordering::Relaxed) {
                return None;
            }
            std::thread::sleep(std::time::Duration::from_millis(5));
        }
        match build.join() {
            Ok(g) => Some(g),
            Err(panic) => std::panic::resume_unwind(panic),
        }
    }

    /// Throughput spectrum `i` (`bins` floats).
    #[inline]
    pub fn throughput(&self, i: u32) -> &[f32] {
        let a = i as usize * self.bins;
        &self.throughputs[a..a + self.bins]
    }

    /// Calls `f` for every surface record within `radius` of `p` (at most the larger of the
    /// gather's radii, which its bounds hold).
    #[inline]
    pub fn surfaces_at(&self, p: Vec3, radius: f32, mut f: impl FnMut(&SurfaceRecord)) {
        let Some(bvh) = &self.surface_bvh else { return };
        let r2 = radius * radius;
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
    #[inline(always)]
    pub fn volumes_along(
        &self,
        o: Vec3,
        d: Vec3,
        len: f32,
        mut f: impl FnMut(&SegmentRecord, &VolumeRecord),
    ) {
        let d = positive_zero(d);
        let start = Vec3A::from(o) - d * CWBVH_EPSILON;
        let ray = BvhRay::new(start, d, 0.0, len + CWBVH_EPSILON);
        let mut batch = ([0u32; BATCH], 0);
        for part in &self.volume_bvh {
            part.bvh.ray_traverse_anyhit(ray, |_, i| {
                batch.0[batch.1] = (part.first + i) as u32;
                batch.1 += 1;
                if batch.1 == BATCH {
                    self.visit(&batch.0, &mut f);
                    batch.1 = 0;
                }
            });
        }
        self.visit(&batch.0[..batch.1], &mut f);
    }

    /// Calls `f` for the volumes `batch`, in order (so the splats, and the image's bits, are
    /// those of one call per candidate). The records of a query's candidates are scattered
    /// over more memory than a core's cache holds, and each is followed by a few hundred
    /// instructions of work: reading the batch's segment records first, in a loop of
    /// independent loads, lets their cache misses overlap instead of each one waiting behind
    /// the previous candidate's work (1.5 % of fog-cube's wall time, docs/performance.md).
    #[inline(always)]
    fn visit(&self, batch: &[u32], f: &mut impl FnMut(&SegmentRecord, &VolumeRecord)) {
        let mut touch = 0u8;
        for &k in batch {
            touch ^= self.segments[self.volumes[k as usize].segment as usize].classes;
        }
        std::hint::black_box(touch);
        for &k in batch {
            let v = &self.volumes[k as usize];
            f(&self.segments[v.segment as usize], v);
        }
    }

    /// Number of BVH nodes (surface, volume), for reports.
    pub fn bvh_nodes(&self) -> (usize, usize) {
        let nodes = |b: &Option<CwBvh>| b.as_ref().map_or(0, |b| b.nodes.len());
        let volume = self.volume_bvh.iter().map(|p| p.bvh.nodes.len()).sum();
        (nodes(&self.surface_bvh), volume)
    }

    /// Bytes held by the records, the throughput table and the BVHs.
    pub fn bytes(&self) -> usize {
        let cwbvh = |b: &CwBvh| {
            b.nodes.len() * std::mem::size_of::<obvhs::cwbvh::node::CwBvhNode>()
                + b.primitive_indices.len() * 4
        };
        self.surfaces.len() * std::mem::size_of::<SurfaceRecord>()
            + self.segments.len() * std::mem::size_of::<SegmentRecord>()
            + self.planes.bytes()
            + self.volumes.len() * std::mem::size_of::<VolumeRecord>()
            + self.throughputs.len() * 4
            + self.surface_bvh.as_ref().map_or(0, cwbvh)
            + self.volume_bvh.iter().map(|p| cwbvh(&p.bvh)).sum::<usize>()
    }
}
