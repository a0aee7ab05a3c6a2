//! The box as an analytic primitive: one slab test instead of twelve triangles.
//!
//! Fog is mostly held in boxes whose faces are index-matched boundaries, and every camera and
//! forward flight inside one ends at one of its faces, so the box test is among the hottest
//! geometry of a render. Its faces, normals and uvs are those boxes had as triangles
//! (tests/geometry_box.rs checks them against that mesh): each face has uv (0, 0) at the corner
//! `centre - u - v` and (1, 1) at `centre + u + v` of its in-plane axes, `u x v` outward.

use glam::{Vec2, Vec3, Vec3A, vec2};

/// An axis of a face: its local axis index and sign.
type Axis = (usize, f32);

/// A face's outward axis, then its u and v axes.
type Face = (Axis, Axis, Axis);

/// Per face (outward local axis index and sign), the in-plane axes (index, sign) of its u and v:
/// +X (Y, Z), -X (Z, Y), +Y (Z, X), -Y (X, Z), +Z (X, Y), -Z (Y, X).
const FACES: [Face; 6] = [
    ((0, 1.0), (1, 1.0), (2, 1.0)),
    ((0, -1.0), (2, 1.0), (1, 1.0)),
    ((1, 1.0), (2, 1.0), (0, 1.0)),
    ((1, -1.0), (0, 1.0), (2, 1.0)),
    ((2, 1.0), (0, 1.0), (1, 1.0)),
    ((2, -1.0), (1, 1.0), (0, 1.0)),
];

/// Nearest crossing of the box `[-half, half]` by `o + t d` (local frame) in `(0, t_max)`: the
/// entry from outside, the exit from inside; infinity when there is none. An axis-parallel ray
/// gets infinite bounds from the slabs it runs along; on a slab's own plane a bound is NaN, and
/// every comparison with NaN fails, so such a ray (of measure zero) misses.
#[inline]
pub(super) fn hit(o: Vec3, d: Vec3, half: Vec3, t_max: f32) -> f32 {
    let (o, h) = (Vec3A::from(o), Vec3A::from(half));
    let inv = Vec3A::from(d).recip();
    let a = (-h - o) * inv;
    let b = (h - o) * inv;
    let near = a.min(b).max_element();
    let far = a.max(b).min_element();
    if near.is_nan() || far.is_nan() || near > far {
        return f32::INFINITY;
    }
    if near > 0.0 && near < t_max {
        near
    } else if far > 0.0 && far < t_max {
        far
    } else {
        f32::INFINITY
    }
}

/// The face index (into [`FACES`]) a local point on the box lies on: the axis along which it is
/// furthest out relative to the half size.
fn face_of(lp: Vec3, half: Vec3) -> usize {
    let l = lp / half;
    let axis = l.abs().max_position();
    2 * axis + usize::from(l[axis] < 0.0)
}

/// Local point (projected onto its face), local outward normal and uv at local point `lp`.
pub(super) fn surface(lp: Vec3, half: Vec3) -> (Vec3, Vec3, Vec2) {
    let ((axis, sign), (iu, su), (iv, sv)) = FACES[face_of(lp, half)];
    let mut p = lp.clamp(-half, half);
    p[axis] = sign * half[axis];
    let mut n = Vec3::ZERO;
    n[axis] = sign;
    let uv = vec2(
        0.5 + 0.5 * su * p[iu] / half[iu],
        0.5 + 0.5 * sv * p[iv] / half[iv],
    );
    (p, n, uv)
}

/// The local centre and the two local half-edge vectors of face `f`.
fn face_frame(f: usize, half: Vec3) -> (Vec3, Vec3, Vec3) {
    let ((axis, sign), (iu, _), (iv, _)) = FACES[f];
    let (mut c, mut du, mut dv) = (Vec3::ZERO, Vec3::ZERO, Vec3::ZERO);
    c[axis] = sign * half[axis];
    du[iu] = half[iu];
    dv[iv] = half[iv];
    (c, du, dv)
}

/// World areas of the six faces under the linear map `vector`.
pub(super) fn face_areas(half: Vec3, vector: impl Fn(Vec3) -> Vec3) -> [f32; 6] {
    std::array::from_fn(|f| {
        let (_, du, dv) = face_frame(f, half);
        4.0 * vector(du).cross(vector(dv)).length()
    })
}

