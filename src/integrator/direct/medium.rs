//! Single scattering of direct light along one camera segment `[0, len]` (method note 9):
//!
//! `I_l = ∫_0^len e^{-st_l D(t)} rho(t) ss_l p(u, v) T_l(x(t) -> light) Li_l(x(t)) dt`,
//!
//! with the medium's density `rho` and its optical depth `D(t)` along the segment (`D(t) = t`,
//! `rho = 1` in a homogeneous medium; docs/media.md),
//! estimated with `nee_samples` stratified distances from one density `p(t)` shared by all bins,
//! so that `f_l(t) / p(t)` is unbiased in every bin without mixture weights. The density follows
//! the light: a truncated exponential in `D` whose rate is the camera's extinction plus the
//! growth of the light's optical depth per unit of `D` (exact for a parallel light in a convex
//! homogeneous medium, where that depth is linear), or equiangular about a point light or a
//! point sampled on an area light, clipped to a spot's cone.

use glam::{Vec2, Vec3};
use rand::Rng as _;

use super::sampling::{Equiangular, ExpMixture, cone_interval};
use super::shadow::{optical_depth, visible};
use super::{Direct, Receiver};
use crate::geometry::Ray;
use crate::integrator::by_light::ByLight;
use crate::integrator::rng::Rng;
use crate::light::Anchor;
use crate::medium::{Along, Medium, Mixture, Tracker};
use crate::spectrum::Spectrum;
use crate::world::Scene;

/// One camera segment, as next-event estimation sees it.
pub struct Segment<'a> {
    pub medium: u32,
    pub ray: &'a Ray,
    pub len: f32,
    /// The segment's channel mixture: its probabilities average the extinction the densities
    /// are built from.
    pub mix: &'a Mixture,
    /// The segment's change of variable to optical depth at density 1 (`medium::density`);
    /// the identity in a tracked medium, where `track` is Some.
    pub along: &'a Along,
    /// The null-collision tracker of a tracked (grey) medium (`medium::tracking`): distances
    /// towards a parallel light are then delta-tracking flights, and the camera's
    /// transmittance is ratio tracking's estimate.
    pub track: Option<&'a Tracker<'a>>,
}

impl Direct {
    /// Adds the single-scattering estimate of `seg` (per bin, without the camera throughput)
    /// to `acc`, each sample to the light it sampled.
    pub fn medium_segment(&self, scene: &Scene, seg: &Segment, rng: &mut Rng, acc: &mut ByLight) {
        // A segment the density leaves empty (above a fog bank) scatters nothing.
        if !(seg.len > 0.0 && seg.len.is_finite() && seg.along.depth(seg.len) > 0.0) {
            return;
        }
        let med = &scene.media[seg.medium as usize];
        let n = scene.grid.n;
        let inv_samples = 1.0 / self.samples as f32;
        // The parallel light's density is probed once per segment.
        let mut parallel: Option<(u32, ExpMixture)> = None;
        // Distances are stratified, and so are the bins a mixture picks; pairing stratum i with
        // bin stratum (i + shift) mod n for a random shift keeps each pair uniform on the
        // unit square (a Latin hypercube), so every sample stays unbiased.
        let shift = rng.random_range(0..self.samples);
        let at = self.picking(scene, Receiver::along(seg.ray, seg.len));
        for i in 0..self.samples {
            let (j, prob) = at.pick(rng.random());
            let light = &scene.lights.lights()[j as usize];
            let uv = Vec2::new(rng.random(), rng.random());
            let u = (i as f32 + rng.random::<f32>()) * inv_samples;
            let Some(anchor) = light.nee_anchor(&scene.geometry, uv) else {
                continue;
            };
            let (o, d) = (seg.ray.o, seg.ray.d);
            let (t, pdf) = match anchor {
                Anchor::Direction { .. } if seg.track.is_some() => match flight(seg, med, rng) {
                    Some(t) => (t, FLIGHT),
                    None => continue,
                },
                Anchor::Direction { direction, .. } => {
                    if parallel.as_ref().is_none_or(|(l, _)| *l != j) {
                        parallel = Some((j, parallel_density(scene, seg, direction)));
                    }
                    let e = &parallel.as_ref().expect("just set").1;
                    let stratum = (i + shift) % self.samples;
                    let u_bin = (stratum as f32 + rng.random::<f32>()) * inv_samples;
                    // Sampled in optical depth at density 1, placed at its distance: the
                    // density in t is the one in depth times rho(t).
                    let depth = e.sample(u_bin, u);
                    let t = seg.along.distance(depth).min(seg.len);
                    (t, e.pdf(depth) * seg.along.rho(t))
                }
                Anchor::Point { position, cone } => {
                    let (a, b) = match cone {
                        Some((axis, cos)) => {
                            match cone_interval(o, d, 0.0, seg.len, position, axis, cos) {
                                Some(ab) => ab,
                                None => continue,
                            }
                        }
                        None => (0.0, seg.len),
                    };
                    equiangular(o, d, position, a, b, u)
                }
                Anchor::Surface { position, .. } => equiangular(o, d, position, 0.0, seg.len, u),
            };
            if !(pdf > 0.0 && pdf.is_finite() || pdf == FLIGHT) {
                continue;
            }
            let x = o + d * t;
            let Some(arrival) = anchor.arrival(light, x) else {
                continue;
            };
            let Some(tr) = visible(scene, Some(seg.medium), (x, arrival.wi), arrival.dist, rng)
            else {
                continue;
            };
            // Light travelling along -wi turns towards the camera (-d): cos = wi . d.
            let cos = arrival.wi.dot(d);
            let (value, pdf) = integrand(seg, (t, pdf), (arrival.li, tr), (med, n), rng);
            let sample = if med.phase.varies_per_bin() {
                value * med.phase_bins(cos) * (inv_samples / (pdf * prob))
            } else {
                value * (med.phase.eval(cos) / (pdf * prob) * inv_samples)
            };
            acc.add(j, sample);
        }
    }
}

