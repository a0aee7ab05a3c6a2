use serde::{Deserialize, Serialize};

use super::SpectrumRef;
use crate::medium::PhaseDesc;
use crate::medium::droplets::DropletsDesc;

/// A homogeneous medium. Coefficients are in 1/m. Either `sigma_s` (with `sigma_a` and a
/// phase function: `g` for Henyey–Greenstein or `phase = { type = ... }`) or `[droplets]`,
/// which give the coefficients and the phase by Lorenz–Mie theory (`sigma_a` then adds to the
/// droplets' absorption). The checks and defaults live in `medium::build`.
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MediumDesc {
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sigma_s: Option<SpectrumRef>,
    #[serde(default = "zero")]
    pub sigma_a: SpectrumRef,
    /// Henyey-Greenstein anisotropy in (-1, 1) (default 0 when no `phase` is given).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub g: Option<f32>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub phase: Option<PhaseDesc>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub droplets: Option<DropletsDesc>,
}

impl MediumDesc {
    /// Problems on the description's face: (key relative to the medium, message).
    pub fn check(&self, exists: &dyn Fn(&str) -> bool) -> Vec<(String, String)> {
        crate::medium::check_medium(
            self.sigma_s.is_some(),
            self.g,
            self.phase.as_ref(),
            self.droplets.as_ref(),
            exists,
        )
    }
}

fn zero() -> SpectrumRef {
    SpectrumRef::Constant(0.0)
}
