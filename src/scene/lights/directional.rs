//! `type = "directional"`: parallel light of a given irradiance (the sun, a distant lamp).

use glam::Vec3;
use serde::{Deserialize, Serialize};

use super::MAX_IRRADIANCE;
use super::amount::{self, Amount, Given};
use crate::light::Light;
use crate::scene::array::exact;
use crate::scene::builder::Builder;
use crate::scene::check::Checker;
use crate::scene::error::SceneError;
use crate::spectrum::Spectrum;

#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DirectionalDesc {
    /// W/m^2 on a plane normal to `direction`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub irradiance: Option<f32>,
    /// lx on a plane normal to `direction`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub illuminance: Option<f32>,
    /// Direction light travels in.
    #[serde(deserialize_with = "exact")]
    pub direction: [f32; 3],
}

impl DirectionalDesc {
    fn given(&self) -> Given {
        Given(vec![
            ("irradiance", self.irradiance, Amount::Radiant),
            ("illuminance", self.illuminance, Amount::Illuminance),
        ])
    }

    pub(super) fn check(&self, c: &mut Checker, key: &str) {
        self.given().check(c, key, false);
        if let Some(e) = self.irradiance {
            c.bounded(
                &format!("{key}.irradiance"),
                e,
                MAX_IRRADIANCE,
                "W/m^2",
                "accepted for a light (the film's sums would overflow)",
            );
        }
        c.direction(&format!("{key}.direction"), self.direction);
    }

    /// `unit`: the light's spectrum normalised to 1 W/m^2. Integration volumes reach up to
    /// `radius` beyond the geometry, so the beam is grown by it (see `Light::with_beam_margin`).
    pub(super) fn build(
        &self,
        b: &Builder,
        key: &str,
        unit: Spectrum,
    ) -> Result<Light, SceneError> {
        let Some(amount) = self.given().amount() else {
            return Err(b.source.invalid(key, "give `irradiance` or `illuminance`"));
        };
        let e = amount::radiant(b, key, amount, &unit, 0.0)?;
        if e > MAX_IRRADIANCE {
            return Err(b.source.invalid(
                key,
                format!("{e} W/m^2 is above the {MAX_IRRADIANCE:e} W/m^2 accepted for a light"),
            ));
        }
        Ok(
            Light::directional(Vec3::from(self.direction).normalize(), unit * e)
                .with_beam_margin(b.radius),
        )
    }
}
