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

/// Side lengths: finite, positive and within what the geometry holds.
pub(super) fn check_size(c: &mut Checker, key: &str, size: &[f32]) {
    let key = format!("{key}.size");
    if size.iter().any(|x| !(x.is_finite() && *x > 0.0)) {
        c.fail(key, "sizes must be finite and > 0");
    } else {
        let largest = size.iter().copied().fold(0.0, f32::max);
        c.within_geometry(&key, largest);
    }
}
