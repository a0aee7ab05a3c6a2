//! Direct light at an illuminance sensor: the irradiance `E = sum over lights of Li Tr cos`
//! on the sensor's side, by light samples through shadow rays. The sensor's own paths leave
//! in cosine-distributed directions and may hit the same emitters: a sample on an area light is
//! weighted against that direction density by the power heuristic, and the emitter a sensor
//! path hits takes the complementary weight ([`Direct::emission_weight`] with the sensor as
//! the point the path left from).

use std::f32::consts::FRAC_1_PI;

use glam::{Vec2, Vec3};
use rand::Rng as _;

use super::shadow::visible;
use super::surface::{power, solid_angle_pdf};
use super::{Direct, Receiver};
use crate::geometry::spawn;
use crate::integrator::by_light::ByLight;
use crate::integrator::rng::Rng;
use crate::world::Scene;

impl Direct {
    /// Adds `nee_samples` light samples of the direct irradiance at `x` on the side of the unit
    /// `normal` (W/(m² nm) per bin; `medium` is the medium there) to `acc`, each to its light.
    pub fn irradiance(
        &self,
        scene: &Scene,
        x: Vec3,
        normal: Vec3,
        medium: Option<u32>,
        rng: &mut Rng,
        acc: &mut ByLight,
    ) {
        let inv_samples = 1.0 / self.samples as f32;
        let at = self.picking(scene, Receiver::Point(x));
        for _ in 0..self.samples {
            let (j, prob) = at.pick(rng.random());
            let light = &scene.lights.lights()[j as usize];
            let uv = Vec2::new(rng.random(), rng.random());
            let Some(anchor) = light.nee_anchor(&scene.geometry, uv) else {
                continue;
            };
            let Some(arrival) = anchor.arrival(light, x) else {
                continue;
            };
            let cos = arrival.wi.dot(normal);
            if cos <= 0.0 {
                continue;
            }
            // The sensor's paths sample directions with density cos / pi.
            let mis = solid_angle_pdf(&anchor, &arrival)
                .map_or(1.0, |pl| power(prob * pl, cos * FRAC_1_PI));
            let o = spawn(x, normal, arrival.wi).o;
            let dist = arrival.dist - (o - x).length();
            let Some(tr) = visible(scene, medium, (o, arrival.wi), dist, rng) else {
                continue;
            };
            acc.add(j, arrival.li * tr * (cos * mis / prob * inv_samples));
        }
    }
}
