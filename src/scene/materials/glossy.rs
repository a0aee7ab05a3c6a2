//! `type = "glossy"`: a diffuse base under a GGX coat (the paper's "slightly specular" floor).

use serde::{Deserialize, Serialize};

use super::albedo::AlbedoKeys;
use super::texture::{self, TextureDesc};
use crate::material::{MIN_ROUGHNESS, Material};
use crate::scene::builder::Builder;
use crate::scene::check::Checker;
use crate::scene::error::SceneError;
use crate::scene::spectrum_desc::SpectrumRef;

/// Index of refraction of the coat when none is given (varnish, plastic).
pub const DEFAULT_IOR: f64 = 1.5;
/// GGX alpha of the coat when none is given.
pub const DEFAULT_ROUGHNESS: f32 = 0.1;

#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GlossyDesc {
    /// Albedo of the diffuse base.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub albedo: Option<SpectrumRef>,
    /// RGB image multiplying the albedo.
    #[serde(
        default,
        deserialize_with = "texture::optional",
        skip_serializing_if = "Option::is_none"
    )]
    pub texture: Option<TextureDesc>,
    /// Index of refraction of the coat (its first bin sets the coat's reflectance).
    #[serde(default = "default_ior")]
    pub ior: SpectrumRef,
    /// GGX alpha of the coat.
    #[serde(default = "default_roughness")]
    pub roughness: f32,
    /// Accept an albedo above 1.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub allow_energy_gain: bool,
}

fn default_ior() -> SpectrumRef {
    SpectrumRef::Constant(DEFAULT_IOR)
}

fn default_roughness() -> f32 {
    DEFAULT_ROUGHNESS
}

impl GlossyDesc {
    fn albedo(&self) -> AlbedoKeys<'_> {
        AlbedoKeys {
            albedo: self.albedo.as_ref(),
            texture: self.texture.as_ref(),
            allow_energy_gain: self.allow_energy_gain,
        }
    }

    pub(super) fn check(&self, c: &mut Checker, key: &str) {
        self.albedo().check(c, key, true);
        super::check_ior(c, key, &self.ior);
        // Compared as stored (f32), so that the documented bound itself is accepted.
        c.range_f32(
            &format!("{key}.roughness"),
            self.roughness,
            MIN_ROUGHNESS,
            1.0,
            "in [1e-4, 1]",
        );
    }

    pub(super) fn build(&self, b: &Builder, key: &str) -> Result<Material, SceneError> {
        let surface = self.albedo().surface(b, key)?;
        let ior = b.spectra.unbounded(&self.ior, &format!("{key}.ior"))?;
        Ok(Material::glossy(surface, ior[0], self.roughness, b.grid.n))
    }
}
