//! `type = "sphere"`: a sphere centred on the origin (before its transform).

use serde::{Deserialize, Serialize};

use crate::geometry::ShapeKind;
use crate::scene::check::Checker;

#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SphereDesc {
    /// m.
    pub radius: f32,
}

impl SphereDesc {
    pub(super) fn check(&self, c: &mut Checker, key: &str) {
        c.length(&format!("{key}.radius"), self.radius);
    }

    pub(super) fn build(&self) -> ShapeKind {
        ShapeKind::Sphere {
            radius: self.radius,
        }
    }
}
