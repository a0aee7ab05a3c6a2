//! Colour science: spectrum -> CIE XYZ -> working space, chromatic adaptation, display encoding.

use serde::{Deserialize, Serialize};

/// The RGB (or XYZ) space scene-linear outputs are written in.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum ColourSpace {
    /// Linear Rec.709 / sRGB primaries, D65 white.
    #[default]
    Srgb,
    /// ACEScg (AP1 primaries, ACES white).
    Acescg,
    /// CIE XYZ itself.
    Xyz,
}

/// CIE standard observer used to turn spectra into XYZ.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub enum Observer {
    #[default]
    #[serde(rename = "1931")]
    Cie1931,
    #[serde(rename = "1964")]
    Cie1964,
}

/// How scene-linear values become display values in the PNG.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum ViewTransform {
    /// Exposure, clip to [0, 1], sRGB encoding (matches OCIO's un-tone-mapped sRGB display).
    #[default]
    Clip,
    /// Exposure, a filmic shoulder, sRGB encoding.
    Filmic,
}