/// A local point uniform over the box's surface (faces picked by their world `areas`, an affine
/// map keeps a face's uniform density uniform) and its local outward normal.
pub(super) fn sample(half: Vec3, areas: &[f32; 6], u: Vec2) -> (Vec3, Vec3) {
    let total: f32 = areas.iter().sum();
    let mut target = u.x * total;
    let mut f = 5;
    for (i, a) in areas.iter().enumerate() {
        if target < *a {
            f = i;
            break;
        }
        target -= a;
    }
    let ux = if areas[f] > 0.0 {
        (target / areas[f]).clamp(0.0, 1.0)
    } else {
        0.5
    };
    let (c, du, dv) = face_frame(f, half);
    let ((axis, sign), _, _) = FACES[f];
    let mut n = Vec3::ZERO;
    n[axis] = sign;
    (c + du * (2.0 * ux - 1.0) + dv * (2.0 * u.y - 1.0), n)
}

#[cfg(test)]
mod tests {
    use super::*;

    const HALF: Vec3 = Vec3::new(0.5, 1.0, 1.5);

    /// Entry from outside, exit from inside, misses behind and beside, and the t_max cut.
    #[test]
    fn slab_entry_exit_and_misses() {
        let d = Vec3::new(1.0, 0.0, 0.0);
        assert_eq!(hit(Vec3::new(-2.0, 0.0, 0.0), d, HALF, 10.0), 1.5);
        assert_eq!(hit(Vec3::ZERO, d, HALF, 10.0), 0.5);
        assert_eq!(hit(Vec3::new(2.0, 0.0, 0.0), d, HALF, 10.0), f32::INFINITY);
        assert_eq!(hit(Vec3::new(-2.0, 1.5, 0.0), d, HALF, 10.0), f32::INFINITY);
        assert_eq!(hit(Vec3::new(-2.0, 0.0, 0.0), d, HALF, 1.0), f32::INFINITY);
        // Along a face's plane: a hit or a miss, never a NaN or a distance off the box.
        let t = hit(Vec3::new(-2.0, 1.0, 0.0), d, HALF, 10.0);
        assert!(t == 1.5 || t == f32::INFINITY, "{t}");
        // Oblique, from inside through a corner's neighbourhood.
        let d = Vec3::new(1.0, 2.0, 3.0).normalize();
        let t = hit(Vec3::ZERO, d, HALF, 10.0);
        assert!(((d * t).abs() - HALF).max_element().abs() < 1e-6, "{t}");
    }

    /// Every face's normal, and uv (a, b) at `c + (2a - 1) u + (2b - 1) v`, so (0, 0) towards
    /// the corner `c - u - v` and (1, 1) towards `c + u + v`, with `u x v` outward.
    #[test]
    fn faces_match_the_triangulated_box() {
        for f in 0..6 {
            let (c, du, dv) = face_frame(f, HALF);
            for (a, b) in [(0.25, 0.75), (0.01, 0.02), (0.97, 0.5)] {
                let q = c + du * (2.0 * a - 1.0) + dv * (2.0 * b - 1.0);
                let (p, n, uv) = surface(q * 1.000_001, HALF);
                assert!((p - q).length() < 1e-5, "face {f}: {p} for {q}");
                assert_eq!(n * HALF, c, "face {f}");
                assert!(uv.abs_diff_eq(vec2(a, b), 1e-5), "face {f}: {uv}");
            }
            assert!(du.cross(dv).dot(c) > 0.0, "face {f}");
        }
    }

    /// Face picks in proportion to area: a chi-square over the six faces (5 degrees of
    /// freedom; 20.5 is the 0.1 % point) at a fixed seed, every point on its face.
    #[test]
    fn sampling_is_uniform_over_faces() {
        use rand::{Rng, SeedableRng};
        let areas = face_areas(HALF, |v| v);
        let total: f32 = areas.iter().sum();
        let mut rng = rand::rngs::StdRng::seed_from_u64(7);
        let n = 60_000;
        let mut count = [0u32; 6];
        for _ in 0..n {
            let (p, normal) = sample(HALF, &areas, Vec2::new(rng.random(), rng.random()));
            let f = face_of(p, HALF);
            count[f] += 1;
            let (_, nf, _) = surface(p, HALF);
            assert_eq!(nf, normal);
            assert!((p.abs() - HALF).max_element() < 1e-5);
        }
        let chi2: f32 = (0..6)
            .map(|f| {
                let e = n as f32 * areas[f] / total;
                (count[f] as f32 - e).powi(2) / e
            })
            .sum();
        assert!(chi2 < 20.5, "chi2 {chi2}, counts {count:?}");
    }
}
