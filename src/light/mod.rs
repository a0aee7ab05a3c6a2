//! Light sources: total power, forward-ray sampling and (for area lights) emitted radiance.

mod beam;
mod direct;
pub mod goniometric;
pub mod ies;
mod light_set;
mod spot;

use std::f32::consts::PI;

use glam::{Vec2, Vec3};

use crate::geometry::sampling::{Frame, concentric_disc, cosine_hemisphere, uniform_sphere};
use crate::geometry::{Geometry, Hit, Ray};
use crate::spectrum::Spectrum;
use beam::Beam;

pub use direct::{Anchor, Arrival};
pub use goniometric::{Goniometric, ProfileError};
pub use ies::{IesData, IesError};
pub use light_set::{DirectChoice, LightSet};
pub use spot::{Cone, SpotProfile};

/// A forward ray leaving a light and the spectral flux it carries (W/nm per bin), already divided
/// by every sampling probability, so that E[flux] equals the light's power.
#[derive(Clone, Copy, Debug)]
pub struct EmissionSample {
    pub ray: Ray,
    pub flux: Spectrum,
}

#[derive(Clone, Debug)]
pub enum Light {
    /// Parallel light travelling along `direction`; the beam covers the scene's bounding box
    /// grown by `margin` on every side.
    Directional {
        direction: Vec3,
        irradiance: Spectrum,
        margin: f32,
    },
    /// Isotropic point light.
    Point { position: Vec3, power: Spectrum },
    /// Point light under a conical shade, or with a tabulated (IES) distribution.
    Spot {
        position: Vec3,
        frame: Frame,
        power: Spectrum,
        profile: SpotProfile,
    },
    /// Collimated beam of uniform cross-section (a disc of `radius`).
    Laser {
        position: Vec3,
        frame: Frame,
        radius: f32,
        power: Spectrum,
    },
    /// Lambertian emitter on a shape's surface (outward side unless two-sided).
    Area {
        shape: u32,
        radiance: Spectrum,
        two_sided: bool,
    },
}

impl Light {
    /// `direction` is where the light travels; `irradiance` is W/m^2/nm on a plane normal to it.
    pub fn directional(direction: Vec3, irradiance: Spectrum) -> Light {
        Light::Directional {
            direction: direction.normalize_or(Vec3::NEG_Z),
            irradiance,
            margin: 0.0,
        }
    }

    /// Grows a directional beam by `margin` (at most a tenth of the bounds' diagonal) beyond the
    /// scene's bounds: integration volumes reach up to their radius outside the geometry (open
    /// media, method note 8) and must see the light that passes there. Other lights are
    /// returned unchanged.
    pub fn with_beam_margin(mut self, m: f32) -> Light {
        if let Light::Directional { margin, .. } = &mut self {
            *margin = m.max(0.0);
        }
        self
    }

    /// `power`: total emitted W/nm per bin.
    pub fn point(position: Vec3, power: Spectrum) -> Light {
        Light::Point { position, power }
    }

    /// `power` is the total emitted. Full intensity within `half_angle_deg - soft_edge_deg` of the
    /// axis, fading (linearly in cos theta) to zero at `half_angle_deg`.
    pub fn spot(
        position: Vec3,
        direction: Vec3,
        power: Spectrum,
        half_angle_deg: f32,
        soft_edge_deg: f32,
    ) -> Light {
        Light::Spot {
            position,
            frame: Frame::new(direction.normalize_or(Vec3::NEG_Z)),
            power,
            profile: SpotProfile::new(half_angle_deg, soft_edge_deg),
        }
    }

    /// A point light whose power `power` is spread as the table `profile` says, its gamma = 0
    /// axis along `frame.n` and its C = 0 half-plane towards `frame.s` (C = 90 towards
    /// `frame.t`).
    pub fn profiled(
        position: Vec3,
        frame: Frame,
        power: Spectrum,
        profile: std::sync::Arc<Goniometric>,
    ) -> Light {
        Light::Spot {
            position,
            frame,
            power,
            profile: SpotProfile::Table(profile),
        }
    }

    pub fn laser(position: Vec3, direction: Vec3, radius: f32, power: Spectrum) -> Light {
        Light::Laser {
            position,
            frame: Frame::new(direction.normalize_or(Vec3::NEG_Z)),
            radius: radius.max(0.0),
            power,
        }
    }

    /// `radiance` in W/(m^2 sr nm).
    pub fn area(shape: u32, radiance: Spectrum, two_sided: bool) -> Light {
        Light::Area {
            shape,
            radiance,
            two_sided,
        }
    }

