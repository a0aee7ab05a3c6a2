//! The albedo keys that lambert, glossy and mirror share: `albedo` (a reflectance spectrum),
//! `texture` (an RGB image multiplying it) and `allow_energy_gain`. A reflectance above 1 makes
//! light from nothing, so it is refused unless the material says it is meant.

use std::sync::Arc;

use super::texture::TextureDesc;
use crate::material::Albedo;
use crate::scene::builder::Builder;
use crate::scene::check::{Checker, above_one};
use crate::scene::error::SceneError;
use crate::scene::spectrum_desc::SpectrumRef;
use crate::spectrum::Spectrum;

/// A material's albedo keys.
#[derive(Clone, Copy)]
pub struct AlbedoKeys<'a> {
    pub albedo: Option<&'a SpectrumRef>,
    pub texture: Option<&'a TextureDesc>,
    pub allow_energy_gain: bool,
}

impl AlbedoKeys<'_> {
    /// `required`: the material needs `albedo` or `texture` (a diffuse surface has no
    /// natural default colour).
    pub fn check(&self, c: &mut Checker, key: &str, required: bool) {
        if let Some(a) = self.albedo {
            c.reflectance_ref(&format!("{key}.albedo"), a, self.allow_energy_gain);
        }
        if let Some(t) = self.texture {
            t.check(c, &format!("{key}.texture"));
        }
        if required && self.albedo.is_none() && self.texture.is_none() {
            c.fail(key, "needs `albedo` or `texture`");
        }
    }

    /// The albedo spectrum (1 if absent). With `allow_energy_gain`, an RGB triple above 1 is
    /// upsampled at its largest component 1 and scaled (the reflectance upsampling is bounded).
    pub fn constant(&self, b: &Builder, key: &str) -> Result<Spectrum, SceneError> {
        let key = format!("{key}.albedo");
        let s = match self.albedo {
            None => Spectrum::splat(1.0, b.grid.n),
            Some(SpectrumRef::Rgb(rgb)) if self.allow_energy_gain && max3(*rgb) > 1.0 => {
                let m = max3(*rgb);
                b.spectra
                    .reflectance(&SpectrumRef::Rgb(rgb.map(|c| c / m)), &key)?
                    * m as f32
            }
            Some(a) => b.spectra.reflectance(a, &key)?,
        };
        let max = s.max_value();
        if max > 1.0 && !self.allow_energy_gain {
            return Err(b.source.invalid(&key, above_one(max as f64)));
        }
        Ok(s)
    }

    /// The albedo at a hit: the constant, or the texture times it.
    pub fn surface(&self, b: &Builder, key: &str) -> Result<Albedo, SceneError> {
        let value = self.constant(b, key)?;
        let Some(t) = self.texture else {
            return Ok(value.into());
        };
        let key = format!("{key}.texture");
        // Surfaces a broken upsampling table as an error before texels are converted.
        b.spectra.reflectance(&SpectrumRef::Rgb([0.5; 3]), &key)?;
        let gain = self.allow_energy_gain;
        let convert = |rgb: [f32; 3]| {
            let m = rgb[0].max(rgb[1]).max(rgb[2]);
            if gain && m > 1.0 {
                b.spectra.rgb_reflectance(rgb.map(|c| c / m)) * m * value
            } else {
                b.spectra.rgb_reflectance(rgb) * value
            }
        };
        let loaded = t.load(b, &key, b.grid.n, &convert)?;
        if loaded.max > 1.0 && !gain {
            return Err(b.source.invalid(&key, above_one(loaded.max as f64)));
        }
        if loaded.min < 0.0 {
            return Err(b.source.invalid(
                &key,
                format!(
                    "holds a negative value ({}): a reflectance is >= 0",
                    loaded.min
                ),
            ));
        }
        Ok(Arc::new(loaded.texture).into())
    }
}

fn max3(v: [f64; 3]) -> f64 {
    v[0].max(v[1]).max(v[2])
}
