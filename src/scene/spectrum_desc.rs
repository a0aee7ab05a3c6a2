use std::fmt;

use serde::de::{self, SeqAccess, Visitor};
use serde::{Deserialize, Deserializer, Serialize, Serializer};

/// How an RGB triple is turned into a spectrum.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum RgbKind {
    /// Bounded to [0, 1] (albedos, reflectances).
    #[default]
    Reflectance,
    /// Emission: the RGB scales an illuminant-shaped spectrum.
    Emission,
    /// Unbounded non-negative values (scattering or absorption coefficients).
    Unbounded,
}

/// `sigma(lambda) = k * (lambda / lambda_ref)^-p`, e.g. p = 4 for Rayleigh scattering.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PowerLaw {
    pub k: f64,
    pub p: f64,
    #[serde(default = "default_lambda_ref")]
    pub lambda_ref: f64,
}

fn default_lambda_ref() -> f64 {
    550.0
}

/// A named spectrum in the `[spectra]` section: exactly one source key, then an optional scale.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct SpectrumDesc {
    /// CSV file (wavelength in nm, then value columns), relative to the scene file.
    pub file: Option<String>,
    /// Column of the CSV to use (default: the second column).
    pub column: Option<String>,
    /// A built-in spectrum by name (e.g. "D65", "A").
    pub builtin: Option<String>,
    /// A constant.
    pub value: Option<f64>,
    /// A linear sRGB triple, upsampled (Jakob & Hanika 2019).
    pub rgb: Option<[f64; 3]>,
    pub rgb_kind: RgbKind,
    pub power_law: Option<PowerLaw>,
    /// Multiplies the spectrum.
    pub scale: Option<f64>,
}

impl SpectrumDesc {
    /// Names of the source keys present, for the "exactly one" rule.
    pub fn sources(&self) -> Vec<&'static str> {
        let mut v = Vec::new();
        if self.file.is_some() {
            v.push("file");
        }
        if self.builtin.is_some() {
            v.push("builtin");
        }
        if self.value.is_some() {
            v.push("value");
        }
        if self.rgb.is_some() {
            v.push("rgb");
        }
        if self.power_law.is_some() {
            v.push("power_law");
        }
        v
    }
}

/// Where a spectral parameter comes from: a constant, a name (from `[spectra]` or built in),
/// or an RGB triple upsampled in the parameter's own way (reflectance, emission or unbounded).
#[derive(Clone, Debug, PartialEq)]
pub enum SpectrumRef {
    Constant(f64),
    Named(String),
    Rgb([f64; 3]),
}

impl Serialize for SpectrumRef {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        match self {
            SpectrumRef::Constant(v) => s.serialize_f64(*v),
            SpectrumRef::Named(n) => s.serialize_str(n),
            SpectrumRef::Rgb(rgb) => rgb.serialize(s),
        }
    }
}

impl<'de> Deserialize<'de> for SpectrumRef {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct V;
        impl<'de> Visitor<'de> for V {
            type Value = SpectrumRef;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                f.write_str("a number, the name of a spectrum, or an RGB array [r, g, b]")
            }
            fn visit_f64<E: de::Error>(self, v: f64) -> Result<SpectrumRef, E> {
                Ok(SpectrumRef::Constant(v))
            }
            fn visit_i64<E: de::Error>(self, v: i64) -> Result<SpectrumRef, E> {
                Ok(SpectrumRef::Constant(v as f64))
            }
            fn visit_u64<E: de::Error>(self, v: u64) -> Result<SpectrumRef, E> {
                Ok(SpectrumRef::Constant(v as f64))
            }
            fn visit_str<E: de::Error>(self, v: &str) -> Result<SpectrumRef, E> {
                Ok(SpectrumRef::Named(v.to_string()))
            }
            fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<SpectrumRef, A::Error> {
                let mut rgb = [0.0; 3];
                for (i, c) in rgb.iter_mut().enumerate() {
                    *c = seq
                        .next_element()?
                        .ok_or_else(|| de::Error::invalid_length(i, &"3 numbers"))?;
                }
                if seq.next_element::<f64>()?.is_some() {
                    return Err(de::Error::invalid_length(4, &"3 numbers"));
                }
                Ok(SpectrumRef::Rgb(rgb))
            }
        }
        d.deserialize_any(V)
    }
}
