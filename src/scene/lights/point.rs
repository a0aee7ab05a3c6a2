//! `type = "point"`: an isotropic point light, or one with a photometric profile (IES file).

use std::f64::consts::PI;

use glam::Vec3;
use serde::{Deserialize, Serialize};

use super::amount::{self, Amount, Given};
use crate::light::Light;
use crate::scene::array::{exact, exact_opt};
use crate::scene::builder::Builder;
use crate::scene::check::Checker;
use crate::scene::error::SceneError;
use crate::spectrum::Spectrum;

#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PointDesc {
    /// Total emitted power, W.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub power: Option<f32>,
    /// Total luminous flux, lm.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub luminous_flux: Option<f32>,
    /// Luminous intensity, cd (the peak intensity of a profile).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub intensity: Option<f32>,
    #[serde(deserialize_with = "exact")]
    pub position: [f32; 3],
    /// IES LM-63 file (type C) giving the distribution, relative to the scene file.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub profile: Option<String>,
    /// Where the profile's gamma = 0 axis (its nadir) points; default straight down (-Y).
    #[serde(
        default,
        deserialize_with = "exact_opt",
        skip_serializing_if = "Option::is_none"
    )]
    pub direction: Option<[f32; 3]>,
    /// Towards which the profile's C = 0 half-plane lies.
    #[serde(
        default,
        deserialize_with = "exact_opt",
        skip_serializing_if = "Option::is_none"
    )]
    pub profile_c0: Option<[f32; 3]>,
}

impl PointDesc {
    fn given(&self) -> Given {
        Given(vec![
            ("power", self.power, Amount::Radiant),
            ("luminous_flux", self.luminous_flux, Amount::LuminousFlux),
            ("intensity", self.intensity, Amount::Intensity),
        ])
    }

    pub(super) fn check(&self, c: &mut Checker, key: &str) {
        self.given().check(c, key, self.profile.is_some());
        if let Some(p) = self.power {
            super::check_power(c, key, p);
        }
        c.point(&format!("{key}.position"), self.position);
        let orient = [
            ("direction", self.direction),
            ("profile_c0", self.profile_c0),
        ];
        amount::check_orientation(c, key, self.profile.as_deref(), &orient);
    }

    /// `unit`: the light's spectrum normalised to 1 W.
    pub(super) fn build(
        &self,
        b: &Builder,
        key: &str,
        unit: Spectrum,
    ) -> Result<Light, SceneError> {
        let position = Vec3::from(self.position);
        let amount = self.given().amount();
        let Some(file) = &self.profile else {
            let Some(amount) = amount else {
                return Err(b
                    .source
                    .invalid(key, "give `power`, `luminous_flux` or `intensity`"));
            };
            let w = amount::radiant(b, key, amount, &unit, 1.0 / (4.0 * PI))?;
            return Ok(Light::point(position, unit * w));
        };
        let axis = self.direction.unwrap_or([0.0, -1.0, 0.0]);
        super::profiled(
            b,
            key,
            file,
            position,
            amount::profile_frame(axis, self.profile_c0),
            amount,
            unit,
        )
    }
}
