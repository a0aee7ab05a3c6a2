//! `type = "quad"`: a rectangle in the local XY plane, normal +Z.

use glam::Vec2;
use serde::{Deserialize, Serialize};

use crate::scene::array::exact;

use crate::geometry::ShapeKind;
use crate::scene::check::Checker;

#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct QuadDesc {
    /// [width, height], m, centred on the origin.
    #[serde(deserialize_with = "exact")]
    pub size: [f32; 2],
}

impl QuadDesc {
    pub(super) fn check(&self, c: &mut Checker, key: &str) {
        super::cuboid::check_size(c, key, &self.size);
    }

    pub(super) fn build(&self) -> ShapeKind {
        ShapeKind::Quad {
            size: Vec2::from(self.size),
        }
    }
}
