//! Rays, shapes and meshes, the obvhs scene BVH, area sampling and medium-boundary bookkeeping.

mod analytic;
mod bvh;
mod edge;
mod error;
mod limits;
mod media;
mod obj;
mod ray;
pub mod sampling;
mod shape;
mod tessellate;
mod transform;
mod triangle;

pub use bvh::{Geometry, Hit};
pub use error::GeometryError;
pub use limits::{MAX_LENGTH, out_of_range, resolution_at};
pub use obj::load_obj;
pub use ray::{Aabb, Ray, spawn};
pub use shape::{ShapeDesc, ShapeKind};
pub use transform::Transform;
