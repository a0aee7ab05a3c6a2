//! Angular profile of a spot light, sampled exactly so that every forward ray carries the same flux.

use std::f32::consts::TAU;

use glam::{Vec2, Vec3};

/// Intensity over cos(theta) about the axis: 1 above `c_full`, falling linearly to 0 at `c_edge`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SpotProfile {
    c_full: f32,
    c_edge: f32,
    /// Solid-angle integral of the profile (sr).
    norm: f32,
}

impl SpotProfile {
    pub fn new(half_angle_deg: f32, soft_edge_deg: f32) -> SpotProfile {
        let edge = half_angle_deg.clamp(0.01, 180.0);
        let full = (edge - soft_edge_deg.max(0.0)).clamp(0.0, edge);
        let c_edge = edge.to_radians().cos();
        let c_full = full.to_radians().cos();
        let norm = TAU * ((1.0 - c_full) + 0.5 * (c_full - c_edge));
        SpotProfile {
            c_full,
            c_edge,
            norm,
        }
    }

    /// Cosine of the outer half-angle: no light leaves at larger angles from the axis.
    pub fn cos_edge(&self) -> f32 {
        self.c_edge
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
