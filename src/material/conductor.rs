//! Rough conductor (a metal): a GGX microfacet reflection lobe (Walter et al. 2007) with the
//! Smith height-correlated masking-shadowing term (Heitz 2014), optionally anisotropic, whose
//! Fresnel factor is either exact for a complex index `n + ik` per spectral bin or Schlick's
//! from a normal-incidence reflectance `f0` (glTF's metallic workflow). Directions are sampled
//! from the distribution of visible normals (Heitz 2018), whose density cancels D and G1 so that
//! a sample's weight is `F G2 / G1`.
//!
//! The anisotropy axes are the x and y axes of [`Frame::new`] about the shading normal on
//! `wo`'s side, the frame every material of brume uses (a hit has no surface tangent).
//!
//! A lobe narrower than [`SMOOTH_ALPHA`] on both axes is a delta reflection about the shading
//! normal: f32 no longer resolves D's peak (1 / (pi alpha^2)) well below it, and the
//! microfacet lobe converges to that mirror with the same Fresnel factor as alpha -> 0.

use std::f32::consts::PI;

use glam::{Vec2, Vec3};

use super::fresnel::{fresnel_conductor, reflect};
use super::glossy::MIN_ROUGHNESS;
use super::{BsdfSample, LobeKind, reflects, side_frame};
use crate::geometry::Hit;
use crate::geometry::sampling::Frame;
use crate::spectrum::Spectrum;

/// Below this GGX alpha on both axes the conductor is a smooth (delta) mirror, as in pbrt-v4.
pub const SMOOTH_ALPHA: f32 = 1e-3;

/// Where the conductor's Fresnel factor comes from.
#[derive(Clone, Debug)]
#[allow(clippy::large_enum_variant)] // one per material; boxing a spectrum gains nothing
pub enum ConductorFresnel {
    /// The complex index `eta + i k` of the metal relative to the outside (index 1), per bin:
    /// the exact unpolarised Fresnel reflectance.
    Complex { eta: Spectrum, k: Spectrum },
    /// Schlick's approximation `f0 + (1 - f0)(1 - cos)^5` per bin.
    Schlick { f0: Spectrum },
}

#[derive(Clone, Debug)]
pub struct Conductor {
    /// GGX alpha along the frame's x and y axes (each at least [`MIN_ROUGHNESS`]).
    pub alpha: Vec2,
    pub fresnel: ConductorFresnel,
    pub n_bins: usize,
    /// Both alphas below [`SMOOTH_ALPHA`]: a delta reflection.
    pub smooth: bool,
}

impl Conductor {
    /// `alpha_u`, `alpha_v`: GGX alpha along the two tangent axes; `n_bins`: the scene's bins.
    pub fn new(alpha_u: f32, alpha_v: f32, fresnel: ConductorFresnel, n_bins: usize) -> Self {
        let smooth = alpha_u.max(alpha_v) < SMOOTH_ALPHA;
        Conductor {
            alpha: Vec2::new(alpha_u, alpha_v).max(Vec2::splat(MIN_ROUGHNESS)),
            fresnel,
            n_bins: n_bins.clamp(1, crate::spectrum::MAX_BINS),
            smooth,
        }
    }

    /// Fresnel reflectance per bin at the cosine between the incident direction and the
    /// (micro)normal.
    pub fn fresnel(&self, cos: f32) -> Spectrum {
        let mut out = Spectrum::ZERO;
        match &self.fresnel {
            ConductorFresnel::Complex { eta, k } => {
                for j in 0..self.n_bins {
                    out[j] = fresnel_conductor(cos, eta[j], k[j]);
                }
            }
            ConductorFresnel::Schlick { f0 } => {
                let m = (1.0 - cos).clamp(0.0, 1.0);
                let m5 = m * m * m * m * m;
                for j in 0..self.n_bins {
                    out[j] = f0[j] + (1.0 - f0[j]) * m5;
                }
            }
        }
        out
    }

    /// GGX normal distribution at the local microfacet normal `h` (h.z > 0).
    fn d(&self, h: Vec3) -> f32 {
        let (ax, ay) = (self.alpha.x, self.alpha.y);
        let e = (h.x / ax) * (h.x / ax) + (h.y / ay) * (h.y / ay) + h.z * h.z;
        1.0 / (PI * ax * ay * e * e)
    }

    /// Smith's Lambda for the GGX distribution in local direction `w` (w.z > 0).
    fn lambda(&self, w: Vec3) -> f32 {
        let (x, y) = (self.alpha.x * w.x, self.alpha.y * w.y);
        let tan2 = (x * x + y * y) / (w.z * w.z);
        0.5 * ((1.0 + tan2).sqrt() - 1.0)
    }

    /// f (no cosine) for local directions, both above the surface.
    fn f_local(&self, lo: Vec3, li: Vec3) -> Spectrum {
        let h = (lo + li).normalize_or_zero();
        if h.z <= 0.0 {
            return Spectrum::ZERO;
        }
        let g2 = 1.0 / (1.0 + self.lambda(lo) + self.lambda(li));
        let scale = self.d(h) * g2 / (4.0 * lo.z * li.z);
        self.fresnel(lo.dot(h)) * scale
    }

