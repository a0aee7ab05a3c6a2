use serde::{Deserialize, Serialize};

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
    pub position: [f32; 3],
    pub look_at: [f32; 3],
    pub up: [f32; 3],
    /// Vertical field of view in degrees (perspective).
    pub fov: f32,
    /// Width and height in metres of the viewed rectangle (orthographic).
    pub view_width: f32,
    pub view_height: f32,
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
            fov: 40.0,
            view_width: 1.0,
            view_height: 1.0,
        }
    }
}
