//! Angular profile of a spot light (a cone with a soft edge, or a tabulated distribution from a
//! photometric file), sampled exactly so that every forward ray carries the same flux.

use std::f32::consts::TAU;
use std::sync::Arc;

use glam::{Vec2, Vec3};

use super::goniometric::Goniometric;

/// How a spot's power is spread over directions (local frame: axis +Z).
#[derive(Clone, Debug, PartialEq)]
pub enum SpotProfile {
    /// A conical shade with a soft edge.
    Cone(Cone),
    /// A tabulated intensity distribution (IES file), axis = its nadir (gamma = 0).
    Table(Arc<Goniometric>),
}

impl SpotProfile {
    /// A conical shade: full intensity within `half_angle_deg - soft_edge_deg` of the axis,
    /// fading linearly in cos theta to zero at `half_angle_deg`.
    pub fn new(half_angle_deg: f32, soft_edge_deg: f32) -> SpotProfile {
        SpotProfile::Cone(Cone::new(half_angle_deg, soft_edge_deg))
    }

    /// Cosine of the largest angle from the axis at which light leaves (-1 when it may leave
    /// in any direction).
    pub fn cos_edge(&self) -> f32 {
        self.cone_cos().unwrap_or(-1.0)
    }

    /// Cosine of the hard cut-off about the axis outside which nothing is emitted, if any.
    pub fn cone_cos(&self) -> Option<f32> {
        match self {
            SpotProfile::Cone(c) => Some(c.c_edge),
            SpotProfile::Table(t) => t.cone_cos(),
        }
    }

    /// Fraction of the power per steradian towards the local unit direction `d`.
    pub fn fraction(&self, d: Vec3) -> f32 {
        match self {
            SpotProfile::Cone(c) => c.intensity_fraction(d.z),
            SpotProfile::Table(t) => (t.eval(d) / t.total()) as f32,
        }
    }

    /// A local direction with density [`Self::fraction`] per steradian.
    pub fn sample(&self, u: Vec2) -> Vec3 {
        match self {
            SpotProfile::Cone(c) => c.sample(u),
            SpotProfile::Table(t) => t.sample(u),
        }
    }
}

/// Intensity over cos(theta) about the axis: 1 above `c_full`, falling linearly to 0 at `c_edge`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cone {
    c_full: f32,
    c_edge: f32,
    /// Solid-angle integral of the profile (sr).
    norm: f32,
}

impl Cone {
    pub fn new(half_angle_deg: f32, soft_edge_deg: f32) -> Cone {
        let edge = half_angle_deg.clamp(0.01, 180.0);
        let full = (edge - soft_edge_deg.max(0.0)).clamp(0.0, edge);
        let c_edge = edge.to_radians().cos();
        let c_full = full.to_radians().cos();
        let norm = TAU * ((1.0 - c_full) + 0.5 * (c_full - c_edge));
        Cone {
            c_full,
            c_edge,
            norm,
        }
    }

    /// Fraction of the power per steradian towards a direction with axis cosine `c`.
    pub fn intensity_fraction(&self, c: f32) -> f32 {
        let p = if c >= self.c_full {
            1.0
        } else if c > self.c_edge {
            (c - self.c_edge) / (self.c_full - self.c_edge)
        } else {
            0.0
        };
        p / self.norm
    }

    /// Local direction (axis +Z) with density proportional to the profile.
    pub fn sample(&self, u: Vec2) -> Vec3 {
        let core = 1.0 - self.c_full;
        let ramp = 0.5 * (self.c_full - self.c_edge);
        let pick = u.x * (core + ramp);
        let c = if pick < core || ramp <= 0.0 {
            1.0 - pick.min(core)
        } else {
            // Density in c proportional to (c - c_edge) on [c_edge, c_full]: invert its CDF.
            let v = ((pick - core) / ramp).clamp(0.0, 1.0);
            self.c_full - (self.c_full - self.c_edge) * (1.0 - (1.0 - v).sqrt())
        };
        let s = (1.0 - c * c).max(0.0).sqrt();
        let phi = TAU * u.y;
        Vec3::new(s * phi.cos(), s * phi.sin(), c)
    }
}
