//! `[[shapes]]`: the keys every shape shares (what lies on either side of it, its emission and
//! placement) and the loops over kinds. Each kind's geometry keys, checks and runtime
//! [`ShapeKind`] are in its own file.

mod cuboid;
mod disc;
mod mesh;
mod quad;
mod sphere;

use glam::Vec3;
use serde::{Deserialize, Serialize};

use crate::scene::array::exact;

pub use cuboid::BoxDesc;
pub use disc::DiscDesc;
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
    #[serde(default = "one", skip_serializing_if = "is_one")]
    pub emit_scale: f32,
    /// How the emitted light reaches the image under `integrator.direct = "nee"` (with `emit`).
    #[serde(default, skip_serializing_if = "is_auto")]
    pub direct: DirectChoice,
    #[serde(default)]
    pub transform: TransformDesc,
}

fn one() -> f32 {
    1.0
}

fn is_one(v: &f32) -> bool {
    *v == 1.0
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
        } else if s.direct != DirectChoice::Auto {
            c.fail(
                format!("{key}.direct"),
                "only an emitting shape (`emit`) has direct light",
            );
        }
        c.non_negative(&format!("{key}.emit_scale"), s.emit_scale as f64);
        let t = &s.transform;
        c.vector(&format!("{key}.transform.translate"), t.translate);
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
        };
        let s = &self.common;
        let radiance = match &s.emit {
            Some(e) => Some(emission(b, key, e, s.emit_scale)?),
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
