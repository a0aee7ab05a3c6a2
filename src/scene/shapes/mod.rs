//! `[[shapes]]`: the keys every shape shares (what lies on either side of it, its emission and
//! placement) and the loops over kinds. Each kind's geometry keys, checks and runtime
//! [`ShapeKind`] are in its own file.

mod cuboid;
mod disc;
mod gltf;
mod mesh;
mod quad;
mod sphere;

use glam::Vec3;
use serde::{Deserialize, Serialize};

use crate::scene::array::exact;

pub use cuboid::BoxDesc;
pub use disc::DiscDesc;
pub use gltf::{GltfDesc, Part, SceneRef};
pub use mesh::MeshDesc;
pub use quad::QuadDesc;
pub use sphere::SphereDesc;

use super::builder::Builder;
use super::check::Checker;
use super::error::SceneError;
use super::spectrum_desc::SpectrumRef;
use super::tagged::{Tagged, kinds};
use crate::geometry::{self, ShapeKind, Transform};
use crate::light::DirectChoice;
use crate::spectrum::Spectrum;

/// Largest radiance an emitting shape may have in any bin, W/(m^2 sr nm): about 4000 times the
/// sun's. Brighter emitters overflow the film's fixed-point sums (see `lights::MAX_POWER`).
pub const MAX_RADIANCE: f32 = 1e8;

#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct TransformDesc {
    /// Applied last, in metres.
    #[serde(deserialize_with = "exact")]
    pub translate: [f32; 3],
    /// Euler angles in degrees about X, then Y, then Z.
    #[serde(deserialize_with = "exact")]
    pub rotate: [f32; 3],
    /// Applied first.
    #[serde(deserialize_with = "exact")]
    pub scale: [f32; 3],
}

impl Default for TransformDesc {
    fn default() -> Self {
        Self {
            translate: [0.0; 3],
            rotate: [0.0; 3],
            scale: [1.0; 3],
        }
    }
}

/// Keys every shape has.
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ShapeCommon {
    /// Material name; absent = index-matched (`null`) boundary that only changes the medium.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub material: Option<String>,
    /// Medium inside the (closed) shape.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub interior: Option<String>,
    /// Medium outside; defaults to the scene's `medium`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub exterior: Option<String>,
    /// Emitted radiance spectrum (W / (m^2 sr nm) before `emit_scale`): makes the shape an area light.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub emit: Option<SpectrumRef>,
    /// Multiplier of `emit` (default 1; not with `luminous_flux`).
    #[serde(default, skip_serializing_if = "none_or_one")]
    pub emit_scale: Option<f32>,
    /// Total luminous flux of the emitter, lm: `emit` then gives only the spectral shape.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub luminous_flux: Option<f32>,
    /// Luminance of the emitter, cd/m² (nits): `emit` then gives only the spectral shape.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub luminance: Option<f32>,
    /// Multiplier of the emitter's share of forward rays (see `[[lights]]`).
    #[serde(
        default = "crate::scene::lights::one",
        skip_serializing_if = "crate::scene::lights::is_one"
    )]
    pub importance: f32,
    /// How the emitted light reaches the image under `integrator.direct = "nee"` (with `emit`).
    #[serde(default, skip_serializing_if = "is_auto")]
    pub direct: DirectChoice,
    #[serde(default)]
    pub transform: TransformDesc,
}

fn none_or_one(v: &Option<f32>) -> bool {
    v.is_none_or(|v| v == 1.0)
}

fn is_auto(d: &DirectChoice) -> bool {
    *d == DirectChoice::Auto
}

kinds! {
    /// The kinds of shape, by their `type`.
    pub enum ShapeKindDesc: "shape" {
        "quad" => Quad(QuadDesc),
        "box" => Box(BoxDesc),
        "sphere" => Sphere(SphereDesc),
        "disc" => Disc(DiscDesc),
        "mesh" => Mesh(MeshDesc),
        "gltf" => Gltf(GltfDesc),
    }
}

/// A `[[shapes]]` table.
pub type ShapeDesc = Tagged<ShapeCommon, ShapeKindDesc>;

