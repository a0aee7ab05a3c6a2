//! A light shut inside an opaque closed shape while the camera is outside it lights nothing the
//! camera can see: without a word the image would be black, or lack that light (a lamp modelled
//! inside its housing with an opaque "lens"). Found when the scene is built, by rays.
//!
//! A light at `p` is *shut in* when every one of [`DIRECTIONS`] rays from `p` (a spherical
//! Fibonacci set) first meets the inside of a surface that does not transmit: a back face
//! (`d . ng > 0`, outward normals) of a shape whose material is not a dielectric. Boundaries
//! without a material (media boundaries) are passed through. The warning is given only when the
//! camera is outside too: the first surface from the light towards the camera is such a back
//! face. A room with the camera inside it (inward-facing walls are front faces from the lamp,
//! and the camera is seen from the lamp or behind a front face) is not warned about.

use glam::Vec3;

use crate::geometry::{Geometry, Hit, Ray, spawn};
use crate::light::Light;
use crate::material::Material;

/// Rays cast from each light.
const DIRECTIONS: usize = 256;

/// Null boundaries passed through on one ray, at most.
const MAX_NULL: usize = 32;

/// What a ray from a light meets first.
enum First {
    /// Nothing, a front face, or a surface that transmits: light can get out this way.
    Open,
    /// The inside of an opaque surface of this shape.
    Wall(u32),
}

/// The lights (indices into `lights`) shut inside an opaque shape that the camera at `camera`
/// is outside of, each with that shape's index.
pub fn shut_in(
    geometry: &Geometry,
    materials: &[Material],
    lights: &[Light],
    camera: Vec3,
) -> Vec<(usize, u32)> {
    let mut out = Vec::new();
    for (i, light) in lights.iter().enumerate() {
        let p = match light {
            Light::Point { position, .. }
            | Light::Spot { position, .. }
            | Light::Laser { position, .. } => *position,
            Light::Directional { .. } | Light::Area { .. } => continue,
        };
        let mut wall = None;
        let all_walls =
            fibonacci().all(|d| match first(geometry, materials, p, d, f32::INFINITY) {
                First::Wall(s) => {
                    wall.get_or_insert(s);
                    true
                }
                First::Open => false,
            });
        if !all_walls {
            continue;
        }
        let to_cam = camera - p;
        let len = to_cam.length();
        if len.is_nan() || len <= 0.0 {
            continue;
        }
        if let First::Wall(s) = first(geometry, materials, p, to_cam / len, len) {
            out.push((i, wall.unwrap_or(s)));
        }
    }
    out
}

/// The first surface with a material along the ray from `p` in direction `d` up to `t_max`.
fn first(geometry: &Geometry, materials: &[Material], p: Vec3, d: Vec3, t_max: f32) -> First {
    let mut ray = Ray { o: p, d };
    let mut left = t_max;
    for _ in 0..MAX_NULL {
        let Some(hit) = geometry.intersect(&ray, left) else {
            return First::Open;
        };
        let shape = geometry.shape(hit.shape);
        match shape.material {
            None => {
                left -= hit.t;
                ray = spawn(hit.p, hit.ng, d);
            }
            Some(m) => return wall_or_open(&hit, d, &materials[m as usize]),
        }
    }
    First::Open
}

fn wall_or_open(hit: &Hit, d: Vec3, material: &Material) -> First {
    if d.dot(hit.ng) > 0.0 && !material.transmits() {
        First::Wall(hit.shape)
    } else {
        First::Open
    }
}

/// `DIRECTIONS` unit vectors spread evenly over the sphere (a spherical Fibonacci lattice).
fn fibonacci() -> impl Iterator<Item = Vec3> {
    let golden = std::f32::consts::PI * (3.0 - 5f32.sqrt());
    (0..DIRECTIONS).map(move |k| {
        let z = 1.0 - (2 * k + 1) as f32 / DIRECTIONS as f32;
        let r = (1.0 - z * z).max(0.0).sqrt();
        let phi = golden * k as f32;
        Vec3::new(r * phi.cos(), r * phi.sin(), z)
    })
}
