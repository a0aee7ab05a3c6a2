//! How much of a surface sphere's disc lies on its own surface (issue 19, method note 8).
//!
//! A surface sphere of radius R at point p gathers the forward rays that hit its surface inside
//! the disc of radius R around p, and divides by the disc's area. Near an edge part of that disc
//! is off the surface: no ray lands there, and the estimate comes out dark by the missing
//! fraction (20 % at the outermost pixels of a wall, measured). Dividing by the area of the part
//! of the disc that is on the surface instead makes the estimate the mean irradiance over that
//! part: the bias falls from first order in R to second order, as in the interior.
//!
//! Exact for quads and box faces (rectangles under any rotation and axis scale: the area of a
//! circle cut by a rectangle, integrated in closed form), and for discs (the lens of two
//! circles, a disc scaled uniformly); spheres have no edge; meshes are taken as edgeless
//! (their boundary is not known per triangle).

use std::f32::consts::PI;

use glam::{Vec2, Vec3};

use super::{Geometry, ShapeKind};

impl Geometry {
    /// The fraction (0, 1] of the disc of radius `r` about `p` (on shape `shape`, in its tangent
    /// plane) that lies on the shape.
    pub fn disc_fraction(&self, shape: u32, p: Vec3, r: f32) -> f32 {
        let s = self.shape(shape);
        let t = &s.transform;
        let f = match &s.kind {
            ShapeKind::Quad { size } => {
                let half = [
                    t.vector(Vec3::X) * (0.5 * size.x),
                    t.vector(Vec3::Y) * (0.5 * size.y),
                ];
                rectangle_fraction(p - t.point(Vec3::ZERO), half, r)
            }
            ShapeKind::Box { size } => {
                // The face p is on: the local axis along which p is furthest out (relative to
                // the half size); the face spans the other two.
                let l = t.inv_point(p) / (*size * 0.5);
                let axis = l.abs().max_position();
                let (j, k) = ((axis + 1) % 3, (axis + 2) % 3);
                let mut centre = Vec3::ZERO;
                centre[axis] = 0.5 * size[axis] * l[axis].signum();
                let half = [
                    t.vector(Vec3::AXES[j]) * (0.5 * size[j]),
                    t.vector(Vec3::AXES[k]) * (0.5 * size[k]),
                ];
                rectangle_fraction(p - t.point(centre), half, r)
            }
            ShapeKind::Disc { radius } => {
                let rw = radius * t.vector(Vec3::X).length();
                lens_area((p - t.point(Vec3::ZERO)).length(), r, rw) / (PI * r * r)
            }
            ShapeKind::Sphere { .. } | ShapeKind::Mesh { .. } => 1.0,
        };
        // Never below a sliver: a record exactly on a corner keeps a bounded weight.
        f.clamp(0.05, 1.0)
    }
}

/// Fraction of the disc of radius `r` centred at offset `d` from a rectangle's centre (in the
/// rectangle's plane) covered by the rectangle of half-extent vectors `half` (orthogonal).
fn rectangle_fraction(d: Vec3, half: [Vec3; 2], r: f32) -> f32 {
    let (hx, hy) = (half[0].length(), half[1].length());
    if !(hx > 0.0 && hy > 0.0 && r > 0.0) {
        return 1.0;
    }
    let local = Vec2::new(d.dot(half[0]) / hx, d.dot(half[1]) / hy);
    if local.x.abs() + r <= hx && local.y.abs() + r <= hy {
        // The whole disc is on the rectangle: the common case, away from every edge.
        return 1.0;
    }
    let area = circle_rectangle_area(r, local.x - hx, local.x + hx, local.y - hy, local.y + hy);
    area / (PI * r * r)
}

