//! The gather structure: BVHs (obvhs PLOC, rebuilt every pass) over the pass's integration
//! spheres on surfaces and integration volumes in media.

use glam::{Vec3, Vec3A};
use obvhs::aabb::Aabb;
use obvhs::bvh2::Bvh2;
use obvhs::cwbvh::CwBvh;
use obvhs::cwbvh::bvh2_to_cwbvh::bvh2_to_cwbvh;
use obvhs::ploc::{PlocBuilder, PlocSearchDistance, SortPrecision};
use obvhs::ray::Ray as BvhRay;

use super::record::{SurfaceRecord, VolumeRecord, VolumeShape};

/// Records of one camera pass and the acceleration structures over them.
pub struct Gather {
    pub radius: f32,
    pub surfaces: Vec<SurfaceRecord>,
    pub volumes: Vec<VolumeRecord>,
    /// Spectral weights, addressed by the records' `weight` offsets.
    pub weights: Vec<f32>,
    surface_bvh: Option<Bvh2>,
    /// Segment queries are long rays through dense clouds of volumes: the 8-wide compressed BVH
    /// traverses them several times faster than the binary one.
    volume_bvh: Option<CwBvh>,
}

/// obvhs' wide traversal skips nodes that end within this distance of the ray origin; segment
/// queries start this far behind their origin so that no volume near it is missed.
const CWBVH_EPSILON: f32 = 2e-4;

fn build_bvh(aabbs: &[Aabb]) -> Option<Bvh2> {
    if aabbs.is_empty() {
        return None;
    }
    let indices = (0..aabbs.len() as u32).collect();
    Some(PlocBuilder::new().build(
        PlocSearchDistance::VeryLow,
        aabbs,
        indices,
        SortPrecision::U64,
        0,
    ))
}

/// Bounds of a volume record: a sphere, or the capsule around a cylinder's axis.
pub fn volume_aabb(v: &VolumeRecord, radius: f32) -> Aabb {
    let r = Vec3A::splat(radius);
    let a = Vec3A::from(v.start);
    let b = match v.shape {
        VolumeShape::Sphere => a,
        _ => Vec3A::from(v.start + v.dir * v.len),
    };
    Aabb::new(a.min(b) - r, a.max(b) + r)
}

impl Gather {
    pub fn new(
        radius: f32,
        surfaces: Vec<SurfaceRecord>,
        volumes: Vec<VolumeRecord>,
        weights: Vec<f32>,
    ) -> Self {
        let r = Vec3A::splat(radius);
        let s_aabbs: Vec<Aabb> = surfaces
            .iter()
            .map(|s| Aabb::new(Vec3A::from(s.p) - r, Vec3A::from(s.p) + r))
            .collect();
        let v_aabbs: Vec<Aabb> = volumes.iter().map(|v| volume_aabb(v, radius)).collect();
        let (surface_bvh, volume_bvh) = rayon::join(
            || build_bvh(&s_aabbs),
            || build_bvh(&v_aabbs).map(|b| bvh2_to_cwbvh(&b, 3, true, false)),
        );
        Self {
            radius,
            surfaces,
            volumes,
            weights,
            surface_bvh,
            volume_bvh,
        }
    }

    pub fn weight(&self, offset: u32, n: usize) -> &[f32] {
        &self.weights[offset as usize..offset as usize + n]
    }

    /// Calls `f` for every surface record whose sphere contains `p`.
    #[inline]
    pub fn surfaces_at(&self, p: Vec3, mut f: impl FnMut(&SurfaceRecord)) {
        let Some(bvh) = &self.surface_bvh else { return };
        let r2 = self.radius * self.radius;
        bvh.point_traverse(Vec3A::from(p), |bvh, node| {
            let node = &bvh.nodes[node as usize];
            for i in node.first_index..node.first_index + node.prim_count {
                let rec = &self.surfaces[bvh.primitive_indices[i as usize] as usize];
                if rec.p.distance_squared(p) < r2 {
                    f(rec);
                }
            }
            true
        });
    }

    /// Calls `f` for every volume record whose bounds the segment `[o, o + d * len]` meets.
    #[inline]
    pub fn volumes_along(&self, o: Vec3, d: Vec3, len: f32, mut f: impl FnMut(&VolumeRecord)) {
        let Some(bvh) = &self.volume_bvh else { return };
        // obvhs mishandles -0.0 direction components: use +0.0.
        let d = Vec3A::from(d).map(|c| if c == 0.0 { 0.0 } else { c });
        let start = Vec3A::from(o) - d * CWBVH_EPSILON;
        let ray = BvhRay::new(start, d, 0.0, len + CWBVH_EPSILON);
        bvh.ray_traverse_anyhit(ray, |_, i| {
            f(&self.volumes[bvh.primitive_indices[i] as usize]);
        });
    }

    /// Bytes held by the records, weights and BVHs.
    pub fn bytes(&self) -> usize {
        let bvh = |b: &Option<Bvh2>| {
            b.as_ref().map_or(0, |b| {
                b.nodes.len() * std::mem::size_of::<obvhs::bvh2::node::Bvh2Node>()
                    + b.primitive_indices.len() * 4
            })
        };
        let cwbvh = |b: &Option<CwBvh>| {
            b.as_ref().map_or(0, |b| {
                b.nodes.len() * std::mem::size_of::<obvhs::cwbvh::node::CwBvhNode>()
                    + b.primitive_indices.len() * 4
            })
        };
        self.surfaces.len() * std::mem::size_of::<SurfaceRecord>()
            + self.volumes.len() * std::mem::size_of::<VolumeRecord>()
            + self.weights.len() * 4
            + bvh(&self.surface_bvh)
            + cwbvh(&self.volume_bvh)
    }
}