    /// The directional beam: the silhouette of the scene's bounding box seen along
    /// `direction`. Every beam ray meets the box, so no forward ray is spent on empty space
    /// (a bounding-sphere disc wastes about 30 % of them on a cube).
    fn beam(geometry: &Geometry, direction: Vec3, margin: f32) -> Beam {
        let b = geometry.bounds();
        if b.is_empty() {
            return Beam::empty();
        }
        // Radii beyond a tenth of the scene are blur, not gathering: growing the beam by them
        // would spread the forward rays over mostly empty space.
        let m = Vec3::splat(margin.min(0.1 * b.diagonal().length()));
        Beam::new(b.min - m, b.max + m, direction)
    }

    /// Total emitted spectral power (W/nm per bin).
    pub fn power(&self, geometry: &Geometry) -> Spectrum {
        match self {
            Light::Directional {
                irradiance,
                direction,
                margin,
            } => *irradiance * Self::beam(geometry, *direction, *margin).area,
            Light::Point { power, .. } | Light::Spot { power, .. } | Light::Laser { power, .. } => {
                *power
            }
            Light::Area {
                shape,
                radiance,
                two_sided,
            } => {
                let sides = if *two_sided { 2.0 } else { 1.0 };
                *radiance * (PI * geometry.area(*shape) * sides)
            }
        }
    }

    /// A forward ray; every sample carries `flux` = power because each light's positions and
    /// directions are drawn exactly from its emission distribution.
    pub fn sample_emission(&self, geometry: &Geometry, u: [f32; 4]) -> EmissionSample {
        let (u0, u1) = (Vec2::new(u[0], u[1]), Vec2::new(u[2], u[3]));
        let ray = match self {
            Light::Directional {
                direction,
                irradiance,
                margin,
            } => {
                // One beam per ray gives both the origin and the flux.
                let beam = Self::beam(geometry, *direction, *margin);
                return EmissionSample {
                    ray: Ray::new(beam.sample(u0, u[2]), *direction),
                    flux: *irradiance * beam.area,
                };
            }
            Light::Point { position, .. } => Ray::new(*position, uniform_sphere(u0)),
            Light::Spot {
                position,
                frame,
                profile,
                ..
            } => Ray::new(*position, frame.to_world(profile.sample(u0))),
            Light::Laser {
                position,
                frame,
                radius,
                ..
            } => {
                let d = concentric_disc(u0) * *radius;
                Ray::new(*position + frame.s * d.x + frame.t * d.y, frame.n)
            }
            Light::Area {
                shape, two_sided, ..
            } => {
                let (p, n) = geometry.sample_point(*shape, u0);
                let mut v = u1;
                let mut n = n;
                if *two_sided {
                    // Reuse one coordinate for the side choice, stretched back to [0,1).
                    if v.x < 0.5 {
                        v.x *= 2.0;
                    } else {
                        v.x = 2.0 * v.x - 1.0;
                        n = -n;
                    }
                }
                let dir = Frame::new(n).to_world(cosine_hemisphere(v));
                crate::geometry::spawn(p, n, dir)
            }
        };
        EmissionSample {
            ray,
            flux: self.power(geometry),
        }
    }

    /// Radiance leaving an area light towards `wo` at a hit on its shape (0 for delta lights).
    /// The caller matches the hit's shape to the light (`ShapeDesc::light`).
    pub fn radiance(&self, hit: &Hit, wo: Vec3) -> Spectrum {
        match self {
            Light::Area {
                radiance,
                two_sided,
                ..
            } => {
                if *two_sided || wo.dot(hit.ng) > 0.0 {
                    *radiance
                } else {
                    Spectrum::ZERO
                }
            }
            // Only area lights have a surface that can be hit.
            Light::Directional { .. }
            | Light::Point { .. }
            | Light::Spot { .. }
            | Light::Laser { .. } => Spectrum::ZERO,
        }
    }

    /// Radiant intensity (W/sr/nm) of point-like lights towards `dir`; zero for the others.
    pub fn intensity(&self, dir: Vec3) -> Spectrum {
        match self {
            Light::Point { power, .. } => *power / (4.0 * PI),
            Light::Spot {
                frame,
                power,
                profile,
                ..
            } => *power * profile.fraction(frame.to_local(dir.normalize())),
            // Not point-like: next-event estimation samples these by their own routines
            // (directional, area) or leaves them to photons (a laser's beam has no spread).
            Light::Directional { .. } | Light::Laser { .. } | Light::Area { .. } => Spectrum::ZERO,
        }
    }
}