impl ShapeDesc {
    pub fn check(&self, c: &mut Checker, key: &str) {
        match &self.kind {
            ShapeKindDesc::Quad(s) => s.check(c, key),
            ShapeKindDesc::Box(s) => s.check(c, key),
            ShapeKindDesc::Sphere(s) => s.check(c, key),
            ShapeKindDesc::Disc(s) => s.check(c, key),
            ShapeKindDesc::Mesh(s) => s.check(c, key),
            ShapeKindDesc::Gltf(g) => {
                g.check(c, key);
                // A glTF's emission comes from its materials.
                if g.part.is_none() && self.common.emit.is_some() {
                    c.fail(
                        format!("{key}.emit"),
                        "a glTF shape emits through its materials' `emissive`: drop `emit`",
                    );
                }
            }
        }
        let s = &self.common;
        if let Some(m) = &s.material {
            c.material(&format!("{key}.material"), m);
        }
        for (k, v) in [("interior", &s.interior), ("exterior", &s.exterior)] {
            if let Some(m) = v {
                c.medium(&format!("{key}.{k}"), m);
            }
        }
        if let Some(e) = &s.emit {
            c.emission_ref(&format!("{key}.emit"), e);
        } else {
            let light_keys = [
                ("direct", s.direct != DirectChoice::Auto),
                ("luminous_flux", s.luminous_flux.is_some()),
                ("luminance", s.luminance.is_some()),
                ("importance", s.importance != 1.0),
            ];
            for (k, given) in light_keys {
                if given {
                    c.fail(
                        format!("{key}.{k}"),
                        format!("only an emitting shape (`emit`) has `{k}`"),
                    );
                }
            }
        }
        if let Some(v) = s.emit_scale {
            c.non_negative(&format!("{key}.emit_scale"), v as f64);
        }
        if let Some(v) = s.luminous_flux {
            c.positive(&format!("{key}.luminous_flux"), v as f64);
        }
        if let Some(v) = s.luminance {
            c.positive(&format!("{key}.luminance"), v as f64);
        }
        let amounts = [
            ("emit_scale", s.emit_scale.is_some()),
            ("luminous_flux", s.luminous_flux.is_some()),
            ("luminance", s.luminance.is_some()),
        ];
        let given: Vec<&str> = amounts.iter().filter(|a| a.1).map(|a| a.0).collect();
        if given.len() > 1 {
            c.fail(
                format!("{key}.{}", given[1]),
                format!(
                    "give one of `emit_scale`, `luminous_flux`, `luminance` (found {})",
                    given.join(" and ")
                ),
            );
        }
        crate::scene::lights::check_importance(c, key, s.importance);
        let t = &s.transform;
        c.point(&format!("{key}.transform.translate"), t.translate);
        c.vector(&format!("{key}.transform.rotate"), t.rotate);
        if t.scale.iter().any(|x| !(x.is_finite() && *x != 0.0)) {
            c.fail(
                format!("{key}.transform.scale"),
                "scale factors must be finite and non-zero",
            );
        }
    }

    /// The runtime shape (no light id yet) and, for an emitting shape, its radiance.
    pub fn build(
        &self,
        b: &Builder,
        key: &str,
    ) -> Result<(geometry::ShapeDesc, Option<Spectrum>), SceneError> {
        let kind: ShapeKind = match &self.kind {
            ShapeKindDesc::Quad(s) => s.build(),
            ShapeKindDesc::Box(s) => s.build(),
            ShapeKindDesc::Sphere(s) => s.build(),
            ShapeKindDesc::Disc(s) => s.build(),
            ShapeKindDesc::Mesh(s) => s.build(b, key)?,
            ShapeKindDesc::Gltf(g) => g.build(),
        };
        let s = &self.common;
        let radiance = match &s.emit {
            // A flux-given emitter is scaled (and bounded) once its area is known.
            Some(e) if s.luminous_flux.is_some() => {
                Some(b.spectra.emission(e, &format!("{key}.emit"))?)
            }
            Some(e) => match s.luminance {
                Some(nits) => Some(scale_to_luminance(b, key, e, nits)?),
                None => Some(emission(b, key, e, s.emit_scale.unwrap_or(1.0))?),
            },
            None => None,
        };
        let t = &s.transform;
        let v3 = Vec3::from_array;
        let shape = geometry::ShapeDesc {
            kind,
            transform: Transform::new(v3(t.translate), v3(t.rotate), v3(t.scale)),
            material: s.material.as_deref().and_then(|m| b.material_id(m)),
            interior: s.interior.as_deref().and_then(|m| b.medium_id(m)),
            exterior: match &s.exterior {
                Some(m) => b.medium_id(m),
                None => b.outside_medium(),
            },
            light: None,
        };
        Ok((shape, radiance))
    }
}

