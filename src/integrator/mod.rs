//! The bidirectional engine: camera pass -> gather structure -> light pass -> film.
//!
//! An [`Integrator`] is built once from the `[integrator]` settings and owned by the
//! [`Renderer`]: the settings, the integration-volume [`Estimator`], next-event estimation of
//! direct light ([`Direct`]) and the radius schedule.
//! The runtime scene (`world::Scene`) holds the content it renders.

mod camera_pass;
pub mod direct;
pub mod estimator;
mod exp;
pub mod gather;
mod light_pass;
mod memory;
mod oct;
mod pass;
mod path;
mod radius;
pub mod record;
mod rng;
pub mod settings;
mod throughput;

pub use direct::Direct;
pub use estimator::Estimator;
pub use memory::MemoryEstimate;
pub use pass::{Budget, Renderer, Stats};
pub use radius::{RadiusSchedule, radius_for_pass};
pub use settings::{DEFAULT_GATHER_BYTES, DirectMode, GatherMode, IntegratorDesc, VolumeKind};

use crate::medium::MediumError;
use crate::world::Scene;

/// How a scene is rendered: built once from its settings, then read by every pass.
#[derive(Clone, Debug)]
pub struct Integrator {
    pub settings: IntegratorDesc,
    pub estimator: Estimator,
    /// Next-event estimation of direct light, when any light is handled by it.
    pub direct: Option<Direct>,
    pub radius: RadiusSchedule,
}

impl Integrator {
    /// The integrator the (validated) settings describe, for `scene`.
    pub fn from_desc(desc: &IntegratorDesc, scene: &Scene) -> Result<Self, MediumError> {
        Ok(Self {
            settings: desc.clone(),
            estimator: Estimator::from_desc(desc, &scene.media)?,
            direct: Direct::from_desc(desc, scene),
            radius: RadiusSchedule {
                r0: desc.radius,
                alpha: desc.alpha,
            },
        })
    }
}

#[cfg(test)]
mod tests;
