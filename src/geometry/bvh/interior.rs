//! Where a medium is bounded: the box around the shapes that hold it inside (a density field
//! defined by a formula is sampled over that box, `medium::density::noise`).

use glam::Vec3;

use super::Geometry;
use crate::geometry::Aabb;

impl Geometry {
    /// The box around every shape whose interior is medium `m`, None when no shape's is.
    pub fn interior_bounds(&self, m: u32) -> Option<Aabb> {
        let inside = |shape: u32| self.shapes[shape as usize].interior == Some(m);
        let (mut lo, mut hi) = (Vec3::INFINITY, Vec3::NEG_INFINITY);
        for (tri, &shape) in self.tris.iter().zip(&self.tri_shape) {
            if inside(shape) {
                for v in tri.v {
                    (lo, hi) = (lo.min(v.into()), hi.max(v.into()));
                }
            }
        }
        for a in self.analytic.iter().filter(|a| inside(a.shape)) {
            let (a, b) = a.bounds();
            (lo, hi) = (lo.min(a), hi.max(b));
        }
        lo.cmple(hi).all().then_some(Aabb { min: lo, max: hi })
    }
}
