//! `type = "dielectric"`: a smooth refractive interface (glass, water).

use serde::{Deserialize, Serialize};

use crate::material::Material;
use crate::scene::builder::Builder;
use crate::scene::check::Checker;
use crate::scene::error::SceneError;
use crate::scene::spectrum_desc::SpectrumRef;

#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DielectricDesc {
    /// Index of refraction inside the shape (outside: 1); dispersion where it varies.
    pub ior: SpectrumRef,
}

impl DielectricDesc {
    pub(super) fn check(&self, c: &mut Checker, key: &str) {
        super::check_ior(c, key, &self.ior);
    }

    pub(super) fn build(&self, b: &Builder, key: &str) -> Result<Material, SceneError> {
        let ior = b.spectra.unbounded(&self.ior, &format!("{key}.ior"))?;
        Ok(Material::dielectric(ior, b.grid.n))
    }
}
