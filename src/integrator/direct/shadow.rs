//! Shadow rays of next-event estimation: the per-bin transmittance between a point and a light
//! through index-matched (null) boundaries and the media between them (their density's optical
//! depth in closed form, `medium::density`). Any surface
//! with a material blocks: light that arrives through a reflection or refraction is not direct
//! (method note 9) and stays with the forward rays.

use glam::Vec3;

use super::super::path::MAX_CROSSINGS;
use crate::geometry::{Ray, spawn};
use crate::integrator::rng::Rng;
use crate::medium::Tracker;
use crate::spectrum::Spectrum;
use crate::world::Scene;

/// A shadow ray stops this far (relative, at least 1e-4 m) before a light at a finite distance,
/// so that the light's own surface does not block it.
const END_GAP: f32 = 1e-4;

/// Calls `each(medium, ray, len)` for every medium piece from `ray.o` (in `medium`) along
/// `ray.d` over `dist` (`+inf`: to the world's edge); None when a surface with a material is in
/// the way.
fn through_media(
    scene: &Scene,
    mut medium: Option<u32>,
    mut ray: Ray,
    dist: f32,
    mut each: impl FnMut(u32, &Ray, f32),
) -> Option<()> {
    let mut left = if dist.is_finite() {
        dist - END_GAP.max(dist * END_GAP)
    } else {
        f32::INFINITY
    };
    for _ in 0..MAX_CROSSINGS {
        if left <= 0.0 {
            return Some(());
        }
        let hit = scene.geometry.intersect(&ray, left);
        let len = match &hit {
            Some(h) => h.t,
            None if left.is_finite() => left,
            None => scene.world_exit(&ray),
        };
        if let Some(m) = medium {
            each(m, &ray, len);
        }
        let Some(h) = hit else { return Some(()) };
        if scene.geometry.shape(h.shape).material.is_some() {
            return None;
        }
        medium = scene.geometry.medium_after(&h, ray.d);
        ray = spawn(h.p, h.ng, ray.d);
        left -= h.t;
    }
    None
}

/// Optical depth per bin from `ray.o` (in `medium`) along `ray.d` over `dist` (`+inf`: to the
/// world's edge), exact in every medium (tracked ones included), or None when a surface with a
/// material is in the way.
pub fn optical_depth(scene: &Scene, medium: Option<u32>, ray: Ray, dist: f32) -> Option<Spectrum> {
    let mut tau = Spectrum::ZERO;
    through_media(scene, medium, ray, dist, |m, ray, len| {
        let med = &scene.media[m as usize];
        tau += med.sigma_t * med.density.depth_to(ray.o, ray.d, len);
    })?;
    Some(tau)
}

/// `e^{-tau_l}` per bin over the scene's bins.
pub fn transmittance(tau: &Spectrum, n: usize) -> Spectrum {
    tau.transmittance(1.0, n)
}

/// Transmittance from `x` in `medium` towards `wi` over `dist`, or None when blocked: exact
/// through media integrated exactly, ratio tracking's unbiased estimate through tracked ones
/// (`medium::tracking`).
pub fn visible(
    scene: &Scene,
    medium: Option<u32>,
    (x, wi): (Vec3, Vec3),
    dist: f32,
    rng: &mut Rng,
) -> Option<Spectrum> {
    let n = scene.grid.n;
    let mut tau = Spectrum::ZERO;
    let mut tracked: Option<Spectrum> = None;
    through_media(scene, medium, Ray { o: x, d: wi }, dist, |m, ray, len| {
        let med = &scene.media[m as usize];
        match med.tracking.as_deref() {
            None => tau += med.sigma_t * med.density.depth_to(ray.o, ray.d, len),
            Some(t) => {
                let tr =
                    Tracker::new(t, ray.o, ray.d).transmittance((0.0, len), &med.sigma_t, n, rng);
                tracked = Some(tracked.map_or(tr, |p| p * tr));
            }
        }
    })?;
    let exact = transmittance(&tau, n);
    Some(tracked.map_or(exact, |p| exact * p))
}
