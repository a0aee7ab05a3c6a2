//! Next-event estimation (NEE) of direct light, beside the gathered estimators (issue 15,
//! method note 9). "Direct" light is emitted and arrives through index-matched boundaries
//! only. For each light handled here, camera paths estimate it (single scattering along the
//! medium segments where they leave volumes, reflection where they gather on surfaces), and
//! that light's forward rays deposit nothing before their first scattering or surface event:
//! every light path is counted once, by one side.
//!
//! - `sampling.rs`: distance samplers along a camera segment, with their densities;
//! - `shadow.rs`: transmittance of shadow rays through null boundaries and media;
//! - `medium.rs`: the single-scattering estimate of one camera segment;
//! - `surface.rs`: the reflected estimate at a surface gather point;
//! - `pick.rs`: which light each sample goes to (`integrator.light_pick`);
//! - `sensor.rs`: the irradiance at an illuminance sensor.

mod medium;
mod pick;

pub use medium::Segment;
pub use pick::Receiver;
pub mod sampling;
mod sensor;
pub(super) mod shadow;
mod surface;

pub use surface::Part;

use crate::light::{DirectChoice, Light};
use crate::world::Scene;

use super::settings::{DirectMode, IntegratorDesc, LightPick};

/// Spot lights narrower than this half-angle (degrees) keep their direct light with the
/// forward rays under a light's `direct = "auto"`: a camera segment rarely meets so thin a
/// cone, while forward rays concentrate in it (as for a laser). A light's `direct = "nee"` or
/// `"photons"` overrides the rule.
pub const NARROW_SPOT_DEGREES: f32 = 1.0;

/// Which lights next-event estimation handles and how it picks among them.
#[derive(Clone, Debug)]
pub struct Direct {
    /// Per scene light: handled here.
    nee: Vec<bool>,
    /// The handled lights with the cumulative probability of picking them by power (the
    /// `power` pick, and the fallback of the `local` one where its estimate is degenerate).
    picks: Vec<(u32, f32)>,
    /// Per scene light: the probability of picking it (0 when not handled).
    prob: Vec<f32>,
    /// Per scene light: what the local pick's estimate needs of it.
    reach: Vec<pick::Reach>,
    pick: LightPick,
    samples: u32,
}

impl Direct {
    /// The NEE of a scene under `desc`, or None when no light is handled by it (`direct =
    /// "photons"`, or only lasers and narrow spots).
    pub fn from_desc(desc: &IntegratorDesc, scene: &Scene) -> Option<Self> {
        match desc.direct {
            DirectMode::Photons => return None,
            DirectMode::Nee => {}
        }
        let lights = scene.lights.lights();
        let nee: Vec<bool> = lights
            .iter()
            .enumerate()
            .map(|(i, l)| match scene.lights.direct_choice(i) {
                DirectChoice::Auto => auto_nee(l),
                DirectChoice::Nee => l.nee_capable(),
                DirectChoice::Photons => false,
            })
            .collect();
        let weights: Vec<f64> = lights
            .iter()
            .zip(&nee)
            .map(|(l, &on)| {
                let p = scene.grid.weighted_sum(&l.power(&scene.geometry));
                if on && p.is_finite() && p > 0.0 {
                    p
                } else {
                    0.0
                }
            })
            .collect();
        let total: f64 = weights.iter().sum();
        if total <= 0.0 {
            return None;
        }
        let mut acc = 0.0;
        let picks = weights
            .iter()
            .enumerate()
            .filter(|(_, w)| **w > 0.0)
            .map(|(i, w)| {
                acc += w;
                (i as u32, (acc / total) as f32)
            })
            .collect();
        let prob = weights.iter().map(|w| (w / total) as f32).collect();
        let reach = lights
            .iter()
            .map(|l| pick::Reach::of(l, &scene.geometry, &scene.grid))
            .collect();
        Some(Self {
            nee,
            picks,
            prob,
            reach,
            pick: desc.light_pick,
            samples: desc.nee_samples.max(1),
        })
    }

    /// Whether light `i`'s direct light is estimated here (so its forward rays must not
    /// deposit it).
    pub fn handles(&self, i: u32) -> bool {
        self.nee.get(i as usize).copied().unwrap_or(false)
    }

    /// The probability of picking light `i` by power (`LightPick::Power`).
    fn probability(&self, i: u32) -> f32 {
        self.prob.get(i as usize).copied().unwrap_or(0.0)
    }

    /// A handled light by power from a uniform `u`: (index, probability).
    fn pick(&self, u: f32) -> (u32, f32) {
        let k = self
            .picks
            .partition_point(|&(_, c)| c <= u)
            .min(self.picks.len() - 1);
        let below = if k == 0 { 0.0 } else { self.picks[k - 1].1 };
        (self.picks[k].0, self.picks[k].1 - below)
    }
}

/// The `auto` rule: NEE for every light a sampled direction can reach, except spots narrower
/// than `NARROW_SPOT_DEGREES`.
fn auto_nee(light: &Light) -> bool {
    match light {
        Light::Spot { profile, .. } => profile.cos_edge() < NARROW_SPOT_DEGREES.to_radians().cos(),
        Light::Directional { .. }
        | Light::Point { .. }
        | Light::Area { .. }
        | Light::Laser { .. } => light.nee_capable(),
    }
}
