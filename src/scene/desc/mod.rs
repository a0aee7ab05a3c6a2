//! The scene file's typed description: what a TOML scene file (plus `--set` overrides) says,
//! before anything is built. Every struct rejects unknown keys; defaults live here.
//! docs/scene-format.md documents every field; keep the two in step.

mod camera;
mod film;
mod lights;
mod materials;
mod media;
mod shapes;
mod spectra;

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

pub use crate::integrator::settings::{GatherMode, IntegratorDesc, VolumeKind};
pub use camera::{CameraDesc, Projection};
pub use film::FilmDesc;
pub use lights::{LightDesc, LightKind};
pub use materials::{MaterialDesc, MaterialKind};
pub use media::MediumDesc;
pub use shapes::{ShapeDesc, ShapeKindDesc, TransformDesc};
pub use spectra::{PowerLaw, RgbKind, SpectrumDesc, SpectrumRef};

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
    /// Name of the medium filling all space outside every shape (none = vacuum).
    pub medium: Option<String>,
}
