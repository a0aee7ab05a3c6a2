use serde::{Deserialize, Serialize};

use super::SpectrumRef;

#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum LightKind {
    /// Parallel light; `irradiance` W/m^2 on a plane normal to `direction`.
    Directional,
    /// Isotropic point light of total `power` W.
    Point,
    /// Point light under a conical shade (`angle` half-angle, `soft_edge` degrees).
    Spot,
    /// Collimated beam of `radius` metres and total `power` W.
    Laser,
}

#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LightDesc {
    #[serde(rename = "type")]
    pub kind: LightKind,
    /// Relative spectral shape; scaled so that its integral over the spectral range is `power`
    /// (or `irradiance`). Default: the D65 illuminant.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub spectrum: Option<SpectrumRef>,
    /// Total emitted power in watts (point, spot, laser).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub power: Option<f32>,
    /// Irradiance in W/m^2 (directional).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub irradiance: Option<f32>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub position: Option<[f32; 3]>,
    /// Direction light travels in (directional, spot, laser).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub direction: Option<[f32; 3]>,
    /// Spot half-angle in degrees.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub angle: Option<f32>,
    /// Width in degrees of the spot's soft edge.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub soft_edge: Option<f32>,
    /// Laser beam radius in metres.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub radius: Option<f32>,
}
