//! The path loop camera paths and forward rays share: find the next surface, step through the
//! medium segment before it, then handle the surface. Real events (medium scatterings,
//! reflections and refractions) count towards `max_depth` and are followed by Russian roulette;
//! index-matched (null) boundaries only change the medium and are bounded on their own.
//!
//! Each kind of path supplies what it does at each step through [`PathStep`]; the order of its
//! random numbers is its own, so this loop draws none.

use glam::Vec3;

use super::rng::Rng;
use crate::geometry::{Hit, Ray, spawn};
use crate::world::Scene;

/// Null-boundary crossings allowed per path (far more than any sane scene needs): degenerate
/// geometry (coincident boundaries) must not loop forever.
pub const MAX_CROSSINGS: u32 = 1024;

/// How a path left a medium segment.
pub enum MediumStep {
    /// It goes on to the surface (or world boundary) at the segment's end.
    Reached,
    /// It ended inside the medium.
    Ended,
    /// A real scattering at distance `t` along the segment.
    Scattered(f32),
}

/// What a path did at a surface hit.
pub enum SurfaceStep {
    /// The path ended (gathered, absorbed, or no continuation).
    Stop,
    /// An index-matched boundary: straight on, only the medium changes.
    Null,
    /// Reflected or refracted into direction `wi` (a real event).
    Scattered(Vec3),
}

/// What one kind of path does at each step.
pub trait PathStep {
    /// The segment along `ray` inside medium `m`: `seg` is its length and the surface it ends
    /// on (None: the world's edge).
    fn medium(&mut self, m: u32, ray: &Ray, seg: (f32, Option<&Hit>), rng: &mut Rng) -> MediumStep;
    /// A real scattering at `t` along `ray` in medium `m`, the path's `depth`-th real event:
    /// the ray that goes on, or None when the path ends there (Russian roulette).
    fn scatter(&mut self, m: u32, ray: &Ray, t: f32, depth: u32, rng: &mut Rng) -> Option<Ray>;
    /// The stretch along `ray` outside every medium up to `hit` (None: to the world's edge).
    fn vacuum(&mut self, ray: &Ray, hit: Option<&Hit>);
    /// A surface hit (all shapes, including null boundaries and emitters).
    fn surface(&mut self, hit: &Hit, ray: &Ray, rng: &mut Rng) -> SurfaceStep;
    /// Russian roulette after the `depth`-th real event at a surface: false ends the path.
    fn roulette(&mut self, depth: u32, rng: &mut Rng) -> bool;
}

/// Traces a path from `ray` in `medium` until it ends, `max_depth` real events happened, or it
/// crossed `MAX_CROSSINGS` null boundaries.
pub fn trace(
    scene: &Scene,
    max_depth: u32,
    mut ray: Ray,
    mut medium: Option<u32>,
    path: &mut impl PathStep,
    rng: &mut Rng,
) {
    let (mut depth, mut crossings) = (0, 0);
    while depth < max_depth && crossings < MAX_CROSSINGS {
        let hit = scene.geometry.intersect(&ray, f32::INFINITY);
        match medium {
            Some(m) => {
                let len = match &hit {
                    Some(h) => h.t,
                    None => scene.world_exit(&ray),
                };
                match path.medium(m, &ray, (len, hit.as_ref()), rng) {
                    MediumStep::Reached => {}
                    MediumStep::Ended => return,
                    MediumStep::Scattered(t) => {
                        depth += 1;
                        match path.scatter(m, &ray, t, depth, rng) {
                            Some(next) => {
                                ray = next;
                                continue;
                            }
                            None => return,
                        }
                    }
                }
            }
            None => path.vacuum(&ray, hit.as_ref()),
        }
        let Some(hit) = hit else { return };
        match path.surface(&hit, &ray, rng) {
            SurfaceStep::Stop => return,
            SurfaceStep::Null => {
                medium = scene.geometry.medium_after(&hit, ray.d);
                ray = spawn(hit.p, hit.ng, ray.d);
                crossings += 1;
            }
            SurfaceStep::Scattered(wi) => {
                // Refraction (`wi` on the other side) enters the medium behind the surface.
                if wi.dot(hit.ng).signum() != (-ray.d).dot(hit.ng).signum() {
                    medium = scene.geometry.medium_after(&hit, wi);
                }
                ray = spawn(hit.p, hit.ng, wi);
                depth += 1;
                if !path.roulette(depth, rng) {
                    return;
                }
            }
        }
    }
}
