//! Colour science: spectrum -> CIE XYZ -> working space, chromatic adaptation, display
//! encoding, and the way back (RGB -> spectrum, `rgb`).

use serde::{Deserialize, Serialize};

mod adapt;
mod convert;
pub mod describe;
mod display;
pub mod matrix;
mod observer;
pub mod photometry;
pub mod rgb;
mod space;

pub use adapt::Cat;
pub use convert::FilmToRgb;
pub use display::{srgb_decode, srgb_encode};
pub use observer::{Cmfs, XyzWeights};
pub use rgb::{RgbKind, rgb_to_spectrum};
pub use space::{ACES_XY, AP1_PRIMARIES, D65_XY, E_XY, REC709_PRIMARIES, XYZ_PRIMARIES};

use crate::spectrum::SpectrumError;

#[derive(Debug, thiserror::Error)]
pub enum ColourError {
    #[error(transparent)]
    Spectrum(#[from] SpectrumError),
    #[error("{0}")]
    Other(String),
}

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
    /// CIE 1931 2-degree.
    #[default]
    #[serde(rename = "1931")]
    Cie1931,
    /// CIE 1964 10-degree.
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

impl std::str::FromStr for Observer {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "1931" | "cie1931" | "2" => Ok(Observer::Cie1931),
            "1964" | "cie1964" | "10" => Ok(Observer::Cie1964),
            _ => Err(format!("unknown observer {s:?} (use 1931 or 1964)")),
        }
    }
}