    /// Density of the visible normals seen from local `lo` (lo.z > 0) at the local normal
    /// `h`, over the hemisphere of normals: D_wo(h) = G1(wo) max(0, wo.h) D(h) / wo.z, which
    /// [`Self::sample`] draws from and which integrates to 1.
    pub fn visible_normal_pdf(&self, lo: Vec3, h: Vec3) -> f32 {
        if h.z <= 0.0 || lo.z <= 0.0 {
            return 0.0;
        }
        lo.dot(h).max(0.0) * self.d(h) / ((1.0 + self.lambda(lo)) * lo.z)
    }

    /// Density of the sampled direction: D_wo(h) / (4 wo.h) = G1(wo) D(h) / (4 wo.z).
    fn pdf_local(&self, lo: Vec3, li: Vec3) -> f32 {
        let h = (lo + li).normalize_or_zero();
        if h.z <= 0.0 || li.z <= 0.0 {
            return 0.0;
        }
        self.d(h) / ((1.0 + self.lambda(lo)) * 4.0 * lo.z)
    }

    /// A microfacet normal visible from `lo` (lo.z > 0), by Heitz (2018): the view direction in
    /// the configuration stretched to alpha = 1, where visible normals are uniform over the
    /// projected hemisphere, sampled there on a disc whose far half is squeezed by the
    /// hemisphere's projection, then unstretched.
    fn sample_normal(&self, lo: Vec3, u: Vec2) -> Vec3 {
        let v = Vec3::new(self.alpha.x * lo.x, self.alpha.y * lo.y, lo.z).normalize();
        let len2 = v.x * v.x + v.y * v.y;
        let t1 = if len2 > 0.0 {
            Vec3::new(-v.y, v.x, 0.0) / len2.sqrt()
        } else {
            Vec3::X
        };
        let t2 = v.cross(t1);
        let r = u.x.sqrt();
        let phi = 2.0 * PI * u.y;
        let p1 = r * phi.cos();
        let s = 0.5 * (1.0 + v.z);
        let p2 = (1.0 - s) * (1.0 - p1 * p1).max(0.0).sqrt() + s * r * phi.sin();
        let up = (1.0 - p1 * p1 - p2 * p2).max(0.0).sqrt();
        let n = p1 * t1 + p2 * t2 + up * v;
        Vec3::new(self.alpha.x * n.x, self.alpha.y * n.y, n.z.max(0.0)).normalize()
    }

    /// f (no cosine) at a hit; zero for the smooth conductor's delta lobe.
    pub fn eval(&self, wo: Vec3, wi: Vec3, hit: &Hit) -> Spectrum {
        if self.smooth {
            return Spectrum::ZERO;
        }
        match side_frame(wo, hit).and_then(|f| reflects(wo, wi, hit, &f)) {
            Some((lo, li)) => self.f_local(lo, li),
            None => Spectrum::ZERO,
        }
    }

    /// Density (solid angle) of [`Self::sample`] producing `wi`; zero for the delta lobe.
    pub fn pdf(&self, wo: Vec3, wi: Vec3, hit: &Hit) -> f32 {
        if self.smooth {
            return 0.0;
        }
        side_frame(wo, hit)
            .and_then(|f| reflects(wo, wi, hit, &f))
            .map_or(0.0, |(lo, li)| self.pdf_local(lo, li))
    }

    /// A reflected direction with weight f |cos| / pdf = F G2 / G1 (the delta lobe: F, about
    /// the shading normal). None when the sampled microfacet reflects below the surface, which
    /// the lobe's pdf counts as lost.
    pub fn sample(&self, wo: Vec3, hit: &Hit, u: Vec2) -> Option<BsdfSample> {
        let f = side_frame(wo, hit)?;
        let lo = f.to_local(wo);
        if lo.z <= 0.0 {
            return None;
        }
        if self.smooth {
            return self.sample_smooth(wo, lo, hit, &f);
        }
        let h = self.sample_normal(lo, u);
        let li = reflect(lo, h);
        let wi = f.to_world(li);
        if li.z <= 0.0 || wi.dot(hit.ng) * wo.dot(hit.ng) <= 0.0 {
            return None;
        }
        let pdf = self.pdf_local(lo, li);
        if !(pdf > 0.0 && pdf.is_finite()) {
            return None;
        }
        let (l_o, l_i) = (self.lambda(lo), self.lambda(li));
        let weight = self.fresnel(lo.dot(h)) * ((1.0 + l_o) / (1.0 + l_o + l_i));
        Some(BsdfSample {
            wi,
            weight,
            pdf,
            kind: LobeKind::Glossy,
        })
    }

    fn sample_smooth(&self, wo: Vec3, lo: Vec3, hit: &Hit, f: &Frame) -> Option<BsdfSample> {
        let wi = reflect(wo, f.n);
        if wi.dot(hit.ng) * wo.dot(hit.ng) <= 0.0 {
            return None;
        }
        Some(BsdfSample {
            wi,
            weight: self.fresnel(lo.z),
            pdf: 1.0,
            kind: LobeKind::Specular,
        })
    }
}
