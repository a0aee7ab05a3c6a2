//! `type = "disc"`: a disc in the local XY plane, normal +Z.

use serde::{Deserialize, Serialize};

use crate::geometry::ShapeKind;
use crate::scene::check::Checker;

#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DiscDesc {
    /// m.
    pub radius: f32,
}

impl DiscDesc {
    pub(super) fn check(&self, c: &mut Checker, key: &str) {
        c.length(&format!("{key}.radius"), self.radius);
    }

    pub(super) fn build(&self) -> ShapeKind {
        ShapeKind::Disc {
            radius: self.radius,
        }
    }
}
