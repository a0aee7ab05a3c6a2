//! What next-event estimation needs from a light: a sample of where its direct light comes
//! from (an anchor), and the light arriving from it at a point. The integrator chooses the
//! distance samples along camera segments from the anchor (equiangular about a point, product of
//! exponentials for a direction), then evaluates the arrival with a shadow ray.

use glam::{Vec2, Vec3};

use super::Light;
use crate::geometry::Geometry;
use crate::spectrum::Spectrum;

/// Where a light's direct light comes from, for one sample.
#[derive(Clone, Copy, Debug)]
pub enum Anchor {
    /// A parallel light travelling along `direction`.
    Direction { direction: Vec3 },
    /// A point (point and spot lights); `cone` = (axis, cos of the outer half-angle) for a spot,
    /// outside which it emits nothing.
    Point {
        position: Vec3,
        cone: Option<(Vec3, f32)>,
    },
    /// A point `position` sampled with density `pdf_area` (1/m²) on an emitting surface of
    /// outward normal `normal`.
    Surface {
        position: Vec3,
        normal: Vec3,
        pdf_area: f32,
    },
}

/// Light arriving at a point from an anchor.
#[derive(Clone, Copy, Debug)]
pub struct Arrival {
    /// Unit direction from the point towards the light.
    pub wi: Vec3,
    /// Distance to the light along `wi` (`+inf` for a direction).
    pub dist: f32,
    /// What a receiver multiplies by its BSDF or phase function (and cosine for a surface) and
    /// the transmittance: the irradiance normal to `wi` for a direction, the intensity over
    /// distance² for a point, radiance x cos_light / (distance² pdf_area) for a surface sample.
    pub li: Spectrum,
}

impl Anchor {
    /// The light from this anchor at point `x` (None when none arrives: outside a spot's cone,
    /// behind a one-sided emitter, or at the anchor itself).
    pub fn arrival(&self, light: &Light, x: Vec3) -> Option<Arrival> {
        match *self {
            Anchor::Direction { direction } => match light {
                Light::Directional { irradiance, .. } => Some(Arrival {
                    wi: -direction,
                    dist: f32::INFINITY,
                    li: *irradiance,
                }),
                Light::Point { .. }
                | Light::Spot { .. }
                | Light::Laser { .. }
                | Light::Area { .. } => None,
            },
            Anchor::Point { position, .. } => {
                let (wi, dist) = towards(x, position)?;
                let li = light.intensity(-wi) * (1.0 / (dist * dist));
                (!li.is_zero()).then_some(Arrival { wi, dist, li })
            }
            Anchor::Surface {
                position,
                normal,
                pdf_area,
            } => {
                let (wi, dist) = towards(x, position)?;
                let cos_light = -wi.dot(normal);
                let (radiance, two_sided) = match light {
                    Light::Area {
                        radiance,
                        two_sided,
                        ..
                    } => (*radiance, *two_sided),
                    Light::Directional { .. }
                    | Light::Point { .. }
                    | Light::Spot { .. }
                    | Light::Laser { .. } => return None,
                };
                if cos_light <= 0.0 && !two_sided {
                    return None;
                }
                let g = cos_light.abs() / (dist * dist * pdf_area);
                Some(Arrival {
                    wi,
                    dist,
                    li: radiance * g,
                })
            }
        }
    }
}

fn towards(x: Vec3, p: Vec3) -> Option<(Vec3, f32)> {
    let d = p - x;
    let dist = d.length();
    (dist > 0.0 && dist.is_finite()).then(|| (d / dist, dist))
}

impl Light {
    /// Can next-event estimation reach this light's direct light at all? A laser's collimated
    /// beam cannot be hit by a sampled direction: its light stays with forward rays.
    pub fn nee_capable(&self) -> bool {
        match self {
            Light::Directional { .. }
            | Light::Point { .. }
            | Light::Spot { .. }
            | Light::Area { .. } => true,
            Light::Laser { .. } => false,
        }
    }

    /// An anchor for next-event estimation from two uniforms (used by area lights only).
    pub fn nee_anchor(&self, geometry: &Geometry, u: Vec2) -> Option<Anchor> {
        match self {
            Light::Directional { direction, .. } => Some(Anchor::Direction {
                direction: *direction,
            }),
            Light::Point { position, .. } => Some(Anchor::Point {
                position: *position,
                cone: None,
            }),
            Light::Spot {
                position,
                frame,
                profile,
                ..
            } => Some(Anchor::Point {
                position: *position,
                cone: profile.cone_cos().map(|c| (frame.n, c)),
            }),
            Light::Area { shape, .. } => {
                let area = geometry.area(*shape);
                if !(area > 0.0 && area.is_finite()) {
                    return None;
                }
                let (position, normal) = geometry.sample_point(*shape, u);
                Some(Anchor::Surface {
                    position,
                    normal,
                    pdf_area: 1.0 / area,
                })
            }
            Light::Laser { .. } => None,
        }
    }
}
