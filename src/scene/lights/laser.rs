//! `type = "laser"`: a collimated beam of uniform circular cross-section.

use glam::Vec3;
use serde::{Deserialize, Serialize};

use crate::scene::array::exact;

use crate::light::Light;
use crate::scene::check::Checker;
use crate::spectrum::Spectrum;

#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LaserDesc {
    /// Total emitted power, W.
    pub power: f32,
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
    pub(super) fn check(&self, c: &mut Checker, key: &str) {
        super::check_power(c, key, self.power);
        c.vector(&format!("{key}.position"), self.position);
        c.direction(&format!("{key}.direction"), self.direction);
        c.positive(&format!("{key}.radius"), self.radius as f64);
    }

    /// `unit`: the light's spectrum normalised to 1 W.
    pub(super) fn build(&self, unit: Spectrum) -> Light {
        Light::laser(
            self.position.into(),
            Vec3::from(self.direction).normalize(),
            self.radius,
            unit * self.power,
        )
    }
}
