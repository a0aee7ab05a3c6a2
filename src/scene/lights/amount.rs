//! How much a light emits: one radiometric quantity (W, or W/m² for a directional light) or one
//! photometric quantity (lm, cd, lx), converted to watts with the light's own spectrum; and the
//! tabulated profile (IES file) of point and spot lights.

use std::sync::Arc;

use glam::Vec3;

use super::MAX_POWER;
use crate::colour::photometry;
use crate::geometry::sampling::Frame;
use crate::light::{Goniometric, IesError};
use crate::scene::builder::Builder;
use crate::scene::check::Checker;
use crate::scene::error::{KeyText, Origin, SceneError};
use crate::spectrum::Spectrum;

/// The quantity a light is given by.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Amount {
    /// W (W/m² for a directional light): key `power` (`irradiance`).
    Radiant(f32),
    /// Luminous flux, lm: key `luminous_flux`.
    LuminousFlux(f32),
    /// Peak luminous intensity, cd: key `intensity`.
    Intensity(f32),
    /// Illuminance on a plane normal to a directional light, lx: key `illuminance`.
    Illuminance(f32),
}

/// One key a light may give its amount by: its name, its value (None: absent), and the amount
/// a value means.
pub type AmountKey = (&'static str, Option<f32>, fn(f32) -> Amount);

/// The keys a light may give its amount by, with their values.
pub struct Given(pub Vec<AmountKey>);

impl Given {
    /// Checks that exactly one key is given (at most one when `optional`, as with a profile
    /// that brings its own flux), and that it is a finite number > 0.
    pub fn check(&self, c: &mut Checker, key: &str, optional: bool) {
        let present: Vec<&str> = self
            .0
            .iter()
            .filter(|(_, v, _)| v.is_some())
            .map(|(k, _, _)| *k)
            .collect();
        let names: Vec<String> = self.0.iter().map(|(k, _, _)| format!("`{k}`")).collect();
        if present.len() > 1 {
            c.fail(
                format!("{key}.{}", present[1]),
                format!(
                    "give one of {} (found {})",
                    names.join(", "),
                    present.join(" and ")
                ),
            );
        } else if present.is_empty() && !optional {
            c.fail(key, format!("give one of {}", names.join(", ")));
        }
        for (k, v, _) in &self.0 {
            if let Some(v) = v {
                c.positive(&format!("{key}.{k}"), *v as f64);
            }
        }
    }

    /// The amount given and its key (the first present: checks refused several).
    pub fn amount(&self) -> Option<(&'static str, Amount)> {
        self.0.iter().find_map(|(k, v, f)| v.map(|v| (*k, f(v))))
    }
}

/// Luminous efficacy (lm/W) of `unit` (a spectrum of 1 W over the film's range), refused when
/// the spectrum has no light V(λ) sees.
fn efficacy(b: &Builder, key: &str, unit: &Spectrum) -> Result<f64, SceneError> {
    let w =
        photometry::luminous_weights(&b.grid).map_err(|e| b.source.invalid(key, e.to_string()))?;
    let e = photometry::luminous_efficacy(&w, unit.as_slice(b.grid.n), &b.grid).unwrap_or(0.0);
    if e > 0.0 && e.is_finite() {
        Ok(e)
    } else {
        Err(b.source.invalid(
            key,
            "the light's spectrum is invisible (zero luminous efficacy over the film's range): \
             give it in radiometric units",
        ))
    }
}

/// Radiant power (W, or W/m²) of a light given by `amount` at `key`, whose spectrum normalised
/// to 1 W is `unit` and which sends `peak` of each watt per steradian in its brightest
/// direction (1/(4 pi) for an isotropic light; unused for other amounts).
pub fn radiant(
    b: &Builder,
    key: &str,
    (name, amount): (&str, Amount),
    unit: &Spectrum,
    peak: f64,
) -> Result<f32, SceneError> {
    let at = format!("{key}.{name}");
    let (watts, unit_name) = match amount {
        Amount::Radiant(p) => return Ok(p),
        Amount::LuminousFlux(lm) => (lm as f64 / efficacy(b, &at, unit)?, "lm"),
        Amount::Illuminance(lx) => (lx as f64 / efficacy(b, &at, unit)?, "lx"),
        Amount::Intensity(cd) => (cd as f64 / (peak * efficacy(b, &at, unit)?), "cd"),
    };
    let max = MAX_POWER as f64;
    if !(watts.is_finite() && watts > 0.0 && watts <= max) {
        return Err(b.source.invalid(
            &at,
            format!(
                "{} {unit_name} is {watts:e} W with this spectrum, outside the (0, {max:e}] W \
                 accepted (the film's sums would overflow)",
                value_of(amount)
            ),
        ));
    }
    Ok(watts as f32)
}

fn value_of(a: Amount) -> f32 {
    match a {
        Amount::Radiant(v)
        | Amount::LuminousFlux(v)
        | Amount::Intensity(v)
        | Amount::Illuminance(v) => v,
    }
}

/// The profile's orientation keys: given only with a profile, and not zero vectors.
pub fn check_orientation(
    c: &mut Checker,
    key: &str,
    profile: Option<&str>,
    keys: &[(&str, Option<[f32; 3]>)],
) {
    if let Some(p) = profile {
        c.file(&format!("{key}.profile"), p);
    }
    for (k, v) in keys {
        if let Some(v) = v {
            c.direction(&format!("{key}.{k}"), *v);
            if profile.is_none() {
                c.fail(
                    format!("{key}.{k}"),
                    "orients a photometric profile: give `profile` too (or drop it)",
                );
            }
        }
    }
}

/// Reads the IES file `rel` of the light at `key` (errors at the file's own line).
pub fn load_profile(b: &Builder, key: &str, rel: &str) -> Result<Arc<Goniometric>, SceneError> {
    let path = b.source.resolve(rel);
    let at = format!("{key}.profile");
    let data = crate::light::ies::load(&path).map_err(|e: IesError| SceneError::Invalid {
        origin: Origin::File {
            file: e.file.clone(),
            line: (e.line > 0).then_some((e.line, 1)),
        },
        key: KeyText(at.clone()),
        message: e.message,
    })?;
    let g = Goniometric::from_ies(&data)
        .map_err(|e| b.source.invalid(&at, format!("{}: {e}", path.display())))?;
    Ok(Arc::new(g))
}

/// The frame of a profile aimed along `axis` (its gamma = 0 direction) with its C = 0
/// half-plane towards `c0` (default: world +X, or +Z when the axis is along X), C = 90
/// counter-clockwise from C = 0 seen from behind the light (from above for a lamp aimed down).
pub fn profile_frame(axis: [f32; 3], c0: Option<[f32; 3]>) -> Frame {
    let n = Vec3::from(axis).normalize_or(Vec3::NEG_Y);
    let project = |v: Vec3| {
        let p = v - n * v.dot(n);
        (p.length() > 1e-4).then(|| p.normalize())
    };
    let s = c0
        .and_then(|v| project(Vec3::from(v)))
        .or_else(|| project(Vec3::X))
        .or_else(|| project(Vec3::Z))
        .unwrap_or(Vec3::X);
    Frame {
        s,
        t: s.cross(n),
        n,
    }
}
