//! Direct light reflected at a surface point where a camera path gathers (method note 9): the
//! diffuse part's BSDF times the light arriving through a shadow ray, one light sample per
//! `nee_samples`.

use glam::{Vec2, Vec3};
use rand::Rng as _;

use super::Direct;
use super::shadow::visible;
use crate::geometry::{Hit, spawn};
use crate::integrator::rng::Rng;
use crate::material::Material;
use crate::spectrum::Spectrum;
use crate::world::Scene;

impl Direct {
    /// The direct light the diffuse part of `material` reflects at `hit` towards `wo` (per bin,
    /// without the camera throughput).
    pub fn diffuse(
        &self,
        scene: &Scene,
        hit: &Hit,
        wo: Vec3,
        material: &Material,
        rng: &mut Rng,
    ) -> Spectrum {
        let mut acc = Spectrum::ZERO;
        let medium = scene.geometry.medium_after(hit, wo);
        let inv_samples = 1.0 / self.samples as f32;
        for _ in 0..self.samples {
            let (j, prob) = self.pick(rng.random());
            let light = &scene.lights.lights()[j as usize];
            let uv = Vec2::new(rng.random(), rng.random());
            let Some(arrival) = light
                .nee_anchor(&scene.geometry, uv)
                .and_then(|a| a.arrival(light, hit.p))
            else {
                continue;
            };
            let f = material.eval_diffuse(wo, arrival.wi, hit);
            // The geometric cosine, as the flux density a surface sphere gathers has it.
            let cos = arrival.wi.dot(hit.ng).abs();
            if f.is_zero() || cos == 0.0 {
                continue;
            }
            let o = spawn(hit.p, hit.ng, arrival.wi).o;
            let dist = arrival.dist - (o - hit.p).length();
            let Some(tr) = visible(scene, medium, o, arrival.wi, dist) else {
                continue;
            };
            acc += f * arrival.li * tr * (cos / prob * inv_samples);
        }
        acc
    }
}
