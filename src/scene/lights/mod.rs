//! `[[lights]]`: the keys every light shares (its spectrum) and the loops over kinds. Each
//! kind's keys, defaults, checks and runtime [`Light`] are in its own file.

mod amount;
mod directional;
mod laser;
mod point;
mod spot;

use std::sync::Arc;

use glam::Vec3;

use serde::{Deserialize, Serialize};

pub use directional::DirectionalDesc;
pub use laser::LaserDesc;
pub use point::PointDesc;
pub use spot::SpotDesc;

use super::builder::Builder;
use super::check::Checker;
use super::error::SceneError;
use super::spectrum_desc::SpectrumRef;
use super::tagged::{Tagged, kinds};
use crate::geometry::sampling::Frame;
use crate::light::{DirectChoice, Light};
use crate::spectrum::Spectrum;
use amount::Amount;

/// Largest total power of a light, W. The film sums pass estimates in fixed point and drops a
/// sample beyond `film::MAX_SAMPLE` (1e11 per pixel and bin): a 1e30 W lamp renders
/// black. 1e9 W (a million stadium floodlights) keeps a single forward ray's splat far inside
/// that range at any sensible radius; larger sources are scaled-down scenes or the sun, which
/// is a directional light.
pub const MAX_POWER: f32 = 1e9;
/// Largest irradiance of a directional light, W/m^2: about 700 suns.
pub const MAX_IRRADIANCE: f32 = 1e6;

/// Keys every light has.
#[derive(Clone, Debug, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LightCommon {
    /// Relative spectral shape, scaled so that its integral over the film's range is the
    /// light's power (or irradiance); spectral lines (`{ line = 532.0 }`) put it all at their
    /// wavelengths. Default: the D65 illuminant.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub spectrum: Option<SpectrumRef>,
    /// How its direct light reaches the image under `integrator.direct = "nee"`.
    #[serde(default, skip_serializing_if = "is_auto")]
    pub direct: DirectChoice,
    /// Multiplier of the light's share of forward rays (> 0; the image's expectation does not
    /// change, only where the noise goes).
    #[serde(default = "one", skip_serializing_if = "is_one")]
    pub importance: f32,
}

fn is_auto(d: &DirectChoice) -> bool {
    *d == DirectChoice::Auto
}

pub(crate) fn one() -> f32 {
    1.0
}

pub(crate) fn is_one(v: &f32) -> bool {
    *v == 1.0
}

kinds! {
    /// The kinds of light, by their `type`.
    pub enum LightKind: "light" {
        "directional" => Directional(DirectionalDesc),
        "point" => Point(PointDesc),
        "spot" => Spot(SpotDesc),
        "laser" => Laser(LaserDesc),
    }
}

/// A `[[lights]]` table.
pub type LightDesc = Tagged<LightCommon, LightKind>;

impl LightDesc {
    pub fn check(&self, c: &mut Checker, key: &str) {
        if let Some(s) = &self.common.spectrum {
            c.emission_ref(&format!("{key}.spectrum"), s);
        }
        check_importance(c, key, self.common.importance);
        match &self.kind {
            LightKind::Directional(l) => l.check(c, key),
            LightKind::Point(l) => l.check(c, key),
            LightKind::Spot(l) => l.check(c, key),
            LightKind::Laser(l) => {
                l.check(c, key);
                if self.common.direct == DirectChoice::Nee {
                    c.fail(
                        format!("{key}.direct"),
                        "a laser's direct light cannot be reached by next-event estimation \
                         (no sampled direction hits its beam): use \"auto\" or \"photons\"",
                    );
                }
            }
        }
    }

    pub fn build(&self, b: &Builder, key: &str) -> Result<Light, SceneError> {
        let spectrum_key = format!("{key}.spectrum");
        let shape = match &self.common.spectrum {
            Some(s) => b.spectra.emission(s, &spectrum_key)?,
            None => b.spectra.emission(&SpectrumRef::Named("D65".into()), key)?,
        };
        // Normalise the shape so that its integral over the spectral range is 1 (per nm).
        let integral = b.grid.integral(&shape);
        if integral <= 0.0 {
            let message = "the spectrum is zero over the film's range";
            return Err(b.source.invalid(&spectrum_key, message));
        }
        let unit = shape * (1.0 / integral as f32);
        match &self.kind {
            LightKind::Directional(l) => l.build(b, key, unit),
            LightKind::Point(l) => l.build(b, key, unit),
            LightKind::Spot(l) => l.build(b, key, unit),
            LightKind::Laser(l) => l.build(b, key, unit),
        }
    }

    /// The light's kind as its `type` spells it (names its light layer).
    pub fn kind_name(&self) -> &'static str {
        match &self.kind {
            LightKind::Directional(_) => "directional",
            LightKind::Point(_) => "point",
            LightKind::Spot(_) => "spot",
            LightKind::Laser(_) => "laser",
        }
    }
}

/// `importance`: a finite number > 0 (0 would leave the light's forward-ray light out of the
/// image).
pub(crate) fn check_importance(c: &mut Checker, key: &str, importance: f32) {
    c.range_f32(
        &format!("{key}.importance"),
        importance,
        f32::MIN_POSITIVE,
        1e6,
        "a number in (0, 1e6]",
    );
}

/// A point light with the IES profile `file`, oriented by `frame`, emitting `amount` (or, when
/// none is given, the flux of the file's own table).
fn profiled(
    b: &Builder,
    key: &str,
    file: &str,
    position: Vec3,
    frame: Frame,
    amount: Option<(&'static str, Amount)>,
    unit: Spectrum,
) -> Result<Light, SceneError> {
    let table = amount::load_profile(b, key, file)?;
    // Per watt, the brightest direction gets peak / total of it per steradian.
    let peak = table.peak() / table.total();
    let amount = amount.unwrap_or(("profile", Amount::LuminousFlux(table.total() as f32)));
    let w = amount::radiant(b, key, amount, &unit, peak)?;
    Ok(Light::profiled(
        position,
        frame,
        unit * w,
        Arc::clone(&table),
    ))
}

/// The power of a point-like light: positive and at most [`MAX_POWER`].
fn check_power(c: &mut Checker, key: &str, power: f32) {
    c.bounded(
        &format!("{key}.power"),
        power,
        MAX_POWER,
        "W",
        "accepted for a light (the film's sums would overflow)",
    );
}
