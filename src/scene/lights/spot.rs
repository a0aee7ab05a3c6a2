//! `type = "spot"`: a point light under a conical shade with a soft edge, or aimed along its
//! axis with a photometric profile (IES file).

use glam::Vec3;
use serde::{Deserialize, Serialize};

use super::amount::{self, Amount, Given};
use crate::light::{Light, SpotProfile};
use crate::scene::array::{exact, exact_opt};
use crate::scene::builder::Builder;
use crate::scene::check::Checker;
use crate::scene::error::SceneError;
use crate::spectrum::Spectrum;

#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SpotDesc {
    /// Total emitted power, W.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub power: Option<f32>,
    /// Total luminous flux, lm.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub luminous_flux: Option<f32>,
    /// Peak luminous intensity (on the axis of a cone), cd.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub intensity: Option<f32>,
    #[serde(deserialize_with = "exact")]
    pub position: [f32; 3],
    /// Axis of the cone (the profile's gamma = 0 axis): the direction light travels in.
    #[serde(deserialize_with = "exact")]
    pub direction: [f32; 3],
    /// Half-angle of the cone, degrees (not with a profile).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub angle: Option<f32>,
    /// Width of the soft edge inside the cone, degrees (0: a hard edge).
    #[serde(default)]
    pub soft_edge: f32,
    /// IES LM-63 file (type C) giving the distribution instead of a cone.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub profile: Option<String>,
    /// Towards which the profile's C = 0 half-plane lies.
    #[serde(
        default,
        deserialize_with = "exact_opt",
        skip_serializing_if = "Option::is_none"
    )]
    pub profile_c0: Option<[f32; 3]>,
}

impl SpotDesc {
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
        c.direction(&format!("{key}.direction"), self.direction);
        let orient = [("profile_c0", self.profile_c0)];
        amount::check_orientation(c, key, self.profile.as_deref(), &orient);
        match (&self.profile, self.angle) {
            (None, None) => c.fail(
                format!("{key}.angle"),
                "a spot needs its cone's half-angle `angle` (or a `profile`)",
            ),
            (None, Some(a)) => c.range(
                &format!("{key}.angle"),
                a as f64,
                1e-3,
                90.0,
                "in (0, 90] degrees",
            ),
            (Some(_), Some(_)) => c.fail(
                format!("{key}.angle"),
                "the profile gives the distribution: drop `angle` (or the profile)",
            ),
            (Some(_), None) => {}
        }
        if self.profile.is_some() && self.soft_edge != 0.0 {
            c.fail(
                format!("{key}.soft_edge"),
                "the profile gives the distribution: drop `soft_edge`",
            );
        }
        c.range(
            &format!("{key}.soft_edge"),
            self.soft_edge as f64,
            0.0,
            90.0,
            "in [0, 90] degrees",
        );
    }

    /// `unit`: the light's spectrum normalised to 1 W.
    pub(super) fn build(
        &self,
        b: &Builder,
        key: &str,
        unit: Spectrum,
    ) -> Result<Light, SceneError> {
        let position = Vec3::from(self.position);
        let direction = Vec3::from(self.direction).normalize();
        let amount = self.given().amount();
        if let Some(file) = &self.profile {
            let frame = amount::profile_frame(self.direction, self.profile_c0);
            return super::profiled(b, key, file, position, frame, amount, unit);
        }
        let (Some(angle), Some(amount)) = (self.angle, amount) else {
            return Err(b.source.invalid(
                key,
                "a spot needs `angle` and one of `power`, `luminous_flux`, `intensity`",
            ));
        };
        // The on-axis intensity per watt: the profile's fraction along its axis.
        let peak = SpotProfile::new(angle, self.soft_edge).fraction(Vec3::Z) as f64;
        let w = amount::radiant(b, key, amount, &unit, peak)?;
        Ok(Light::spot(
            position,
            direction,
            unit * w,
            angle,
            self.soft_edge,
        ))
    }
}
