//! Spheres, discs and boxes intersected exactly in their local frame (any affine transform).

use std::f32::consts::{PI, TAU};

use glam::{Vec2, Vec3, vec2};

use super::Transform;
use super::sampling::{concentric_disc, uniform_sphere};

mod cuboid;

#[derive(Clone, Copy, Debug)]
pub(crate) enum AnalyticKind {
    Sphere {
        radius: f32,
    },
    Disc {
        radius: f32,
    },
    /// Centred, `half` the size along each local axis; `areas` are its faces' world areas
    /// (`cuboid::face_areas`), for uniform area sampling.
    Box {
        half: Vec3,
        areas: [f32; 6],
    },
}

#[derive(Clone, Copy, Debug)]
pub(crate) struct Analytic {
    pub kind: AnalyticKind,
    pub transform: Transform,
    pub shape: u32,
}

/// Surface details of an analytic hit: world point, outward normal, uv.
pub(crate) struct SurfacePoint {
    pub p: Vec3,
    pub n: Vec3,
    pub uv: Vec2,
}

impl Analytic {
    /// A box of `size` (local frame) under `transform`, for shape `shape`.
    pub fn cuboid(size: Vec3, transform: Transform, shape: u32) -> Self {
        let half = size * 0.5;
        let areas = cuboid::face_areas(half, |v| transform.vector(v));
        Self {
            kind: AnalyticKind::Box { half, areas },
            transform,
            shape,
        }
    }

    /// Closest hit distance in `(0, t_max)`, or infinity. The local-frame direction is not
    /// normalised, so the local ray parameter equals the world distance.
    #[inline]
    pub fn intersect(&self, o: Vec3, d: Vec3, t_max: f32) -> f32 {
        let lo = self.transform.inv_point(o);
        let ld = self.transform.inv_vector(d);
        let t = match self.kind {
            AnalyticKind::Sphere { radius } => sphere_hit(lo, ld, radius, t_max),
            AnalyticKind::Disc { radius } => {
                let t = -lo.z / ld.z;
                let p = lo + ld * t;
                if t > 0.0 && t < t_max && p.x * p.x + p.y * p.y <= radius * radius {
                    t
                } else {
                    f32::INFINITY
                }
            }
            AnalyticKind::Box { half, .. } => cuboid::hit(lo, ld, half, t_max),
        };
        if t > 0.0 && t < t_max {
            t
        } else {
            f32::INFINITY
        }
    }

    /// Details at a hit distance found by [`Self::intersect`].
    pub fn surface(&self, o: Vec3, d: Vec3, t: f32) -> SurfacePoint {
        let lo = self.transform.inv_point(o);
        let ld = self.transform.inv_vector(d);
        let lp = lo + ld * t;
        match self.kind {
            AnalyticKind::Sphere { radius } => {
                // Reproject onto the surface: removes the rounding error of o + t d.
                let ln = lp.normalize_or(Vec3::Z);
                self.sphere_point(ln, radius)
            }
            AnalyticKind::Disc { radius } => {
                let lp = Vec3::new(lp.x, lp.y, 0.0);
                let r = lp.truncate().length();
                let phi = lp.y.atan2(lp.x).rem_euclid(TAU);
                SurfacePoint {
                    p: self.transform.point(lp),
                    n: self.transform.normal(Vec3::Z),
                    uv: vec2(r / radius, phi / TAU),
                }
            }
            AnalyticKind::Box { half, .. } => {
                let (lp, ln, uv) = cuboid::surface(lp, half);
                SurfacePoint {
                    p: self.transform.point(lp),
                    n: self.transform.normal(ln),
                    uv,
                }
            }
        }
    }

    /// World surface area (spheres: exact under uniform scaling only).
    pub fn area(&self) -> f32 {
        let t = &self.transform;
        match self.kind {
            AnalyticKind::Sphere { radius } => {
                // Uniform scale factor of a similarity transform.
                let s = t.matrix().determinant().abs().cbrt();
                4.0 * PI * radius * radius * s * s
            }
            AnalyticKind::Disc { radius } => {
                let area_scale = t.vector(Vec3::X).cross(t.vector(Vec3::Y)).length();
                PI * radius * radius * area_scale
            }
            AnalyticKind::Box { areas, .. } => areas.iter().sum(),
        }
    }

