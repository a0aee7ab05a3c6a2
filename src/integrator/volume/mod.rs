//! Gather-volume geometry and weights (method notes 1, 5): pure functions on `glam::Vec3` in f32.
//!
//! Conventions: the camera ray direction `u` points from the camera into the scene; a forward
//! ray travels along `v`; distances along the forward segment are `lam` (from its origin), along
//! the camera segment `tau` (from the cylinder's origin). The phase function is evaluated at
//! `cos = -u.v` (light turning from `v` towards the camera), see `medium::HenyeyGreenstein`.
//!
//! Every "weight" returned here excludes the phase function, the forward flux and the camera
//! throughput: the engine multiplies `weight_l * f * Phi_l * W_l`.

mod bounds;
mod cylinder;
mod long;
mod quadrature;
mod sphere;
mod truncated;

pub use bounds::{Aabb, capsule_aabb, cylinder_aabb, segment_aabb, sphere_aabb};
pub use cylinder::{CameraAxis, CylinderChord, cylinder_eq2, eq2_factor, segment_cylinder};
pub use long::{long_eq3_exact, long_eq3_paper};
pub use quadrature::{GL4_NODES, GL4_WEIGHTS, chord_integral, panels_for};
pub use sphere::{SphereChord, crossing_density, segment_sphere, track_length_density};
pub use truncated::{cylinder_eq2_fwd, cylinder_truncated};
