//! The scene geometry: every shape's triangles and analytic primitives in one obvhs CWBVH
//! (built in `parts`), intersected through it or, in scenes of a few primitives, one by one.

mod interior;
mod parts;

use glam::{Vec2, Vec3, Vec3A};
use obvhs::{
    cwbvh::CwBvh,
    ray::{Ray as BvhRay, RayHit},
};

use super::analytic::Analytic;
use super::ray::null_rank;
use super::sampling::uniform_triangle;
use super::triangle::{ShearedRay, TriGeom};
use super::{Aabb, GeometryError, Ray, ShapeDesc};
use parts::{Parts, build_bvh};

/// A surface hit. `ng` is the geometric normal pointing out of the shape (the exterior side),
/// `ns` the shading normal on the same side as `ng`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hit {
    pub t: f32,
    pub p: Vec3,
    pub ng: Vec3,
    pub ns: Vec3,
    pub uv: Vec2,
    pub shape: u32,
}

#[derive(Clone, Copy, Debug)]
struct TriShading {
    n: Option<[Vec3; 3]>,
    uv: [Vec2; 3],
}

/// How to pick a uniform point on one shape.
#[derive(Clone, Debug)]
enum AreaSampler {
    /// Triangles `first..first+count`, with the shape's cumulative area table.
    Triangles {
        first: u32,
        cdf: Vec<f32>,
    },
    Analytic(u32),
    Empty,
}

pub struct Geometry {
    shapes: Vec<ShapeDesc>,
    tris: Vec<TriGeom>,
    tri_shape: Vec<u32>,
    tri_shading: Vec<TriShading>,
    analytic: Vec<Analytic>,
    bvh: Option<CwBvh>,
    /// Triangles in BVH leaf order (so a leaf's primitives are adjacent in memory); analytic
    /// primitives' slots hold a NaN triangle, which never hits.
    slot_tris: Vec<TriGeom>,
    /// Per BVH slot: does the primitive belong to a shape without a material (a null boundary,
    /// which [`Geometry::intersect`] ranks behind a surface it coincides with)?
    slot_null: Vec<bool>,
    bounds: Aabb,
    areas: Vec<f32>,
    samplers: Vec<AreaSampler>,
}

impl Geometry {
    pub fn new(shapes: Vec<ShapeDesc>) -> Result<Geometry, GeometryError> {
        let mut parts = Parts::default();
        for (i, desc) in shapes.iter().enumerate() {
            parts.add(i, desc)?;
        }
        let Parts {
            world,
            tri_shape,
            analytic,
            areas,
            samplers,
        } = parts;
        let tris: Vec<TriGeom> = world
            .iter()
            .map(|t| TriGeom {
                v: t.v.map(Vec3A::from),
            })
            .collect();
        let tri_shading = world
            .iter()
            .map(|t| TriShading { n: t.n, uv: t.uv })
            .collect();
        let (bvh, bounds) = build_bvh(&world, &analytic);
        let slot_tris = bvh.as_ref().map_or(Vec::new(), |b| {
            b.primitive_indices
                .iter()
                .map(|&p| tris.get(p as usize).copied().unwrap_or(TriGeom::INVALID))
                .collect()
        });
        let mut geometry = Geometry {
            shapes,
            tris,
            tri_shape,
            tri_shading,
            analytic,
            bvh,
            slot_tris,
            slot_null: Vec::new(),
            bounds,
            areas,
            samplers,
        };
        let slot_null = geometry.bvh.as_ref().map_or(Vec::new(), |b| {
            let slots = b.primitive_indices.iter();
            slots.map(|&p| geometry.prim_null(p as usize)).collect()
        });
        geometry.slot_null = slot_null;
        Ok(geometry)
    }

    pub fn bounds(&self) -> Aabb {
        self.bounds
    }

    pub fn num_shapes(&self) -> usize {
        self.shapes.len()
    }

    pub fn shape(&self, id: u32) -> &ShapeDesc {
        &self.shapes[id as usize]
    }

    pub fn shapes(&self) -> &[ShapeDesc] {
        &self.shapes
    }

    /// Number of BVH primitives (triangles plus analytic spheres, discs and boxes).
    pub fn num_primitives(&self) -> usize {
        self.tris.len() + self.analytic.len()
    }

    /// Distance to the primitive in BVH slot `slot`: triangles straight from leaf-ordered
    /// storage, analytic shapes through the slot's primitive id.
    #[inline(always)]
    fn slot_t(&self, bvh: &CwBvh, slot: usize, ray: &Ray, sr: &ShearedRay, t_max: f32) -> f32 {
        let tri = &self.slot_tris[slot];
        if tri.is_valid() {
            sr.hit(tri, t_max).0
        } else {
            let prim = bvh.primitive_indices[slot] as usize;
            self.analytic[prim - self.tris.len()].intersect(ray.o, ray.d, t_max)
        }
    }

