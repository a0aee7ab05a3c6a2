//! The scene geometry: every shape's triangles and analytic primitives in one obvhs CWBVH.

mod interior;

use std::time::Duration;

use glam::{Vec2, Vec3, Vec3A};
use obvhs::{
    BvhBuildParams,
    aabb::Aabb as BvhAabb,
    cwbvh::{CwBvh, builder::build_cwbvh},
    ray::{Ray as BvhRay, RayHit},
};

use super::analytic::{Analytic, AnalyticKind};
use super::limits::{collapsed_at, out_of_range};
use super::ray::null_rank;
use super::sampling::{concentric_disc, uniform_sphere, uniform_triangle};
use super::tessellate::{WorldTri, tessellate};
use super::triangle::{ShearedRay, TriGeom};
use super::{Aabb, GeometryError, Ray, ShapeDesc, ShapeKind};

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

/// The primitives of the shapes added so far: world triangles, analytic shapes, and each
/// shape's area and area sampler.
#[derive(Default)]
struct Parts {
    world: Vec<WorldTri>,
    tri_shape: Vec<u32>,
    analytic: Vec<Analytic>,
    areas: Vec<f32>,
    samplers: Vec<AreaSampler>,
}

impl Parts {
    /// Adds shape `i`, checking its parameters.
    fn add(&mut self, i: usize, desc: &ShapeDesc) -> Result<(), GeometryError> {
        let bad = |message: &str| GeometryError::InvalidShape {
            shape: i,
            message: message.into(),
        };
        if !desc.transform.is_valid() {
            return Err(bad("transform is singular or not finite"));
        }
        let positive = |v: &[f32]| v.iter().all(|x| *x > 0.0 && x.is_finite());
        let analytic = match desc.kind {
            ShapeKind::Sphere { radius } => Some(AnalyticKind::Sphere { radius }),
            ShapeKind::Disc { radius } => Some(AnalyticKind::Disc { radius }),
            ShapeKind::Quad { size } if !positive(&size.to_array()) => {
                return Err(bad("size must be positive and finite"));
            }
            ShapeKind::Box { size } if !positive(&size.to_array()) => {
                return Err(bad("size must be positive and finite"));
            }
            ShapeKind::Quad { .. } | ShapeKind::Box { .. } | ShapeKind::Mesh { .. } => None,
        };
        match analytic {
            Some(kind) => self.add_analytic(i, desc, kind).map_err(|m| bad(&m)),
            None => self.add_triangles(i, desc),
        }
    }

    fn add_analytic(
        &mut self,
        i: usize,
        desc: &ShapeDesc,
        kind: AnalyticKind,
    ) -> Result<(), String> {
        let radius = match kind {
            AnalyticKind::Sphere { radius } | AnalyticKind::Disc { radius } => radius,
        };
        if !(radius > 0.0 && radius.is_finite()) {
            return Err("radius must be positive".into());
        }
        let a = Analytic {
            kind,
            transform: desc.transform,
            shape: i as u32,
        };
        let (lo, hi) = a.bounds();
        if let Some(why) = out_of_range(lo).or_else(|| out_of_range(hi)) {
            return Err(why);
        }
        self.areas.push(analytic_area(&a));
        self.samplers
            .push(AreaSampler::Analytic(self.analytic.len() as u32));
        self.analytic.push(a);
        Ok(())
    }

    fn add_triangles(&mut self, i: usize, desc: &ShapeDesc) -> Result<(), GeometryError> {
        let first = self.world.len();
        tessellate(i, desc, &mut self.world)?;
        let bad = |message: String| GeometryError::InvalidShape { shape: i, message };
        let mut total = 0.0f32;
        let mut cdf = Vec::with_capacity(self.world.len() - first);
        for t in &self.world[first..] {
            if let Some(why) = t.v.iter().find_map(|&v| out_of_range(v)) {
                return Err(bad(why));
            }
            total += 0.5 * (t.v[1] - t.v[0]).cross(t.v[2] - t.v[0]).length();
            cdf.push(total);
        }
        // Vertices that round to the same f32 values (a small shape far from the origin) leave
        // triangles no ray can hit: the shape would be silently missing from the image.
        if !cdf.is_empty() && total <= 0.0 {
            return Err(bad(collapsed_at(self.world[first].v[0])));
        }
        self.tri_shape.resize(self.world.len(), i as u32);
        self.areas.push(total);
        self.samplers.push(if cdf.is_empty() {
            AreaSampler::Empty
        } else {
            AreaSampler::Triangles {
                first: first as u32,
                cdf,
            }
        });
        Ok(())
    }
}

