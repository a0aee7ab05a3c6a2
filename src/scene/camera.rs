//! `[camera]`: its keys and defaults, their checks, and the runtime [`Camera`].

use glam::Vec3;
use serde::{Deserialize, Serialize};

use crate::scene::array::exact;

use super::check::Checker;
use crate::camera::Camera;

/// Largest image side and pixel count accepted (beyond this the film alone would exhaust memory).
pub const MAX_SIDE: u32 = 32_768;
pub const MAX_PIXELS: u64 = 1 << 27;
/// Vertical field of view of a perspective camera that gives none, degrees.
pub const DEFAULT_FOV: f32 = 40.0;
/// Viewed rectangle of an orthographic camera that gives none, metres.
pub const DEFAULT_VIEW: f32 = 1.0;
/// Smallest angle between `up` and the view direction, degrees: below it the image's
/// orientation hangs on rounding.
const MIN_UP_ANGLE: f32 = 0.1;

#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Projection {
    /// Parallel projection; `view_width` x `view_height` metres are seen.
    Orthographic,
    #[default]
    Perspective,
}

#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct CameraDesc {
    #[serde(rename = "type")]
    pub projection: Projection,
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    #[serde(deserialize_with = "exact")]
    pub position: [f32; 3],
    #[serde(deserialize_with = "exact")]
    pub look_at: [f32; 3],
    #[serde(deserialize_with = "exact")]
    pub up: [f32; 3],
    /// Vertical field of view in degrees (perspective only; default [`DEFAULT_FOV`]).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub fov: Option<f32>,
    /// Width and height in metres of the viewed rectangle (orthographic only; default
    /// [`DEFAULT_VIEW`]).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub view_width: Option<f32>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub view_height: Option<f32>,
}

impl Default for CameraDesc {
    fn default() -> Self {
        Self {
            projection: Projection::Perspective,
            width: 256,
            height: 256,
            position: [0.0, 0.0, 5.0],
            look_at: [0.0, 0.0, 0.0],
            up: [0.0, 1.0, 0.0],
            fov: None,
            view_width: None,
            view_height: None,
        }
    }
}

impl CameraDesc {
    pub fn check(&self, c: &mut Checker, key: &str) {
        for (k, v) in [("width", self.width), ("height", self.height)] {
            if !(1..=MAX_SIDE).contains(&v) {
                c.fail(
                    format!("{key}.{k}"),
                    format!("must be in 1..={MAX_SIDE} pixels, got {v}"),
                );
            }
        }
        if self.width as u64 * self.height as u64 > MAX_PIXELS {
            c.fail(
                format!("{key}.width"),
                format!("the image has more than {MAX_PIXELS} pixels"),
            );
        }
        c.point(&format!("{key}.position"), self.position);
        c.point(&format!("{key}.look_at"), self.look_at);
        c.direction(&format!("{key}.up"), self.up);
        if self.position == self.look_at {
            c.fail(format!("{key}.look_at"), "must differ from camera.position");
        } else if self.up_is_along_view() {
            c.fail(
                format!("{key}.up"),
                format!(
                    "is parallel to the view direction (look_at - position): the image's \
                     orientation is undefined; give an up direction at least {MIN_UP_ANGLE} \
                     degrees away from it"
                ),
            );
        }
        self.check_projection(c, key);
    }

    /// The keys of the projection in use; the other projection's keys are refused.
    fn check_projection(&self, c: &mut Checker, key: &str) {
        match self.projection {
            Projection::Perspective => {
                if let Some(fov) = self.fov {
                    c.range(
                        &format!("{key}.fov"),
                        fov as f64,
                        1e-3,
                        179.0,
                        "in (0, 179] degrees",
                    );
                }
                for (k, v) in [
                    ("view_width", self.view_width),
                    ("view_height", self.view_height),
                ] {
                    if v.is_some() {
                        c.fail(
                            format!("{key}.{k}"),
                            "applies to orthographic cameras only (this one is perspective)",
                        );
                    }
                }
            }
            Projection::Orthographic => {
                for (k, v) in [
                    ("view_width", self.view_width),
                    ("view_height", self.view_height),
                ] {
                    if let Some(v) = v {
                        c.length(&format!("{key}.{k}"), v);
                    }
                }
                if self.fov.is_some() {
                    c.fail(
                        format!("{key}.fov"),
                        "applies to perspective cameras only (this one is orthographic)",
                    );
                }
            }
        }
    }

    /// Whether `up` is (nearly) parallel to the view direction, or so small that it has none.
    fn up_is_along_view(&self) -> bool {
        let forward = (Vec3::from(self.look_at) - Vec3::from(self.position)).normalize_or_zero();
        let up = Vec3::from(self.up).normalize_or_zero();
        if forward == Vec3::ZERO || up == Vec3::ZERO {
            return false;
        }
        forward.cross(up).length() < MIN_UP_ANGLE.to_radians().sin()
    }

    pub fn build(&self) -> Camera {
        let (position, look_at, up) = (self.position.into(), self.look_at.into(), self.up.into());
        match self.projection {
            Projection::Orthographic => Camera::orthographic(
                self.width,
                self.height,
                position,
                look_at,
                up,
                self.view_width.unwrap_or(DEFAULT_VIEW),
                self.view_height.unwrap_or(DEFAULT_VIEW),
            ),
            Projection::Perspective => Camera::perspective(
                self.width,
                self.height,
                position,
                look_at,
                up,
                self.fov.unwrap_or(DEFAULT_FOV),
            ),
        }
    }
}