    /// Distance to primitive `prim` along the ray if in `(0, t_max)`, else infinity.
    #[inline(always)]
    fn prim_t(&self, prim: usize, ray: &Ray, sr: &ShearedRay, t_max: f32) -> f32 {
        if let Some(tri) = self.tris.get(prim) {
            sr.hit(tri, t_max).0
        } else {
            self.analytic[prim - self.tris.len()].intersect(ray.o, ray.d, t_max)
        }
    }

    /// Closest hit in `(0, t_max)`, traversing the CWBVH. A null boundary (no material) ranks
    /// behind any surface with a material less than a spawn offset beyond it
    /// ([`null_rank`]), so that coincident faces are met surface first.
    pub fn intersect(&self, ray: &Ray, t_max: f32) -> Option<Hit> {
        let bvh = self.bvh.as_ref()?;
        let o = Vec3A::from(ray.o);
        let sr = ShearedRay::new(o, ray.d.into());
        let (slot, rank) = if self.slot_null.len() <= SMALL_SCENE {
            self.closest_slot(bvh, ray, &sr, t_max)?
        } else {
            let mut hit = RayHit::none();
            let found = bvh.ray_traverse(
                BvhRay::new(o, bvh_dir(ray.d), 0.0, t_max),
                &mut hit,
                |r, id| self.slot_rank(bvh, id, ray, &sr, (r.tmax, t_max)),
            );
            if !found {
                return None;
            }
            (hit.primitive_id as usize, hit.t)
        };
        let prim = bvh.primitive_indices[slot];
        // A null boundary's rank is not its distance: find the distance again.
        let t = if self.slot_null[slot] {
            self.prim_t(prim as usize, ray, &sr, t_max)
        } else {
            rank
        };
        Some(self.hit_details(ray, prim, t))
    }

    /// The rank of slot `slot`'s primitive along the ray (its distance, a null boundary's
    /// [`null_rank`]) when nearer than `best`; `t_max` is the query's.
    #[inline(always)]
    fn slot_rank(
        &self,
        bvh: &CwBvh,
        slot: usize,
        ray: &Ray,
        sr: &ShearedRay,
        (best, t_max): (f32, f32),
    ) -> f32 {
        let t = self.slot_t(bvh, slot, ray, sr, best);
        if t < best && self.slot_null[slot] {
            null_rank(ray, t, t_max)
        } else {
            t
        }
    }

    /// The slot of the closest hit and its rank, every primitive tested in turn: for scenes of
    /// a few primitives (a fog box and its walls) the BVH's traversal costs more than the tests.
    fn closest_slot(
        &self,
        bvh: &CwBvh,
        ray: &Ray,
        sr: &ShearedRay,
        t_max: f32,
    ) -> Option<(usize, f32)> {
        let mut best = (t_max, None);
        for slot in 0..self.slot_null.len() {
            let rank = self.slot_rank(bvh, slot, ray, sr, (best.0, t_max));
            if rank < best.0 {
                best = (rank, Some(slot));
            }
        }
        best.1.map(|slot| (slot, best.0))
    }

    /// Does primitive `prim` belong to a null boundary (a shape without a material)?
    fn prim_null(&self, prim: usize) -> bool {
        let shape = match self.tri_shape.get(prim) {
            Some(&s) => s,
            None => self.analytic[prim - self.tris.len()].shape,
        };
        self.shapes[shape as usize].material.is_none()
    }

    /// Is anything hit in `(0, t_max)`?
    pub fn occluded(&self, ray: &Ray, t_max: f32) -> bool {
        let Some(bvh) = self.bvh.as_ref() else {
            return false;
        };
        let o = Vec3A::from(ray.o);
        let sr = ShearedRay::new(o, ray.d.into());
        if self.slot_null.len() <= SMALL_SCENE {
            return (0..self.slot_null.len()).any(|s| self.slot_t(bvh, s, ray, &sr, t_max) < t_max);
        }
        !bvh.ray_traverse_miss(BvhRay::new(o, bvh_dir(ray.d), 0.0, t_max), |r, id| {
            self.slot_t(bvh, id, ray, &sr, r.tmax)
        })
    }

