//! `[import]`: what glTF shapes bring besides their meshes and materials.

use serde::{Deserialize, Serialize};

/// The `[import]` table: what glTF files bring besides their meshes and materials.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct ImportDesc {
    /// Add the files' `KHR_lights_punctual` lights to the scene's lights.
    pub lights: bool,
}

impl ImportDesc {
    pub fn is_default(&self) -> bool {
        *self == ImportDesc::default()
    }
}