/// The radiance of an emitter given by its `luminous_flux`: `radiance` (the `emit` spectrum)
/// scaled so that a Lambertian emitter of `area` m² (one side) sends out `lm` lumens.
pub fn scale_to_flux(
    b: &Builder,
    key: &str,
    radiance: Spectrum,
    lm: f32,
    area: f32,
) -> Result<Spectrum, SceneError> {
    let at = format!("{key}.luminous_flux");
    let w = crate::colour::photometry::luminous_weights(&b.grid)
        .map_err(|e| b.source.invalid(&at, e.to_string()))?;
    let per_area = crate::colour::photometry::photometric(&w, radiance.as_slice(b.grid.n))
        * std::f64::consts::PI;
    let k = lm as f64 / (per_area * area as f64);
    let scaled = radiance * k as f32;
    let max = scaled.max_value();
    if !(k.is_finite() && k > 0.0 && max.is_finite() && max <= MAX_RADIANCE) {
        return Err(b.source.invalid(
            &at,
            format!(
                "{lm} lm from {area} m² with this `emit` spectrum needs a radiance of {max:e} \
                 W/(m^2 sr nm), outside the (0, {MAX_RADIANCE:e}] accepted (the spectrum must \
                 be visible and the film's sums must not overflow)"
            ),
        ));
    }
    Ok(scaled)
}

/// The radiance of an emitter given by its `luminance` (cd/m²): the `emit` spectrum scaled
/// so that its photometric value is `nits` (`film.units = "photometric"` reads it back).
fn scale_to_luminance(
    b: &Builder,
    key: &str,
    e: &SpectrumRef,
    nits: f32,
) -> Result<Spectrum, SceneError> {
    let at = format!("{key}.luminance");
    let radiance = b.spectra.emission(e, &format!("{key}.emit"))?;
    let w = crate::colour::photometry::luminous_weights(&b.grid)
        .map_err(|e| b.source.invalid(&at, e.to_string()))?;
    let per_unit = crate::colour::photometry::photometric(&w, radiance.as_slice(b.grid.n));
    let k = nits as f64 / per_unit;
    let scaled = radiance * k as f32;
    let max = scaled.max_value();
    if !(k.is_finite() && k > 0.0 && max.is_finite() && max <= MAX_RADIANCE) {
        return Err(b.source.invalid(
            &at,
            format!(
                "{nits} cd/m² with this `emit` spectrum needs a radiance of {max:e} \
                 W/(m^2 sr nm), outside the (0, {MAX_RADIANCE:e}] accepted (the spectrum must \
                 be visible and the film's sums must not overflow)"
            ),
        ));
    }
    Ok(scaled)
}

/// Emitted radiance `emit * scale`, refused above [`MAX_RADIANCE`].
fn emission(b: &Builder, key: &str, e: &SpectrumRef, scale: f32) -> Result<Spectrum, SceneError> {
    let radiance = b.spectra.emission(e, &format!("{key}.emit"))? * scale;
    let max = radiance.max_value();
    if !(max.is_finite() && max <= MAX_RADIANCE) {
        return Err(b.source.invalid(
            &format!("{key}.emit"),
            format!(
                "an emitted radiance of {max:e} W/(m^2 sr nm) (emit x emit_scale) is above the \
                 {MAX_RADIANCE:e} accepted (the film's sums would overflow)"
            ),
        ));
    }
    Ok(radiance)
}
