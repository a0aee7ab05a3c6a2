//! A linear blend of two materials, f = (1 - w) f_first + w f_second (as Mitsuba's `blendbsdf`):
//! a glossy coat over part of a diffuse floor, worn paint, a mask. With w in [0, 1] and each
//! part energy-conserving, so is the blend.
//!
//! Every method the integrator calls is the same mixture of the parts' methods, so the camera
//! side (diffuse probability, diffuse f, non-diffuse sampling) and the light side (sampling, f,
//! pdf) see one BSDF. Sampling picks part c with probability equal to its weight w_c, so the
//! blend's sample weight w_c f_c |cos| / (w_c pdf_c) is the part's own.

use std::sync::Arc;

use glam::{Vec2, Vec3};

use super::{BsdfSample, LobeKind, Material, Texture};
use crate::geometry::Hit;
use crate::spectrum::Spectrum;

/// Weight of the second material: a constant or the first bin of a one-bin texture.
#[derive(Clone, Debug)]
pub enum BlendWeight {
    Constant(f32),
    Texture(Arc<Texture>),
}

impl BlendWeight {
    #[inline]
    fn at(&self, uv: Vec2) -> f32 {
        match self {
            BlendWeight::Constant(w) => *w,
            BlendWeight::Texture(t) => t.lookup(uv)[0],
        }
        .clamp(0.0, 1.0)
    }
}

#[derive(Clone, Debug)]
pub struct Blend {
    pub first: Material,
    pub second: Material,
    pub weight: BlendWeight,
}

impl Blend {
    /// (1 - w, w) at the hit.
    #[inline]
    fn weights(&self, hit: &Hit) -> (f32, f32) {
        let w = self.weight.at(hit.uv);
        (1.0 - w, w)
    }

    /// The part picked by `u` in [0, 1) with probability equal to its weight, the other part
    /// and their weights, and `u` stretched back to [0, 1) for the part's own use.
    fn pick(&self, hit: &Hit, u: f32) -> (&Material, f32, &Material, f32, f32) {
        let (wa, wb) = self.weights(hit);
        if u < wa {
            (&self.first, wa, &self.second, wb, stretch(u / wa))
        } else {
            (&self.second, wb, &self.first, wa, stretch((u - wa) / wb))
        }
    }

    pub fn eval(&self, wo: Vec3, wi: Vec3, hit: &Hit) -> Spectrum {
        let (wa, wb) = self.weights(hit);
        self.first.eval(wo, wi, hit) * wa + self.second.eval(wo, wi, hit) * wb
    }

    pub fn pdf(&self, wo: Vec3, wi: Vec3, hit: &Hit) -> f32 {
        let (wa, wb) = self.weights(hit);
        wa * self.first.pdf(wo, wi, hit) + wb * self.second.pdf(wo, wi, hit)
    }

    /// A part chosen with probability w_c, then sampled: its weight f_c |cos| / (P pdf) times
    /// w_c / w_c is the blend's. The pdf of a non-delta sample is the mixture's, as [`Self::pdf`].
    pub fn sample(&self, wo: Vec3, hit: &Hit, u: Vec3) -> Option<BsdfSample> {
        let (part, p, other, q, uz) = self.pick(hit, u.z);
        let mut s = part.sample(wo, hit, Vec3::new(u.x, u.y, uz))?;
        s.pdf = match s.kind {
            // A delta direction has no density under the other part.
            LobeKind::Specular => p * s.pdf,
            LobeKind::Diffuse | LobeKind::Glossy => p * s.pdf + q * other.pdf(wo, s.wi, hit),
        };
        Some(s)
    }

    pub fn diffuse_probability(&self, wo: Vec3, hit: &Hit) -> f32 {
        let (wa, wb) = self.weights(hit);
        wa * self.first.diffuse_probability(wo, hit) + wb * self.second.diffuse_probability(wo, hit)
    }

    pub fn eval_diffuse(&self, wo: Vec3, wi: Vec3, hit: &Hit) -> Spectrum {
        let (wa, wb) = self.weights(hit);
        self.first.eval_diffuse(wo, wi, hit) * wa + self.second.eval_diffuse(wo, wi, hit) * wb
    }

    pub fn eval_nondiffuse(&self, wo: Vec3, wi: Vec3, hit: &Hit) -> Spectrum {
        let (wa, wb) = self.weights(hit);
        self.first.eval_nondiffuse(wo, wi, hit) * wa + self.second.eval_nondiffuse(wo, wi, hit) * wb
    }

    /// The density of [`Self::sample_nondiffuse`]: its parts' densities mixed by the
    /// probabilities with which it picks them.
    pub fn pdf_nondiffuse(&self, wo: Vec3, wi: Vec3, hit: &Hit) -> f32 {
        let (ra, rb) = self.nondiffuse_picks(hit);
        let total = ra + rb;
        if total <= 0.0 {
            return 0.0;
        }
        (ra * self.first.pdf_nondiffuse(wo, wi, hit) + rb * self.second.pdf_nondiffuse(wo, wi, hit))
            / total
    }

    /// Unnormalised probabilities of picking each part for a non-diffuse sample: its weight
    /// if it has a non-diffuse lobe, else 0.
    fn nondiffuse_picks(&self, hit: &Hit) -> (f32, f32) {
        let (wa, wb) = self.weights(hit);
        let ra = if self.first.has_nondiffuse() { wa } else { 0.0 };
        let rb = if self.second.has_nondiffuse() {
            wb
        } else {
            0.0
        };
        (ra, rb)
    }

    /// The non-diffuse parts only: a part that has one is picked in proportion to its weight
    /// (probability r_c), and its non-diffuse sample weighted by w_c / r_c. `pdf` is the picked
    /// part's density times r_c.
    pub fn sample_nondiffuse(&self, wo: Vec3, hit: &Hit, u: Vec3) -> Option<BsdfSample> {
        let (wa, wb) = self.weights(hit);
        let (ra, rb) = self.nondiffuse_picks(hit);
        let total = ra + rb;
        if total <= 0.0 {
            return None;
        }
        // A part without a non-diffuse lobe is never picked, whatever the rounding of u.z.
        let first = rb <= 0.0 || (ra > 0.0 && u.z * total < ra);
        let (part, w, r, uz) = if first {
            (&self.first, wa, ra / total, stretch(u.z * total / ra))
        } else {
            (
                &self.second,
                wb,
                rb / total,
                stretch((u.z * total - ra) / rb),
            )
        };
        let mut s = part.sample_nondiffuse(wo, hit, Vec3::new(u.x, u.y, uz))?;
        s.weight *= w / r;
        s.pdf *= r;
        Some(s)
    }
}

/// A uniform rescaled from a sub-interval, kept below 1 against rounding.
#[inline]
fn stretch(u: f32) -> f32 {
    u.clamp(0.0, 1.0 - f32::EPSILON / 2.0)
}
