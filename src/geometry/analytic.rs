//! Spheres and discs intersected exactly in their local frame (any affine transform).

use std::f32::consts::{PI, TAU};

use glam::{Vec2, Vec3, vec2};

use super::Transform;

#[derive(Clone, Copy, Debug)]
pub(crate) enum AnalyticKind {
    Sphere { radius: f32 },
    Disc { radius: f32 },
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

    /// World-space bounds (of the transformed local box: loose for rotated spheres, but cheap).
    pub fn bounds(&self) -> (Vec3, Vec3) {
        let r = match self.kind {
            AnalyticKind::Sphere { radius } => Vec3::splat(radius),
            AnalyticKind::Disc { radius } => Vec3::new(radius, radius, 0.0),
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