/// The wide BVH over the triangles then the analytic shapes (their primitive ids in that
/// order), and the bounds of everything.
fn build_bvh(world: &[WorldTri], analytic: &[Analytic]) -> (Option<CwBvh>, Aabb) {
    let mut boxes: Vec<BvhAabb> = world
        .iter()
        .map(|t| {
            let lo = t.v[0].min(t.v[1]).min(t.v[2]);
            let hi = t.v[0].max(t.v[1]).max(t.v[2]);
            let pad = bvh_pad(lo, hi);
            BvhAabb::new((lo - pad).into(), (hi + pad).into())
        })
        .collect();
    boxes.extend(analytic.iter().map(|a| {
        let (lo, hi) = a.bounds();
        let pad = bvh_pad(lo, hi);
        BvhAabb::new((lo - pad).into(), (hi + pad).into())
    }));
    let mut bounds = Aabb::EMPTY;
    for b in &boxes {
        bounds.grow(b.min.into());
        bounds.grow(b.max.into());
    }
    let bvh = (!boxes.is_empty()).then(|| {
        build_cwbvh(
            &boxes,
            BvhBuildParams::medium_build(),
            &mut Duration::default(),
        )
    });
    (bvh, bounds)
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

    /// Number of BVH primitives (triangles plus analytic spheres and discs).
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
        let mut hit = RayHit::none();
        let found = bvh.ray_traverse(
            BvhRay::new(o, bvh_dir(ray.d), 0.0, t_max),
            &mut hit,
            |r, id| {
                let t = self.slot_t(bvh, id, ray, &sr, r.tmax);
                if t < r.tmax && self.slot_null[id] {
                    null_rank(ray, t, t_max)
                } else {
                    t
                }
            },
        );
        if !found {
            return None;
        }
        let prim = bvh.primitive_indices[hit.primitive_id as usize];
        let t = if self.slot_null[hit.primitive_id as usize] {
            self.prim_t(prim as usize, ray, &sr, t_max)
        } else {
            hit.t
        };
        Some(self.hit_details(ray, prim, t))
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
            AreaSampler::Analytic(i) => {
                let a = &self.analytic[*i as usize];
                match a.kind {
                    AnalyticKind::Sphere { .. } => {
                        let m = a.transform.matrix();
                        let l = [m.x_axis, m.y_axis, m.z_axis].map(|c| c.truncate().length());
                        (l[0] - l[1]).abs() <= 1e-5 * l[0] && (l[0] - l[2]).abs() <= 1e-5 * l[0]
                    }
                    AnalyticKind::Disc { .. } => true,
                }
            }
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
            AreaSampler::Analytic(i) => {
                let a = &self.analytic[*i as usize];
                match a.kind {
                    AnalyticKind::Sphere { radius } => {
                        let s = a.sphere_point(uniform_sphere(u), radius);
                        (s.p, s.n)
                    }
                    AnalyticKind::Disc { radius } => {
                        let d = concentric_disc(u) * radius;
                        (
                            a.transform.point(Vec3::new(d.x, d.y, 0.0)),
                            a.transform.normal(Vec3::Z),
                        )
                    }
                }
            }
            AreaSampler::Empty => (Vec3::ZERO, Vec3::Z),
        }
    }
}

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

fn analytic_area(a: &Analytic) -> f32 {
    let t = &a.transform;
    match a.kind {
        AnalyticKind::Sphere { radius } => {
            // Uniform scale factor of a similarity transform.
            let s = t.matrix().determinant().abs().cbrt();
            4.0 * std::f32::consts::PI * radius * radius * s * s
        }
        AnalyticKind::Disc { radius } => {
            let area_scale = t.vector(Vec3::X).cross(t.vector(Vec3::Y)).length();
            std::f32::consts::PI * radius * radius * area_scale
        }
    }
}