    /// Are [`Self::sample`] exactly uniform and [`Self::area`] exact? False only for spheres
    /// under non-uniform scaling (ellipsoids), which area lights must not use.
    pub fn sampling_exact(&self) -> bool {
        match self.kind {
            AnalyticKind::Sphere { .. } => {
                let m = self.transform.matrix();
                let l = [m.x_axis, m.y_axis, m.z_axis].map(|c| c.truncate().length());
                (l[0] - l[1]).abs() <= 1e-5 * l[0] && (l[0] - l[2]).abs() <= 1e-5 * l[0]
            }
            AnalyticKind::Disc { .. } | AnalyticKind::Box { .. } => true,
        }
    }

    /// A world point uniform over the surface (spheres: under uniform scaling) and the outward
    /// normal there.
    pub fn sample(&self, u: Vec2) -> (Vec3, Vec3) {
        match self.kind {
            AnalyticKind::Sphere { radius } => {
                let s = self.sphere_point(uniform_sphere(u), radius);
                (s.p, s.n)
            }
            AnalyticKind::Disc { radius } => {
                let d = concentric_disc(u) * radius;
                (
                    self.transform.point(Vec3::new(d.x, d.y, 0.0)),
                    self.transform.normal(Vec3::Z),
                )
            }
            AnalyticKind::Box { half, areas } => {
                let (p, n) = cuboid::sample(half, &areas, u);
                (self.transform.point(p), self.transform.normal(n))
            }
        }
    }

    /// World point, normal and uv of the local unit direction `ln` on a sphere.
    pub fn sphere_point(&self, ln: Vec3, radius: f32) -> SurfacePoint {
        let phi = ln.y.atan2(ln.x).rem_euclid(TAU);
        let theta = ln.z.clamp(-1.0, 1.0).acos();
        SurfacePoint {
            p: self.transform.point(ln * radius),
            n: self.transform.normal(ln),
            uv: vec2(phi / TAU, theta / PI),
        }
    }

    /// World-space bounds (of the transformed local box: loose for rotated spheres, but cheap;
    /// padded but for boxes, whose corners bound them exactly, as their triangles' did).
    pub fn bounds(&self) -> (Vec3, Vec3) {
        let (r, padded) = match self.kind {
            AnalyticKind::Sphere { radius } => (Vec3::splat(radius), true),
            AnalyticKind::Disc { radius } => (Vec3::new(radius, radius, 0.0), true),
            AnalyticKind::Box { half, .. } => (half, false),
        };
        let mut lo = Vec3::splat(f32::INFINITY);
        let mut hi = Vec3::splat(f32::NEG_INFINITY);
        for i in 0..8 {
            let c = Vec3::new(
                if i & 1 == 0 { -r.x } else { r.x },
                if i & 2 == 0 { -r.y } else { r.y },
                if i & 4 == 0 { -r.z } else { r.z },
            );
            let p = self.transform.point(c);
            lo = lo.min(p);
            hi = hi.max(p);
        }
        if !padded {
            return (lo, hi);
        }
        // Pad: a flat disc would otherwise have a zero-thickness box.
        let pad = 1e-5 * (1.0 + lo.abs().max(hi.abs()).max_element());
        (lo - pad, hi + pad)
    }
}

/// Nearest root of |o + t d| = r in (0, t_max) with the numerically stable quadratic
/// (discriminant from the closest-approach vector, so large distances lose no precision).
#[inline]
fn sphere_hit(o: Vec3, d: Vec3, r: f32, t_max: f32) -> f32 {
    let dd = d.length_squared();
    let b = -o.dot(d) / dd; // parameter of closest approach
    let q = o + d * b;
    let disc = (r * r - q.length_squared()) / dd;
    if disc < 0.0 {
        return f32::INFINITY;
    }
    let s = disc.sqrt();
    let c = (o.length_squared() - r * r) / dd; // product of the roots
    let far = if b >= 0.0 { b + s } else { b - s };
    let near = if far != 0.0 { c / far } else { 0.0 };
    let (t0, t1) = if near < far { (near, far) } else { (far, near) };
    if t0 > 0.0 && t0 < t_max {
        t0
    } else if t1 > 0.0 && t1 < t_max {
        t1
    } else {
        f32::INFINITY
    }
}
