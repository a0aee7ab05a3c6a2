//! The bidirectional engine: camera pass -> gather structure -> light pass -> film.
//!
//! An [`Integrator`] is built once from the `[integrator]` settings and owned by the
//! [`Renderer`]: the settings, the integration-volume [`Estimator`], next-event estimation of
//! direct light ([`Direct`]) and the radius schedule.
//! The runtime scene (`world::Scene`) holds the content it renders.

pub mod auto;
pub mod boundary;
mod by_light;
mod camera_pass;
mod camera_path;
mod camera_splat;
mod chunk_order;
pub mod direct;
pub mod estimator;
mod exp;
pub mod gather;
mod light_pass;
mod memory;
pub mod nest;
mod oct;
mod pass;
mod path;
pub mod radius;
pub mod record;
mod rng;
mod sensors;
pub mod setting;
pub mod settings;
mod target;
mod throughput;

pub use camera_pass::OverBudget;
pub use direct::Direct;
pub use estimator::Estimator;
pub use memory::{MemoryEstimate, format_bytes};
pub use pass::{Budget, MAX_PASS_END, Renderer, Stats};
pub use radius::{Radii, RadiusSchedule, Shrink};
pub use settings::{
    DEFAULT_GATHER_BYTES, DirectMode, GatherMode, IntegratorDesc, Placement, VolumeKind,
};

use crate::medium::MediumError;
use crate::world::Scene;

/// The values `"auto"` settings take before anything is measured (and while they are).
pub mod defaults {
    /// Forward rays per pass.
    pub const FORWARD_RAYS: u64 = 50_000;
    /// Camera samples per pixel per pass.
    pub const CAMERA_SAMPLES: u32 = 1;
    /// The multiple-spheres control parameter.
    pub const Q: f32 = 1.0;
}

/// How a scene is rendered: built once from its settings, then read by every pass. Settings
/// given as `"auto"` hold their resolved values here (`q` per medium).
#[derive(Clone, Debug)]
pub struct Integrator {
    pub settings: IntegratorDesc,
    pub estimator: Estimator,
    /// Next-event estimation of direct light, when any light is handled by it.
    pub direct: Option<Direct>,
    /// Light tracing to the camera (`camera_splat`): the key, or its default.
    pub splat_to_camera: bool,
    pub radius: RadiusSchedule,
    /// `radius_indirect` over the starting radius (1 when not set).
    pub indirect_scale: f32,
    /// Whether passes whose radius for scattered light the pilots doubled also estimate that
    /// light at the direct radius, for the film's blend of the two (`film::blend`): with
    /// `radius_indirect = "auto"`, on a film without light layers (whose images would be the
    /// larger radius's alone and no longer sum to the blended total). Sensors keep the larger
    /// radius unblended: their values are their own estimates, not the image's pixels.
    pub blend_allowed: bool,
    pub forward_rays: u64,
    pub camera_samples: u32,
    /// The multiple-spheres q of each medium.
    pub q: Vec<f32>,
}

impl Integrator {
    /// The integrator the (validated) settings describe, for `scene`.
    pub fn from_desc(desc: &IntegratorDesc, scene: &Scene) -> Result<Self, MediumError> {
        let q = vec![desc.q.value().unwrap_or(defaults::Q); scene.media.len()];
        let r0 = match desc.radius.value() {
            Some(r) => r,
            None => radius::auto_radius(&scene.camera, &scene.geometry),
        };
        let direct = Direct::from_desc(desc, scene);
        let splat_to_camera = desc
            .splat_to_camera
            .unwrap_or_else(|| splat_by_default(desc, direct.as_ref(), scene));
        Ok(Self {
            settings: desc.clone(),
            estimator: Estimator::from_desc(desc, &q, &scene.media)?,
            direct,
            splat_to_camera,
            radius: RadiusSchedule {
                r0,
                shrink: desc.shrink(),
            },
            indirect_scale: desc.radius_indirect_value().map_or(1.0, |ri| ri / r0),
            blend_allowed: desc.radius_indirect_auto() && scene.film_extras.light_layers.is_empty(),
            forward_rays: desc.forward_rays.value().unwrap_or(defaults::FORWARD_RAYS),
            camera_samples: desc
                .camera_samples
                .value()
                .unwrap_or(defaults::CAMERA_SAMPLES),
            q,
        })
    }
}

/// `splat_to_camera`'s default: on when next-event estimation is in use and leaves the direct
/// light of some light to forward rays (a laser, a spot narrower than
/// `direct::NARROW_SPOT_DEGREES`, a light with `direct = "photons"`). Such light is a thin beam
/// or a small spot that gathered volumes blur over a radius and find only by the camera samples
/// near it; splatted, it is sharp (fog-room-laser: 7x lower error at equal time,
/// docs/performance.md). Off with `direct = "photons"`, whose images keep the paper's method.
fn splat_by_default(desc: &IntegratorDesc, direct: Option<&Direct>, scene: &Scene) -> bool {
    match desc.direct {
        DirectMode::Photons => false,
        DirectMode::Nee => {
            (0..scene.lights.lights().len() as u32).any(|i| !direct.is_some_and(|d| d.handles(i)))
        }
    }
}

impl Integrator {
    /// The radii of film pass `p`: the schedule's radius, and the indirect one in the ratio the
    /// settings give.
    pub fn radii(&self, p: u64) -> Radii {
        let r = self.radius.at(p);
        Radii {
            direct: r,
            indirect: if self.indirect_scale == 1.0 {
                r
            } else {
                r * self.indirect_scale
            },
            blend: self.blend_allowed && self.indirect_scale != 1.0,
        }
    }

    /// How the passes sample now (q per medium, forward rays, camera paths per pixel).
    pub fn pass_config(&self) -> auto::PassConfig {
        auto::PassConfig {
            q: self.q.clone(),
            forward_rays: self.forward_rays,
            camera_samples: self.camera_samples,
            indirect_scale: self.indirect_scale,
        }
    }

    /// Makes the next passes sample as `c` says (an automatic setting's pilot or choice).
    pub fn apply(
        &mut self,
        c: &auto::PassConfig,
        media: &[crate::medium::Medium],
    ) -> Result<(), MediumError> {
        if c.q != self.q {
            self.estimator = Estimator::from_desc(&self.settings, &c.q, media)?;
            self.q = c.q.clone();
        }
        self.forward_rays = c.forward_rays;
        self.camera_samples = c.camera_samples;
        self.indirect_scale = c.indirect_scale;
        Ok(())
    }
}

#[cfg(test)]
mod tests;
