//! `type = "lambert"`: an ideal diffuse reflector.

use serde::{Deserialize, Serialize};

use super::albedo::AlbedoKeys;
use super::texture::{self, TextureDesc};
use crate::material::Material;
use crate::scene::builder::Builder;
use crate::scene::check::Checker;
use crate::scene::error::SceneError;
use crate::scene::spectrum_desc::SpectrumRef;

#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LambertDesc {
    /// Diffuse albedo.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub albedo: Option<SpectrumRef>,
    /// RGB image multiplying the albedo.
    #[serde(
        default,
        deserialize_with = "texture::optional",
        skip_serializing_if = "Option::is_none"
    )]
    pub texture: Option<TextureDesc>,
    /// Accept an albedo above 1 (a surface that creates light).
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub allow_energy_gain: bool,
}

impl LambertDesc {
    fn albedo(&self) -> AlbedoKeys<'_> {
        AlbedoKeys {
            albedo: self.albedo.as_ref(),
            texture: self.texture.as_ref(),
            allow_energy_gain: self.allow_energy_gain,
        }
    }

    pub(super) fn check(&self, c: &mut Checker, key: &str) {
        self.albedo().check(c, key, true);
    }

    pub(super) fn build(&self, b: &Builder, key: &str) -> Result<Material, SceneError> {
        Ok(Material::Lambert {
            albedo: self.albedo().surface(b, key)?,
        })
    }
}
