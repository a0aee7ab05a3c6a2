//! Output units and display exposure: `film.units` and `film.exposure` (stops, or "auto").

use std::fmt;

use serde::de::{self, Deserializer, Visitor};
use serde::{Deserialize, Serialize, Serializer};

use crate::colour::FilmToRgb;
use crate::film::SpectralImage;

/// What an EXR's colour channels hold.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Units {
    /// The film's XYZ (Y = 1 for a constant spectral radiance of 1 W/(m² sr nm)) in the
    /// working space.
    #[default]
    Radiometric,
    /// The same scaled by K_m times the integral of the observer's y-bar, so that Y is the
    /// luminance in cd/m² (1931 observer); X and Z on the same scale.
    Photometric,
}

impl Units {
    pub fn name(self) -> &'static str {
        match self {
            Units::Radiometric => "radiometric",
            Units::Photometric => "photometric",
        }
    }
}

/// Exposure of display outputs: a number of stops, or "auto" (metered per image).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Exposure {
    Stops(f32),
    /// The log-average luminance is mapped to middle grey, unless that would push the
    /// brightest 1 % past white (see [`protected_stops`]).
    Auto,
}

impl Default for Exposure {
    fn default() -> Self {
        Exposure::Stops(0.0)
    }
}

impl Exposure {
    /// The stops to apply to `img` shown through a view whose white is scene value `white`
    /// ([`crate::colour::ViewTransform::white`]).
    pub fn stops(self, img: &SpectralImage, conv: &FilmToRgb, white: f32) -> f32 {
        match self {
            Exposure::Stops(s) => s,
            Exposure::Auto => protected_stops(img, conv, white),
        }
    }

    /// The default of a film in `units`: 0 stops for radiometric films, whose values are in
    /// the scene's own scale; `"auto"` for photometric ones, whose values are true luminances
    /// (a 159 cd/m² grey wall is 0.002 in film units: black at 0 stops).
    pub fn default_for(units: Units) -> Self {
        match units {
            Units::Radiometric => Exposure::Stops(0.0),
            Units::Photometric => Exposure::Auto,
        }
    }
}

impl std::str::FromStr for Exposure {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        if s == "auto" {
            return Ok(Exposure::Auto);
        }
        s.parse::<f32>()
            .map(Exposure::Stops)
            .map_err(|_| format!("`{s}` is neither a number of stops nor \"auto\""))
    }
}

impl Serialize for Exposure {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        match self {
            Exposure::Stops(v) => s.serialize_f32(*v),
            Exposure::Auto => s.serialize_str("auto"),
        }
    }
}

impl<'de> Deserialize<'de> for Exposure {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct V;
        impl Visitor<'_> for V {
            type Value = Exposure;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                write!(f, "a number of stops or \"auto\"")
            }
            fn visit_f64<E: de::Error>(self, v: f64) -> Result<Exposure, E> {
                Ok(Exposure::Stops(v as f32))
            }
            fn visit_i64<E: de::Error>(self, v: i64) -> Result<Exposure, E> {
                Ok(Exposure::Stops(v as f32))
            }
            fn visit_u64<E: de::Error>(self, v: u64) -> Result<Exposure, E> {
                Ok(Exposure::Stops(v as f32))
            }
            fn visit_str<E: de::Error>(self, v: &str) -> Result<Exposure, E> {
                match v {
                    "auto" => Ok(Exposure::Auto),
                    _ => Err(E::invalid_value(de::Unexpected::Str(v), &self)),
                }
            }
        }
        d.deserialize_any(V)
    }
}

/// Pixels darker than this fraction of the 99th percentile count as this fraction in the
/// log-average, so that a black sky does not drag the exposure up without bound.
const FLOOR: f64 = 1e-3;
/// Where the log-average luminance lands (middle grey).
const MIDDLE_GREY: f64 = 0.18;

/// The pixels' finite Y, sorted, and their 99th percentile (None for an image with no
/// positive 99th percentile: black, or nothing finite).
fn sorted_y(img: &SpectralImage, conv: &FilmToRgb) -> Option<(Vec<f64>, f64)> {
    let mut y: Vec<f64> = img
        .data
        .chunks_exact(img.grid.n)
        .map(|px| conv.xyz.xyz(px)[1])
        .filter(|v| v.is_finite())
        .collect();
    if y.is_empty() {
        return None;
    }
    y.sort_by(f64::total_cmp);
    let p99 = y[((y.len() - 1) as f64 * 0.99) as usize];
    (p99 > 0.0).then_some((y, p99))
}

/// Metered exposure (stops): the log-average of the pixels' Y (Reinhard et al. 2002's key),
/// each at least [`FLOOR`] times the 99th percentile, mapped to middle grey. 0 for a black
/// image; within [-64, 64].
pub fn metered_stops(img: &SpectralImage, conv: &FilmToRgb) -> f32 {
    let Some((y, p99)) = sorted_y(img, conv) else {
        return 0.0;
    };
    let floor = p99 * FLOOR;
    let log_avg = (y.iter().map(|v| v.max(floor).ln()).sum::<f64>() / y.len() as f64).exp();
    ((MIDDLE_GREY / log_avg).log2() as f32).clamp(-64.0, 64.0)
}

/// `"auto"` exposure (stops): [`metered_stops`], with highlight protection: never more than
/// puts the 99th percentile of Y at `white`, the scene value the view transform shows as white
/// (so a white wall over more than 1 % of the image is not clipped, where the log-average of a
/// dark foggy scene alone would push it far past white). 0 for a black image.
pub fn protected_stops(img: &SpectralImage, conv: &FilmToRgb, white: f32) -> f32 {
    let Some((_, p99)) = sorted_y(img, conv) else {
        return 0.0;
    };
    let highlight = ((white as f64 / p99).log2() as f32).clamp(-64.0, 64.0);
    metered_stops(img, conv).min(highlight)
}
