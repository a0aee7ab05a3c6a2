//! The scene file's typed description: what a TOML scene file (plus `--set` overrides) says,
//! before anything is built. Every struct rejects unknown keys. The sections without kinds are
//! described here; the camera and each kind of light, shape and material are described beside
//! their checks and builders (`scene/camera.rs`, `scene/lights/`, `scene/shapes/`,
//! `scene/materials/`) and re-exported here. docs/scene-format.md documents every field; keep
//! the two in step.

// Leaf descriptions. The spectrum references and fixed-size arrays every kind uses are
// siblings of this module (`scene/spectrum_desc.rs`, `scene/array.rs`): this module gathers
// the kinds, so a kind (or the checks) reaching into it would close an import cycle.
pub(crate) mod film;
pub(crate) mod import;
pub(crate) mod media;

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};
use toml::Spanned;
use toml::de::DeValue;

pub use super::camera::{CameraDesc, Projection};
pub use super::lights::{
    DirectionalDesc, LaserDesc, LightCommon, LightDesc, LightKind, PointDesc, SpotDesc,
};
pub use super::materials::{
    BlendDesc, ConductorDesc, DielectricDesc, GlossyDesc, LambertDesc, MaterialCommon,
    MaterialDesc, MaterialKind, MirrorDesc, Roughness, TextureDesc, WeightDesc,
};
pub use super::sensors::{
    IlluminanceSensorDesc, LuminanceSensorDesc, SensorCommon, SensorDesc, SensorKindDesc,
};
pub use super::shapes::{
    BoxDesc, DiscDesc, GltfDesc, MeshDesc, QuadDesc, SceneRef, ShapeCommon, ShapeDesc,
    ShapeKindDesc, SphereDesc, TransformDesc,
};
pub use super::spectrum_desc::{PowerLaw, RgbKind, SpectrumDesc, SpectrumRef};
pub use crate::integrator::settings::{GatherMode, IntegratorDesc, VolumeKind};
pub use film::FilmDesc;
pub use import::ImportDesc;
pub use media::MediumDesc;

use super::tagged::{self, Fault};

#[derive(Clone, Debug, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct SceneDesc {
    pub film: FilmDesc,
    pub camera: CameraDesc,
    pub integrator: IntegratorDesc,
    pub spectra: BTreeMap<String, SpectrumDesc>,
    pub materials: BTreeMap<String, MaterialDesc>,
    pub media: BTreeMap<String, MediumDesc>,
    pub shapes: Vec<ShapeDesc>,
    pub lights: Vec<LightDesc>,
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub sensors: Vec<SensorDesc>,
    /// Name of the medium filling all space outside every shape (none = vacuum).
    pub medium: Option<String>,
    /// What glTF shapes bring besides meshes and materials.
    #[serde(skip_serializing_if = "ImportDesc::is_default")]
    pub import: ImportDesc,
}

/// Why the table of `section` (`lights`, `shapes`, `materials`, `sensors`) cannot be read, with the key
/// and span inside it; None for other sections or a table that reads.
pub(crate) fn read_kind_table(section: &str, table: Spanned<DeValue<'_>>) -> Option<Fault> {
    match section {
        "lights" => tagged::read::<LightCommon, LightKind>(table).err(),
        "shapes" => tagged::read::<ShapeCommon, ShapeKindDesc>(table).err(),
        "materials" => tagged::read::<MaterialCommon, MaterialKind>(table).err(),
        "sensors" => tagged::read::<SensorCommon, SensorKindDesc>(table).err(),
        // The other sections are plain serde structs, placed by serde itself.
        _ => None,
    }
}
