//! `type = "mirror"`: a perfect specular reflector.

use serde::{Deserialize, Serialize};

use super::albedo::AlbedoKeys;
use crate::material::Material;
use crate::scene::builder::Builder;
use crate::scene::check::Checker;
use crate::scene::error::SceneError;
use crate::scene::spectrum_desc::SpectrumRef;

#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MirrorDesc {
    /// Reflectance; default 1.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub albedo: Option<SpectrumRef>,
    /// Accept a reflectance above 1.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub allow_energy_gain: bool,
}

impl MirrorDesc {
    fn albedo(&self) -> AlbedoKeys<'_> {
        AlbedoKeys {
            albedo: self.albedo.as_ref(),
            texture: None,
            allow_energy_gain: self.allow_energy_gain,
        }
    }

    pub(super) fn check(&self, c: &mut Checker, key: &str) {
        self.albedo().check(c, key, false);
    }

    pub(super) fn build(&self, b: &Builder, key: &str) -> Result<Material, SceneError> {
        Ok(Material::mirror(self.albedo().constant(b, key)?))
    }
}
