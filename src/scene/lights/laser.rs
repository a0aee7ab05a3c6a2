//! `type = "laser"`: a collimated beam of uniform circular cross-section.

use glam::Vec3;
use serde::{Deserialize, Serialize};

use super::amount::{self, Amount, Given};
use crate::light::Light;
use crate::scene::array::exact;
use crate::scene::builder::Builder;
use crate::scene::check::Checker;
use crate::scene::error::SceneError;
use crate::spectrum::Spectrum;

#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LaserDesc {
    /// Total emitted power, W.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub power: Option<f32>,
    /// Luminous flux of the beam, lm.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub luminous_flux: Option<f32>,
    /// Centre of the beam's start disc.
    #[serde(deserialize_with = "exact")]
    pub position: [f32; 3],
    /// Direction the beam travels in.
    #[serde(deserialize_with = "exact")]
    pub direction: [f32; 3],
    /// Beam radius, m.
    pub radius: f32,
}

impl LaserDesc {
    fn given(&self) -> Given {
        Given(vec![
            ("power", self.power, Amount::Radiant),
            ("luminous_flux", self.luminous_flux, Amount::LuminousFlux),
        ])
    }

    pub(super) fn check(&self, c: &mut Checker, key: &str) {
        self.given().check(c, key, false);
        if let Some(p) = self.power {
            super::check_power(c, key, p);
        }
        c.point(&format!("{key}.position"), self.position);
        c.direction(&format!("{key}.direction"), self.direction);
        c.length(&format!("{key}.radius"), self.radius);
    }

    /// `unit`: the light's spectrum normalised to 1 W.
    pub(super) fn build(
        &self,
        b: &Builder,
        key: &str,
        unit: Spectrum,
    ) -> Result<Light, SceneError> {
        let Some(amount) = self.given().amount() else {
            return Err(b.source.invalid(key, "give `power` or `luminous_flux`"));
        };
        let w = amount::radiant(b, key, amount, &unit, 0.0)?;
        Ok(Light::laser(
            self.position.into(),
            Vec3::from(self.direction).normalize(),
            self.radius,
            unit * w,
        ))
    }
}
