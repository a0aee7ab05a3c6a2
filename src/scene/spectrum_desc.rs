use std::fmt;

use serde::de::{self, MapAccess, SeqAccess, Visitor};
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

/// Spectral lines, an emission only: `{ line = 532.0 }` (one line) or
/// `{ lines = [[532.0, 1.0], [1064.0, 0.1]] }` (wavelengths in nm with relative powers). All of
/// a line's power is at its wavelength; the spectral grid gives each line a narrow bin.
/// Read by [`SpectrumRef`]'s own deserializer, which refuses other keys.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct LinesDesc {
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub line: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub lines: Option<Vec<[f64; 2]>>,
}

/// One line of a [`LinesDesc`]: where its wavelength and power are written (keys relative to
/// the spectrum's own key; the power's is `None` for `line = ...`, whose power is 1).
#[derive(Clone, Debug, PartialEq)]
pub struct LineEntry {
    pub lambda: f64,
    pub power: f64,
    pub lambda_key: String,
    pub power_key: Option<String>,
}

impl LinesDesc {
    /// Every line, in the order written.
    pub fn entries(&self) -> Vec<LineEntry> {
        let one = self.line.map(|lambda| LineEntry {
            lambda,
            power: 1.0,
            lambda_key: "line".into(),
            power_key: None,
        });
        let many = self
            .lines
            .iter()
            .flatten()
            .enumerate()
            .map(|(i, &[l, p])| LineEntry {
                lambda: l,
                power: p,
                lambda_key: format!("lines.{i}.0"),
                power_key: Some(format!("lines.{i}.1")),
            });
        one.into_iter().chain(many).collect()
    }
}

/// Where a spectral parameter comes from: a constant, a name (from `[spectra]` or built in),
/// an RGB triple upsampled in the parameter's own way (reflectance, emission or unbounded), or
/// (emission only) spectral lines.
#[derive(Clone, Debug, PartialEq)]
pub enum SpectrumRef {
    Constant(f64),
    Named(String),
    Rgb([f64; 3]),
    Lines(LinesDesc),
}

impl Serialize for SpectrumRef {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        match self {
            SpectrumRef::Constant(v) => s.serialize_f64(*v),
            SpectrumRef::Named(n) => s.serialize_str(n),
            SpectrumRef::Rgb(rgb) => rgb.serialize(s),
            SpectrumRef::Lines(l) => l.serialize(s),
        }
    }
}

impl<'de> Deserialize<'de> for SpectrumRef {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct V;
        impl<'de> Visitor<'de> for V {
            type Value = SpectrumRef;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                f.write_str(
                    "a number, the name of a spectrum, an RGB array [r, g, b], or lines \
                     ({ line = 532.0 } or { lines = [[532.0, 1.0], ...] })",
                )
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
            fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<SpectrumRef, A::Error> {
                let mut l = LinesDesc::default();
                while let Some(key) = map.next_key::<String>()? {
                    match key.as_str() {
                        "line" => l.line = Some(map.next_value()?),
                        "lines" => l.lines = Some(map.next_value()?),
                        other => {
                            return Err(de::Error::custom(format!(
                                "unknown key `{other}`: a table in place of a spectrum holds \
                                 spectral lines (`line = <nm>` or `lines = [[<nm>, <power>], \
                                 ...]`); other spectra are a number, a name (e.g. of a \
                                 [spectra.NAME] table) or an RGB triple"
                            )));
                        }
                    }
                }
                Ok(SpectrumRef::Lines(l))
            }
        }
        d.deserialize_any(V)
    }
}
