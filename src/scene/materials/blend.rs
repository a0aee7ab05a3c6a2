//! `type = "blend"`: two named materials mixed by a weight, f = (1 - w) first + w second (as
//! Mitsuba's `blendbsdf`), e.g. a glossy coat over part of a diffuse floor.

use std::sync::Arc;

use serde::{Deserialize, Serialize};

use super::texture::WeightDesc;
use crate::material::{BlendWeight, Material};
use crate::scene::builder::Builder;
use crate::scene::check::Checker;
use crate::scene::error::SceneError;
use crate::spectrum::Spectrum;

#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BlendDesc {
    /// Material seen where the weight is 0.
    pub first: String,
    /// Material seen where the weight is 1.
    pub second: String,
    /// Weight of `second`: a number in [0, 1] or a texture (its linear luminance).
    pub weight: WeightDesc,
}

impl BlendDesc {
    pub(super) fn check(&self, c: &mut Checker, key: &str) {
        for (k, name) in [("first", &self.first), ("second", &self.second)] {
            c.material(&format!("{key}.{k}"), name);
        }
        let key = format!("{key}.weight");
        match &self.weight {
            WeightDesc::Constant(w) => c.range(&key, *w as f64, 0.0, 1.0, "in [0, 1]"),
            WeightDesc::Texture(t) => t.check(c, &key),
        }
    }

    /// The blend of the built `first` and `second`.
    pub(super) fn build(
        &self,
        b: &Builder,
        key: &str,
        first: Material,
        second: Material,
    ) -> Result<Material, SceneError> {
        let weight = match &self.weight {
            WeightDesc::Constant(w) => BlendWeight::Constant(*w),
            WeightDesc::Texture(t) => {
                let key = format!("{key}.weight");
                // One bin: the Rec. 709 luminance of the linear RGB (the value for grey masks).
                let luminance =
                    |c: [f32; 3]| Spectrum::splat(0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2], 1);
                let loaded = t.load(b, &key, 1, &luminance)?;
                let (lo, hi) = loaded.texture.value_range();
                if lo < 0.0 || hi > 1.0 {
                    return Err(b.source.invalid(
                        &key,
                        format!("a weight texture's values must lie in [0, 1], found {lo}..{hi}"),
                    ));
                }
                BlendWeight::Texture(Arc::new(loaded.texture))
            }
        };
        Ok(Material::blend(first, second, weight))
    }
}