/// The integrand at `t` without the phase function, for light `li` arriving there through
/// transmittance `tr`, and the density to divide it by: the camera's transmittance, the
/// scattering coefficient and the density at `t`. A delta-tracking flight's sample (`FLIGHT`)
/// has these cancelled by its density but for `1 / sigma_t`.
fn integrand(
    seg: &Segment,
    (t, pdf): (f32, f32),
    (li, tr): (Spectrum, Spectrum),
    (med, n): (&Medium, usize),
    rng: &mut Rng,
) -> (Spectrum, f32) {
    match seg.track {
        None => {
            let camera = med.sigma_t.transmittance(seg.along.depth(t), n);
            // The exact transport's order of products (its images are the golden ones).
            let value = camera * med.sigma_s * li * tr * seg.along.rho(t);
            (value, pdf)
        }
        Some(_) if pdf == FLIGHT => (med.sigma_s * li * tr, med.sigma_t.0[0]),
        Some(track) => {
            let camera = track.transmittance((0.0, t), &med.sigma_t, n, rng);
            (camera * med.sigma_s * li * tr * track.rho(t), pdf)
        }
    }
}

/// In a tracked medium, the distance towards a parallel light is a delta-tracking flight: its
/// density `rho st e^{-st D(t)}` cancels the camera's transmittance and the density in the
/// integrand (`FLIGHT`).
fn flight(seg: &Segment, med: &Medium, rng: &mut Rng) -> Option<f32> {
    let track = seg.track?;
    track.free_flight(0.0, seg.len, med.sigma_t.0[0], rng)
}

/// The "density" of a sample drawn by a delta-tracking flight: a marker (no density has it)
/// for a weight that is `1 / sigma_t` instead (see `medium_segment`).
const FLIGHT: f32 = -1.0;

fn equiangular(o: Vec3, d: Vec3, c: Vec3, a: f32, b: f32, u: f32) -> (f32, f32) {
    let e = Equiangular::new(o, d, c, a, b);
    if e.is_empty() {
        return (0.0, 0.0);
    }
    let t = e.sample(u).clamp(a, b);
    (t, e.pdf(t))
}

/// The density, over the segment's optical depth at density 1 `u in [0, D(len)]` (the
/// distance itself in a uniform medium), that follows `e^{-st_l u} e^{-tau_l(u)}` for a parallel
/// light along `direction`, per bin mixed by the segment's channel probabilities: rate `st_l`
/// plus the slope of the light's optical depth `tau_l` between two probes near the segment's
/// ends. Falls back to the camera's rates alone where a probe is blocked (the segment is then
/// partly shadowed; any density stays unbiased).
fn parallel_density(scene: &Scene, seg: &Segment, direction: Vec3) -> ExpMixture {
    let med = &scene.media[seg.medium as usize];
    let n = scene.grid.n;
    let end = seg.along.depth(seg.len);
    let (u0, u1) = (0.001 * end, 0.999 * end);
    let depth = |u: f32| {
        let t = seg.along.distance(u).min(seg.len);
        let ray = Ray {
            o: seg.ray.o + seg.ray.d * t,
            d: -direction,
        };
        optical_depth(scene, Some(seg.medium), ray, f32::INFINITY)
    };
    let mut rates = med.sigma_t;
    if let (Some(a), Some(b)) = (depth(u0), depth(u1)) {
        rates += (b - a) * (1.0 / (u1 - u0));
    }
    ExpMixture::new(&rates, seg.mix.probabilities(), n, end)
}