/// Area of the circle of radius `r` about the origin inside `[x0, x1] x [y0, y1]` (in the
/// circle's frame: the rectangle's edges relative to the circle's centre).
pub(crate) fn circle_rectangle_area(r: f32, x0: f32, x1: f32, y0: f32, y1: f32) -> f32 {
    let (r, x0, x1, y0, y1) = (r as f64, x0 as f64, x1 as f64, y0 as f64, y1 as f64);
    let (a, b) = (x0.max(-r), x1.min(r));
    if a >= b || y0 >= y1 {
        return 0.0;
    }
    // The chord height h(x) = sqrt(r^2 - x^2) crosses |y0| and |y1| at these x: between
    // consecutive breaks the y-extent [max(y0, -h), min(y1, h)] keeps one analytic form.
    let mut cuts = [a, b, f64::NAN, f64::NAN, f64::NAN, f64::NAN];
    for (i, y) in [y0, y1].into_iter().enumerate() {
        if y.abs() < r {
            let x = (r * r - y * y).sqrt();
            for (k, c) in [-x, x].into_iter().enumerate() {
                if c > a && c < b {
                    cuts[2 + 2 * i + k] = c;
                }
            }
        }
    }
    // Unused slots are positive NaNs, which the total order puts last.
    cuts.sort_by(f64::total_cmp);
    let cuts = &cuts[..cuts.iter().take_while(|c| !c.is_nan()).count()];
    // ∫ h(x) dx = (x h + r^2 asin(x / r)) / 2.
    let h_int = |x: f64| {
        let h = (r * r - x * x).max(0.0).sqrt();
        0.5 * (x * h + r * r * (x / r).clamp(-1.0, 1.0).asin())
    };
    let mut area = 0.0;
    for w in cuts.windows(2) {
        let (u, v) = (w[0], w[1]);
        let m = 0.5 * (u + v);
        let hm = (r * r - m * m).max(0.0).sqrt();
        let top_is_h = hm < y1;
        let bottom_is_h = -hm > y0;
        let top = if top_is_h {
            h_int(v) - h_int(u)
        } else {
            y1 * (v - u)
        };
        let bottom = if bottom_is_h {
            -(h_int(v) - h_int(u))
        } else {
            y0 * (v - u)
        };
        if hm.min(y1) > (-hm).max(y0) {
            area += top - bottom;
        }
    }
    area as f32
}

/// Area of the intersection of two circles of radii `r1`, `r2` whose centres are `d` apart.
fn lens_area(d: f32, r1: f32, r2: f32) -> f32 {
    let (d, r1, r2) = (d as f64, r1 as f64, r2 as f64);
    if d >= r1 + r2 {
        return 0.0;
    }
    if d <= (r1 - r2).abs() {
        let r = r1.min(r2);
        return (std::f64::consts::PI * r * r) as f32;
    }
    let a1 = ((d * d + r1 * r1 - r2 * r2) / (2.0 * d * r1))
        .clamp(-1.0, 1.0)
        .acos();
    let a2 = ((d * d + r2 * r2 - r1 * r1) / (2.0 * d * r2))
        .clamp(-1.0, 1.0)
        .acos();
    let k = ((-d + r1 + r2) * (d + r1 - r2) * (d - r1 + r2) * (d + r1 + r2))
        .max(0.0)
        .sqrt();
    (r1 * r1 * a1 + r2 * r2 * a2 - 0.5 * k) as f32
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};

    /// The closed forms against counting a fine grid of points, for random placements.
    #[test]
    fn areas_match_point_counting() {
        let mut rng = rand_pcg::Pcg64Mcg::seed_from_u64(3);
        let grid = 600;
        for _ in 0..60 {
            let r = rng.random_range(0.2f32..1.0);
            let (x0, y0) = (
                rng.random_range(-1.5f32..0.5),
                rng.random_range(-1.5f32..0.5),
            );
            let (x1, y1) = (
                x0 + rng.random_range(0.1f32..2.0),
                y0 + rng.random_range(0.1f32..2.0),
            );
            let d = rng.random_range(0.0f32..1.5);
            let r2 = rng.random_range(0.2f32..1.5);
            let (mut rect, mut lens) = (0u32, 0u32);
            for i in 0..grid {
                for j in 0..grid {
                    let x = -r + 2.0 * r * (i as f32 + 0.5) / grid as f32;
                    let y = -r + 2.0 * r * (j as f32 + 0.5) / grid as f32;
                    if x * x + y * y > r * r {
                        continue;
                    }
                    rect += (x >= x0 && x <= x1 && y >= y0 && y <= y1) as u32;
                    lens += ((x - d).powi(2) + y * y <= r2 * r2) as u32;
                }
            }
            let cell = (2.0 * r / grid as f32).powi(2);
            let want_rect = rect as f32 * cell;
            let want_lens = lens as f32 * cell;
            let got_rect = circle_rectangle_area(r, x0, x1, y0, y1);
            let got_lens = lens_area(d, r, r2);
            let tol = 0.01 * PI * r * r;
            assert!(
                (got_rect - want_rect).abs() < tol,
                "rect {got_rect} vs {want_rect}"
            );
            assert!(
                (got_lens - want_lens).abs() < tol,
                "lens {got_lens} vs {want_lens}"
            );
        }
        assert!((circle_rectangle_area(1.0, -2.0, 2.0, -2.0, 2.0) - PI).abs() < 1e-5);
        assert!((circle_rectangle_area(1.0, 0.0, 2.0, -2.0, 2.0) - 0.5 * PI).abs() < 1e-5);
        assert!((circle_rectangle_area(1.0, 0.0, 2.0, 0.0, 2.0) - 0.25 * PI).abs() < 1e-5);
    }
}
