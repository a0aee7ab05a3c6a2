//! `type = "point"`: an isotropic point light.

use serde::{Deserialize, Serialize};

use crate::scene::array::exact;

use crate::light::Light;
use crate::scene::check::Checker;
use crate::spectrum::Spectrum;

#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PointDesc {
    /// Total emitted power, W.
    pub power: f32,
    #[serde(deserialize_with = "exact")]
    pub position: [f32; 3],
}

impl PointDesc {
    pub(super) fn check(&self, c: &mut Checker, key: &str) {
        super::check_power(c, key, self.power);
        c.vector(&format!("{key}.position"), self.position);
    }

    /// `unit`: the light's spectrum normalised to 1 W.
    pub(super) fn build(&self, unit: Spectrum) -> Light {
        Light::point(self.position.into(), unit * self.power)
    }
}
