//! `type = "box"`: an axis-aligned box centred on the origin (before its transform).

use glam::Vec3;
use serde::{Deserialize, Serialize};

use crate::scene::array::exact;

use crate::geometry::ShapeKind;
use crate::scene::check::Checker;

#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BoxDesc {
    /// [x, y, z] side lengths, m.
    #[serde(deserialize_with = "exact")]
    pub size: [f32; 3],
}

impl BoxDesc {
    pub(super) fn check(&self, c: &mut Checker, key: &str) {
        check_size(c, key, &self.size);
    }

    pub(super) fn build(&self) -> ShapeKind {
        ShapeKind::Box {
            size: Vec3::from(self.size),
        }
    }
}

/// Side lengths: finite and positive.
pub(super) fn check_size(c: &mut Checker, key: &str, size: &[f32]) {
    if size.iter().any(|x| !(x.is_finite() && *x > 0.0)) {
        c.fail(format!("{key}.size"), "sizes must be finite and > 0");
    }
}
