use serde::{Deserialize, Serialize};

use super::SpectrumRef;

/// A homogeneous medium. Coefficients are in 1/m.
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MediumDesc {
    pub sigma_s: SpectrumRef,
    #[serde(default = "zero")]
    pub sigma_a: SpectrumRef,
    /// Henyey-Greenstein anisotropy in (-1, 1).
    #[serde(default)]
    pub g: f32,
}

fn zero() -> SpectrumRef {
    SpectrumRef::Constant(0.0)
}
