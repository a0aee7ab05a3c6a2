//! Smooth dielectric interface with a spectral index of refraction. The shape's outside (the side
//! `ng` points to) has index 1 and its inside the material's index.

use glam::Vec3;

use super::fresnel::{fresnel_dielectric, reflect, refract};
use super::{BsdfSample, LobeKind};
use crate::geometry::Hit;
use crate::spectrum::Spectrum;

#[derive(Clone, Debug)]
pub struct Dielectric {
    pub ior: Spectrum,
    pub n_bins: usize,
    pub dispersive: bool,
}

impl Dielectric {
    pub fn new(ior: Spectrum, n_bins: usize) -> Dielectric {
        let n_bins = n_bins.clamp(1, crate::spectrum::MAX_BINS);
        let first = ior[0];
        let dispersive = ior.as_slice(n_bins).iter().any(|&x| x != first);
        Dielectric {
            ior,
            n_bins,
            dispersive,
        }
    }

    /// Samples reflection or refraction. `radiance`: scale transmission by (n_i/n_t)^2, as
    /// radiance carried by camera paths must be; forward (flux-carrying) rays pass `false`.
    ///
    /// Reflection is chosen with the bin-averaged Fresnel reflectance and keeps the whole
    /// spectrum (weight F_j / P_R). Transmission of a dispersive material picks one bin uniformly
    /// and returns a weight that is nonzero in that bin only (divided by the 1/n pick probability).
    pub fn sample(&self, wo: Vec3, hit: &Hit, u: Vec3, radiance: bool) -> Option<BsdfSample> {
        let outside = wo.dot(hit.ng) >= 0.0;
        // Normal on wo's side; use the shading normal unless it disagrees with the side.
        let mut n = if outside { hit.ns } else { -hit.ns };
        if wo.dot(n) <= 0.0 {
            n = if outside { hit.ng } else { -hit.ng };
        }
        let cos_o = wo.dot(n).clamp(0.0, 1.0);
        let eta_of = |ior: f32| if outside { ior } else { 1.0 / ior };
        let nb = self.n_bins;

        let mut fres = Spectrum::ZERO;
        for j in 0..nb {
            fres[j] = fresnel_dielectric(cos_o, eta_of(self.ior[j]));
        }
        let p_r = if self.dispersive {
            fres.sum() / nb as f32
        } else {
            fres[0]
        };

        if u.z < p_r {
            let weight = if self.dispersive {
                fres / p_r
            } else {
                Spectrum::splat(1.0, nb)
            };
            return Some(BsdfSample {
                wi: reflect(wo, n),
                weight,
                pdf: p_r,
                kind: LobeKind::Specular,
            });
        }

        let (bin, pick) = if self.dispersive {
            (((u.x * nb as f32) as usize).min(nb - 1), nb as f32)
        } else {
            (0, 1.0)
        };
        let eta = eta_of(self.ior[bin]);
        let wi = refract(wo, n, eta)?;
        let t = 1.0 - fres[bin];
        let scale = if radiance { 1.0 / (eta * eta) } else { 1.0 };
        let w = t / (1.0 - p_r) * pick * scale;
        let weight = if self.dispersive {
            Spectrum::single(bin, w)
        } else {
            Spectrum::splat(w, nb)
        };
        Some(BsdfSample {
            wi,
            weight,
            pdf: (1.0 - p_r) / pick,
            kind: LobeKind::Specular,
        })
    }
}