    /// Closest hit by testing every primitive: the reference the BVH is checked against.
    pub fn intersect_brute_force(&self, ray: &Ray, t_max: f32) -> Option<Hit> {
        let sr = ShearedRay::new(ray.o.into(), ray.d.into());
        // (rank, primitive, distance): ranked as `intersect` ranks.
        let mut best = (t_max, u32::MAX, t_max);
        for prim in 0..self.num_primitives() {
            let t = self.prim_t(prim, ray, &sr, best.0);
            let rank = if self.prim_null(prim) {
                null_rank(ray, t, t_max)
            } else {
                t
            };
            if rank < best.0 {
                best = (rank, prim as u32, t);
            }
        }
        (best.1 != u32::MAX).then(|| self.hit_details(ray, best.1, best.2))
    }

    fn hit_details(&self, ray: &Ray, prim: u32, t: f32) -> Hit {
        let prim = prim as usize;
        if let Some(tri) = self.tris.get(prim) {
            let sr = ShearedRay::new(ray.o.into(), ray.d.into());
            let (_, b0, b1, b2) = sr.hit(tri, f32::INFINITY);
            let p = Vec3::from(tri.v[0] * b0 + tri.v[1] * b1 + tri.v[2] * b2);
            let ng = Vec3::from(tri.normal()).normalize();
            let sh = &self.tri_shading[prim];
            let ns = match sh.n {
                Some(n) => {
                    let ns = (n[0] * b0 + n[1] * b1 + n[2] * b2).normalize_or(ng);
                    if ns.dot(ng) < 0.0 { -ns } else { ns }
                }
                None => ng,
            };
            Hit {
                t,
                p,
                ng,
                ns,
                uv: sh.uv[0] * b0 + sh.uv[1] * b1 + sh.uv[2] * b2,
                shape: self.tri_shape[prim],
            }
        } else {
            let a = &self.analytic[prim - self.tris.len()];
            let s = a.surface(ray.o, ray.d, t);
            Hit {
                t,
                p: s.p,
                ng: s.n,
                ns: s.n,
                uv: s.uv,
                shape: a.shape,
            }
        }
    }

    /// Surface area of a shape in world space (for spheres exact under uniform scaling only).
    pub fn area(&self, shape: u32) -> f32 {
        self.areas[shape as usize]
    }

    /// Is [`Self::sample_point`] exactly uniform and [`Self::area`] exact for this shape? False
    /// only for spheres under non-uniform scaling (ellipsoids), which area lights must not use.
    pub fn area_sampling_exact(&self, shape: u32) -> bool {
        match &self.samplers[shape as usize] {
            AreaSampler::Analytic(i) => self.analytic[*i as usize].sampling_exact(),
            AreaSampler::Triangles { .. } | AreaSampler::Empty => true,
        }
    }

    /// A point uniformly distributed over the shape's area (spheres: exact under uniform
    /// scaling) and the outward geometric normal there.
    pub fn sample_point(&self, shape: u32, u: Vec2) -> (Vec3, Vec3) {
        match &self.samplers[shape as usize] {
            AreaSampler::Triangles { first, cdf } => {
                let total = *cdf.last().unwrap_or(&0.0);
                let target = u.x * total;
                let k = cdf.partition_point(|&c| c <= target).min(cdf.len() - 1);
                let lo = if k == 0 { 0.0 } else { cdf[k - 1] };
                let w = cdf[k] - lo;
                let ux = if w > 0.0 {
                    ((target - lo) / w).clamp(0.0, 1.0)
                } else {
                    0.5
                };
                let tri = &self.tris[*first as usize + k];
                let b = uniform_triangle(Vec2::new(ux, u.y));
                let p = tri.v[0] + (tri.v[1] - tri.v[0]) * b.x + (tri.v[2] - tri.v[0]) * b.y;
                (p.into(), Vec3::from(tri.normal()).normalize())
            }
            AreaSampler::Analytic(i) => self.analytic[*i as usize].sample(u),
            AreaSampler::Empty => (Vec3::ZERO, Vec3::Z),
        }
    }
}

/// Scenes of at most this many primitives are intersected without their BVH
/// ([`Geometry::closest_slot`]).
const SMALL_SCENE: usize = 8;

/// obvhs node tests ignore everything closer than its traversal epsilon (1e-4) to the ray origin,
/// and lose flat boxes to rounding. Padding each primitive box by more than that epsilon keeps
/// hits just in front of a spawned origin (corners, edges) findable: a ray starting in a padded
/// box cannot leave it before t = 1e-4.
fn bvh_pad(lo: Vec3, hi: Vec3) -> f32 {
    2e-4 + 1e-6 * lo.abs().max(hi.abs()).max_element()
}

/// obvhs picks a child's near plane from the direction's sign bit but inverts -0.0 to a negative
/// value: turning -0.0 into +0.0 keeps axis-parallel rays consistent.
#[inline(always)]
fn bvh_dir(d: Vec3) -> Vec3A {
    Vec3A::from(d) + Vec3A::ZERO
}
