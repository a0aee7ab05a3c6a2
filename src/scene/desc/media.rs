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
    /// Grey fog of this meteorological optical range (m): sigma_t = ln(20) / visibility in
    /// every bin, instead of `sigma_s`/`sigma_a`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub visibility: Option<f32>,
    /// With `visibility`: the fraction of the extinction that scatters (default 1).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub albedo: Option<f32>,
    /// A density field scaling the coefficients in space (they, and `visibility`, are the
    /// values at density 1); uniform when absent.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub density: Option<crate::medium::DensityDesc>,
    /// How transport integrates the density: `"exact"` (default), `"delta"` (delta and ratio
    /// tracking against a majorant grid) or `"delta-global"` (against the global maximum).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tracking: Option<crate::medium::Tracking>,
    /// Samples per side of the majorant grid's blocks (`tracking = "delta"`; default 8).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub majorant_block: Option<u32>,
}

impl MediumDesc {
    /// The grey fog `visibility` (and `albedo`) describe, if given.
    pub fn grey_visibility(&self) -> Option<crate::medium::Visibility> {
        self.visibility.map(|metres| crate::medium::Visibility {
            metres,
            albedo: self.albedo.unwrap_or(1.0),
        })
    }

    /// Problems on the description's face: (key relative to the medium, message).
    pub fn check(&self, exists: &dyn Fn(&str) -> bool) -> Vec<(String, String)> {
        let keys = crate::medium::CoefficientKeys {
            sigma_s: self.sigma_s.is_some(),
            sigma_a: self.sigma_a != SpectrumRef::Constant(0.0),
            visibility: self.visibility,
            albedo: self.albedo,
        };
        let mut out = crate::medium::check_medium(
            keys,
            self.g,
            self.phase.as_ref(),
            self.droplets.as_ref(),
            exists,
        );
        if let Some(b) = self.majorant_block
            && !(1..=4096).contains(&b)
        {
            out.push((
                "majorant_block".into(),
                format!("{b} samples: a block has 1 to 4096 samples per side"),
            ));
        }
        if let Some(d) = &self.density {
            out.extend(
                d.check()
                    .into_iter()
                    .map(|(k, m)| (format!("density.{k}"), m)),
            );
        }
        out
    }
}

fn zero() -> SpectrumRef {
    SpectrumRef::Constant(0.0)
}
