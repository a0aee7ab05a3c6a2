//! `type = "directional"`: parallel light of a given irradiance (the sun, a distant lamp).

use glam::Vec3;
use serde::{Deserialize, Serialize};

use crate::scene::array::exact;

use super::MAX_IRRADIANCE;
use crate::light::Light;
use crate::scene::check::Checker;
use crate::spectrum::Spectrum;

#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DirectionalDesc {
    /// W/m^2 on a plane normal to `direction`.
    pub irradiance: f32,
    /// Direction light travels in.
    #[serde(deserialize_with = "exact")]
    pub direction: [f32; 3],
}

impl DirectionalDesc {
    pub(super) fn check(&self, c: &mut Checker, key: &str) {
        c.bounded(
            &format!("{key}.irradiance"),
            self.irradiance,
            MAX_IRRADIANCE,
            "W/m^2",
            "accepted for a light (the film's sums would overflow)",
        );
        c.direction(&format!("{key}.direction"), self.direction);
    }

    /// `unit`: the light's spectrum normalised to 1 W/m^2. Integration volumes reach up to
    /// `radius` beyond the geometry, so the beam is grown by it (see `Light::with_beam_margin`).
    pub(super) fn build(&self, unit: Spectrum, radius: f32) -> Light {
        Light::directional(
            Vec3::from(self.direction).normalize(),
            unit * self.irradiance,
        )
        .with_beam_margin(radius)
    }
}
