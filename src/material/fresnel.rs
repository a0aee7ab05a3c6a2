//! Fresnel terms and the reflect / refract directions (vectors point away from the surface).

use glam::Vec3;
use num_complex::Complex;

/// Unpolarised Fresnel reflectance of a smooth dielectric interface. `cos_i` > 0 is measured on
/// the incident side; `eta` = n_transmitted / n_incident. Total internal reflection gives 1.
pub fn fresnel_dielectric(cos_i: f32, eta: f32) -> f32 {
    let sin2_t = (1.0 - cos_i * cos_i).max(0.0) / (eta * eta);
    if sin2_t >= 1.0 {
        return 1.0;
    }
    let cos_t = (1.0 - sin2_t).sqrt();
    let rs = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    let rp = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    0.5 * (rs * rs + rp * rp)
}

pub fn schlick(r0: f32, cos: f32) -> f32 {
    let m = (1.0 - cos).clamp(0.0, 1.0);
    let m2 = m * m;
    r0 + (1.0 - r0) * m2 * m2 * m
}

pub fn reflect(wo: Vec3, n: Vec3) -> Vec3 {
    2.0 * wo.dot(n) * n - wo
}

/// Refraction of `wo` (on the side of `n`) with relative index `eta` = n_t / n_i; None under
/// total internal reflection.
pub fn refract(wo: Vec3, n: Vec3, eta: f32) -> Option<Vec3> {
    let cos_i = wo.dot(n);
    let sin2_t = (1.0 - cos_i * cos_i).max(0.0) / (eta * eta);
    if sin2_t >= 1.0 {
        return None;
    }
    let cos_t = (1.0 - sin2_t).sqrt();
    Some((-wo / eta + (cos_i / eta - cos_t) * n).normalize())
}

/// Unpolarised Fresnel reflectance of a smooth conductor of complex index `eta + i k` (relative
/// to the incident side's index) at incidence cosine `cos_i`, from the complex form of the
/// s and p amplitudes with Snell's law continued to complex angles. Computed in f64: for
/// silver-like metals (eta ~ 0.05, k ~ 4) f32 loses digits near grazing incidence.
pub fn fresnel_conductor(cos_i: f32, eta: f32, k: f32) -> f32 {
    let c = f64::from(cos_i.clamp(0.0, 1.0));
    let eta = Complex::new(f64::from(eta), f64::from(k));
    let sin2 = 1.0 - c * c;
    let cos_t = (Complex::new(1.0, 0.0) - sin2 / (eta * eta)).sqrt();
    let rs = (c - eta * cos_t) / (c + eta * cos_t);
    let rp = (eta * c - cos_t) / (eta * c + cos_t);
    let r = 0.5 * (rs.norm_sqr() + rp.norm_sqr());
    if r.is_finite() { r as f32 } else { 1.0 }
}
