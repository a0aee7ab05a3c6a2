//! Diffuse base under a GGX reflection lobe (the "slightly specular" floor). The base is the
//! Ashikhmin-Shirley coupled diffuse term, which is reciprocal and leaves room for the energy the
//! specular lobe takes, so the sum stays below one.

use std::f32::consts::PI;

use glam::{Vec2, Vec3};

use super::Albedo;
use super::fresnel::{reflect, schlick};
use crate::spectrum::Spectrum;

/// Smallest GGX alpha: a near-mirror coat. f32 still resolves its lobe (D peaks at 1/(pi a^2),
/// about 3e7), and the scene format documents this bound.
pub const MIN_ROUGHNESS: f32 = 1e-4;

#[derive(Clone, Debug)]
pub struct Glossy {
    pub albedo: Albedo,
    /// Normal-incidence reflectance of the coating, from its index of refraction.
    pub r0: f32,
    /// GGX alpha.
    pub alpha: f32,
    pub n_bins: usize,
}

impl Glossy {
    pub fn new(albedo: Albedo, specular_ior: f32, roughness: f32, n_bins: usize) -> Glossy {
        let r = (specular_ior - 1.0) / (specular_ior + 1.0);
        Glossy {
            albedo,
            r0: (r * r).clamp(0.0, 1.0),
            alpha: roughness.clamp(MIN_ROUGHNESS, 1.0),
            n_bins: n_bins.clamp(1, crate::spectrum::MAX_BINS),
        }
    }

    /// Diffuse part of f; `wo`, `wi` in the local frame (z up), both above.
    pub fn f_diffuse(&self, wo: Vec3, wi: Vec3, uv: Vec2) -> Spectrum {
        let k = 28.0 / (23.0 * PI) * (1.0 - self.r0) * edge(wo.z) * edge(wi.z);
        self.albedo.at(uv) * k
    }

    fn d(&self, cos_h: f32) -> f32 {
        let a2 = self.alpha * self.alpha;
        let c2 = cos_h * cos_h;
        let den = c2 * (a2 - 1.0) + 1.0;
        a2 / (PI * den * den)
    }

    fn lambda(&self, cos: f32) -> f32 {
        let c2 = cos * cos;
        let tan2 = (1.0 - c2).max(0.0) / c2;
        0.5 * ((1.0 + self.alpha * self.alpha * tan2).sqrt() - 1.0)
    }

    /// Specular part of f (scalar: the coating is achromatic).
    pub fn f_specular(&self, wo: Vec3, wi: Vec3) -> f32 {
        let h = (wo + wi).normalize_or_zero();
        if h.z <= 0.0 {
            return 0.0;
        }
        let g = 1.0 / (1.0 + self.lambda(wo.z) + self.lambda(wi.z));
        self.d(h.z) * g * schlick(self.r0, wo.dot(h)) / (4.0 * wo.z * wi.z)
    }

    /// Density of `sample_specular` producing `wi`.
    pub fn pdf_specular(&self, wo: Vec3, wi: Vec3) -> f32 {
        let h = (wo + wi).normalize_or_zero();
        if h.z <= 0.0 || wi.z <= 0.0 {
            return 0.0;
        }
        self.d(h.z) * h.z / (4.0 * wo.dot(h).abs())
    }

    /// Samples the half vector from D(h) cos(theta_h).
    pub fn sample_specular(&self, wo: Vec3, u: Vec2) -> Option<Vec3> {
        let a2 = self.alpha * self.alpha;
        let tan2 = a2 * u.x / (1.0 - u.x).max(1e-7);
        let cos = 1.0 / (1.0 + tan2).sqrt();
        let sin = (1.0 - cos * cos).max(0.0).sqrt();
        let phi = 2.0 * PI * u.y;
        let h = Vec3::new(sin * phi.cos(), sin * phi.sin(), cos);
        let wi = reflect(wo, h);
        (wi.z > 0.0).then_some(wi)
    }

    /// Probability of choosing the diffuse lobe: its reflectance against the lobe's.
    pub fn diffuse_probability(&self, cos_o: f32, uv: Vec2) -> f32 {
        let a = self.albedo.at(uv).max_value() * (1.0 - self.r0);
        let s = schlick(self.r0, cos_o);
        if a + s > 0.0 { a / (a + s) } else { 0.0 }
    }
}

fn edge(c: f32) -> f32 {
    let m = 1.0 - 0.5 * c;
    let m2 = m * m;
    1.0 - m2 * m2 * m
}
