//! Which medium a ray is in: derived from the shape it last crossed, never from a running stack,
//! so one misjudged grazing hit cannot corrupt the rest of a path.

use glam::Vec3;

use super::{Geometry, Hit, Ray, spawn};

/// A direction with no special relation to axis-aligned scenes, so that the probe ray of
/// [`Geometry::medium_at`] rarely runs along an edge or face.
const PROBE: Vec3 = Vec3::new(0.529_813_7, 0.254_310_4, 0.809_084_1);
const MAX_CROSSINGS: usize = 256;

impl Geometry {
    /// The medium on the side of the hit surface that `dir` leaves into.
    pub fn medium_after(&self, hit: &Hit, dir: Vec3) -> Option<u32> {
        let s = self.shape(hit.shape);
        if dir.dot(hit.ng) < 0.0 {
            s.interior
        } else {
            s.exterior
        }
    }

    /// The medium containing point `p`: found from the first medium boundary a probe ray from `p`
    /// meets (leaving through it means `p` is inside). Shapes with `interior == exterior` are
    /// skipped. Outside every boundary the answer is `None` (vacuum).
    pub fn medium_at(&self, p: Vec3) -> Option<u32> {
        let mut ray = Ray::new(p, PROBE.normalize());
        for _ in 0..MAX_CROSSINGS {
            let hit = self.intersect(&ray, f32::INFINITY)?;
            let s = self.shape(hit.shape);
            if s.is_medium_boundary() {
                return if ray.d.dot(hit.ng) > 0.0 {
                    s.interior
                } else {
                    s.exterior
                };
            }
            ray = spawn(hit.p, hit.ng, ray.d);
        }
        None
    }
}
