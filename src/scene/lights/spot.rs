//! `type = "spot"`: a point light under a conical shade with a soft edge.

use glam::Vec3;
use serde::{Deserialize, Serialize};

use crate::scene::array::exact;

use crate::light::Light;
use crate::scene::check::Checker;
use crate::spectrum::Spectrum;

#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SpotDesc {
    /// Total emitted power, W.
    pub power: f32,
    #[serde(deserialize_with = "exact")]
    pub position: [f32; 3],
    /// Axis of the cone: the direction light travels in.
    #[serde(deserialize_with = "exact")]
    pub direction: [f32; 3],
    /// Half-angle of the cone, degrees.
    pub angle: f32,
    /// Width of the soft edge inside the cone, degrees (0: a hard edge).
    #[serde(default)]
    pub soft_edge: f32,
}

impl SpotDesc {
    pub(super) fn check(&self, c: &mut Checker, key: &str) {
        super::check_power(c, key, self.power);
        c.vector(&format!("{key}.position"), self.position);
        c.direction(&format!("{key}.direction"), self.direction);
        c.range(
            &format!("{key}.angle"),
            self.angle as f64,
            1e-3,
            90.0,
            "in (0, 90] degrees",
        );
        c.range(
            &format!("{key}.soft_edge"),
            self.soft_edge as f64,
            0.0,
            90.0,
            "in [0, 90] degrees",
        );
    }

    /// `unit`: the light's spectrum normalised to 1 W.
    pub(super) fn build(&self, unit: Spectrum) -> Light {
        Light::spot(
            self.position.into(),
            Vec3::from(self.direction).normalize(),
            unit * self.power,
            self.angle,
            self.soft_edge,
        )
    }
}
