use serde::{Deserialize, Serialize};

use super::SpectrumRef;

#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum MaterialKind {
    /// Ideal diffuse reflector.
    Lambert,
    /// Perfect mirror.
    Mirror,
    /// "Slightly specular": a diffuse base under a GGX glossy coat.
    Glossy,
    /// Smooth refractive interface (glass, water).
    Dielectric,
}

#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MaterialDesc {
    #[serde(rename = "type")]
    pub kind: MaterialKind,
    /// Diffuse albedo (lambert, glossy) or reflectance (mirror).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub albedo: Option<SpectrumRef>,
    /// RGB image (PNG or EXR, linear values for EXR, sRGB-encoded for PNG) modulating the albedo.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub texture: Option<String>,
    /// Index of refraction (dielectric; glossy coat). A constant or a spectrum name.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ior: Option<SpectrumRef>,
    /// GGX roughness alpha of the glossy coat.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub roughness: Option<f32>,
}
