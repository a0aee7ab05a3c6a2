//! Direct light reflected at a surface point (method note 9): where a camera path gathers, the
//! diffuse part's BSDF times the light arriving through a shadow ray; where it goes on through
//! the non-diffuse (glossy) part, that part's BSDF, its light samples weighted against the
//! BSDF's own samples by the power heuristic (Veach 1997), so that emitters the path then hits
//! count with the complementary weight ([`Direct::emission_weight`]).

use glam::{Vec2, Vec3};
use rand::Rng as _;

use super::shadow::visible;
use super::{Direct, Receiver};
use crate::geometry::{Hit, Ray, spawn};
use crate::integrator::by_light::ByLight;
use crate::integrator::rng::Rng;
use crate::light::{Anchor, Arrival, Light};
use crate::material::Material;
use crate::world::Scene;

/// Which part of a material a surface estimate reflects with.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Part {
    /// The diffuse part, where the camera path gathers.
    Diffuse,
    /// The non-diffuse part, which the camera path samples to go on.
    Glossy,
}

/// The power heuristic (exponent 2) for a sample of density `a` against another strategy's `b`.
pub(super) fn power(a: f32, b: f32) -> f32 {
    let (a2, b2) = (a * a, b * b);
    if a2 + b2 > 0.0 { a2 / (a2 + b2) } else { 0.0 }
}

/// The solid-angle density of a surface anchor's sample seen from a point, for MIS.
pub(super) fn solid_angle_pdf(anchor: &Anchor, arrival: &Arrival) -> Option<f32> {
    match anchor {
        Anchor::Surface {
            normal, pdf_area, ..
        } => {
            let cos = arrival.wi.dot(*normal).abs();
            (cos > 0.0).then(|| pdf_area * arrival.dist * arrival.dist / cos)
        }
        // A delta light: no BSDF sample can hit it.
        Anchor::Direction { .. } | Anchor::Point { .. } => None,
    }
}

impl Direct {
    /// Adds the direct light that `part` of `material` reflects at `hit` towards `wo` (per
    /// bin, without the camera throughput) to `acc`, each sample to the light it sampled.
    #[allow(clippy::too_many_arguments)]
    pub fn reflected(
        &self,
        scene: &Scene,
        hit: &Hit,
        wo: Vec3,
        material: &Material,
        part: Part,
        rng: &mut Rng,
        acc: &mut ByLight,
    ) {
        let medium = scene.geometry.medium_after(hit, wo);
        let inv_samples = 1.0 / self.samples as f32;
        let at = self.picking(scene, Receiver::Point(hit.p));
        for _ in 0..self.samples {
            let (j, prob) = at.pick(rng.random());
            let light = &scene.lights.lights()[j as usize];
            let uv = Vec2::new(rng.random(), rng.random());
            let Some(anchor) = light.nee_anchor(&scene.geometry, uv) else {
                continue;
            };
            let Some(arrival) = anchor.arrival(light, hit.p) else {
                continue;
            };
            let (f, mis) = match part {
                Part::Diffuse => (material.eval_diffuse(wo, arrival.wi, hit), 1.0),
                Part::Glossy => {
                    let f = material.eval_nondiffuse(wo, arrival.wi, hit);
                    let mis = solid_angle_pdf(&anchor, &arrival).map_or(1.0, |pl| {
                        power(prob * pl, material.pdf_nondiffuse(wo, arrival.wi, hit))
                    });
                    (f, mis)
                }
            };
            // The geometric cosine, as the flux density a surface sphere gathers has it.
            let cos = arrival.wi.dot(hit.ng).abs();
            if f.is_zero() || cos == 0.0 {
                continue;
            }
            let o = spawn(hit.p, hit.ng, arrival.wi).o;
            let dist = arrival.dist - (o - hit.p).length();
            let Some(tr) = visible(scene, medium, (o, arrival.wi), dist, rng) else {
                continue;
            };
            acc.add(j, f * arrival.li * tr * (cos * mis / prob * inv_samples));
        }
    }

    /// The weight of emission that a camera path finds at `hit` on light `light` along `ray`
    /// after leaving a glossy surface at `from` with a BSDF sample of density `pdf_bsdf`: the
    /// power heuristic against the light samples of `reflected(.., Part::Glossy, ..)`, which
    /// cover the same light paths. 1 for a light next-event estimation does not handle.
    pub fn emission_weight(
        &self,
        scene: &Scene,
        light: u32,
        ray: &Ray,
        hit: &Hit,
        from: Vec3,
        pdf_bsdf: f32,
    ) -> f32 {
        if !self.handles(light) {
            return 1.0;
        }
        let area = match &scene.lights.lights()[light as usize] {
            Light::Area { shape, .. } => scene.geometry.area(*shape),
            Light::Directional { .. }
            | Light::Point { .. }
            | Light::Spot { .. }
            | Light::Laser { .. } => return 1.0,
        };
        let cos = ray.d.dot(hit.ng).abs();
        if !(area > 0.0 && cos > 0.0) {
            return 1.0;
        }
        let dist2 = hit.p.distance_squared(from);
        let pick = self.probability_at(scene, &Receiver::Point(from), light);
        let pdf_light = pick * dist2 / (area * cos);
        power(pdf_bsdf, pdf_light)
    }
}
