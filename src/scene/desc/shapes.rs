use serde::{Deserialize, Serialize};

use super::SpectrumRef;

#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct TransformDesc {
    /// Applied last, in metres.
    pub translate: [f32; 3],
    /// Euler angles in degrees about X, then Y, then Z.
    pub rotate: [f32; 3],
    /// Applied first.
    pub scale: [f32; 3],
}

impl Default for TransformDesc {
    fn default() -> Self {
        Self {
            translate: [0.0; 3],
            rotate: [0.0; 3],
            scale: [1.0; 3],
        }
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum ShapeKindDesc {
    /// `size` = [w, h] in the local XY plane, normal +Z.
    Quad,
    /// `size` = [x, y, z], centred.
    Box,
    /// `radius`, centred.
    Sphere,
    /// `radius`, local XY plane, normal +Z.
    Disc,
    /// Wavefront OBJ `file`.
    Mesh,
}

#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ShapeDesc {
    #[serde(rename = "type")]
    pub kind: ShapeKindDesc,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub size: Option<Vec<f32>>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub radius: Option<f32>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub file: Option<String>,
    /// Material name; absent = index-matched (`null`) boundary that only changes the medium.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub material: Option<String>,
    /// Medium inside the (closed) shape.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub interior: Option<String>,
    /// Medium outside; defaults to the scene's `medium`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub exterior: Option<String>,
    /// Emitted radiance spectrum (W / (m^2 sr nm) before `emit_scale`): makes the shape an area light.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub emit: Option<SpectrumRef>,
    #[serde(default = "one", skip_serializing_if = "is_one")]
    pub emit_scale: f32,
    #[serde(default)]
    pub transform: TransformDesc,
}

fn one() -> f32 {
    1.0
}

fn is_one(v: &f32) -> bool {
    *v == 1.0
}
