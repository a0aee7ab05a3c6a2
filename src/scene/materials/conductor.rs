//! `type = "conductor"`: a rough metal (GGX, Smith height-correlated), its Fresnel factor from a
//! complex index (`eta`, `k`: spectra, or a metal's name such as `"gold"`) or from a
//! normal-incidence reflectance `f0` (Schlick; glTF's metallic workflow).

use std::fmt;

use serde::de::{self, SeqAccess, Visitor};
use serde::{Deserialize, Deserializer, Serialize, Serializer};

use crate::material::{ConductorFresnel, Material, is_metal, metal_index, metal_names};
use crate::scene::builder::Builder;
use crate::scene::check::{Checker, above_one};
use crate::scene::error::SceneError;
use crate::scene::spectrum_desc::SpectrumRef;
use crate::spectrum::Spectrum;

/// GGX alpha when none is given (as the glossy coat's).
pub const DEFAULT_ROUGHNESS: f32 = 0.1;

/// GGX alpha: one number (isotropic) or `[alpha_u, alpha_v]` along the two tangent axes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Roughness {
    Isotropic(f32),
    Anisotropic([f32; 2]),
}

impl Roughness {
    pub fn alphas(&self) -> [f32; 2] {
        match *self {
            Roughness::Isotropic(a) => [a, a],
            Roughness::Anisotropic(a) => a,
        }
    }
}

impl Serialize for Roughness {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        match self {
            Roughness::Isotropic(a) => s.serialize_f32(*a),
            Roughness::Anisotropic(a) => a.serialize(s),
        }
    }
}

impl<'de> Deserialize<'de> for Roughness {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct V;
        impl<'de> Visitor<'de> for V {
            type Value = Roughness;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                f.write_str("a GGX alpha (a number) or [alpha_u, alpha_v]")
            }
            fn visit_f64<E: de::Error>(self, v: f64) -> Result<Roughness, E> {
                Ok(Roughness::Isotropic(v as f32))
            }
            fn visit_i64<E: de::Error>(self, v: i64) -> Result<Roughness, E> {
                Ok(Roughness::Isotropic(v as f32))
            }
            fn visit_u64<E: de::Error>(self, v: u64) -> Result<Roughness, E> {
                Ok(Roughness::Isotropic(v as f32))
            }
            fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Roughness, A::Error> {
                let mut a = [0.0f32; 2];
                for (i, c) in a.iter_mut().enumerate() {
                    *c = seq
                        .next_element()?
                        .ok_or_else(|| de::Error::invalid_length(i, &"2 numbers"))?;
                }
                if seq.next_element::<f64>()?.is_some() {
                    return Err(de::Error::invalid_length(3, &"2 numbers"));
                }
                Ok(Roughness::Anisotropic(a))
            }
        }
        d.deserialize_any(V)
    }
}

#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ConductorDesc {
    /// GGX alpha; below `material::SMOOTH_ALPHA` on both axes a delta mirror.
    #[serde(default = "default_roughness")]
    pub roughness: Roughness,
    /// Real part of the complex index: a metal's name or a spectrum.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub eta: Option<SpectrumRef>,
    /// Imaginary part (absorption): a metal's name or a spectrum; by default the metal's that
    /// `eta` names.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub k: Option<SpectrumRef>,
    /// Normal-incidence reflectance (Schlick), instead of `eta` and `k`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub f0: Option<SpectrumRef>,
}

fn default_roughness() -> Roughness {
    Roughness::Isotropic(DEFAULT_ROUGHNESS)
}

/// A name that means a metal's table: a metal that [spectra] does not redefine.
fn metal_name(r: Option<&SpectrumRef>, defined: impl Fn(&str) -> bool) -> Option<&str> {
    match r? {
        SpectrumRef::Named(n) if is_metal(n) && !defined(n) => Some(n),
        SpectrumRef::Named(_)
        | SpectrumRef::Constant(_)
        | SpectrumRef::Rgb(_)
        | SpectrumRef::Lines(_) => None,
    }
}

/// `eta` or `k`: a metal's name or a spectrum (`eta` > 0, `k` >= 0 where constant).
fn check_index(c: &mut Checker, key: &str, r: &SpectrumRef, positive: bool) {
    match r {
        SpectrumRef::Named(n) if is_metal(n) => {}
        SpectrumRef::Named(n) if !c.names_spectrum(n) => {
            let metals = metal_names().collect::<Vec<_>>().join(", ");
            c.fail(
                key,
                format!(
                    "`{n}` is not a metal ({metals}), a spectrum in [spectra], a built-in \
                     spectrum or a CSV file"
                ),
            );
        }
        SpectrumRef::Constant(v) if positive => c.positive(key, *v),
        _ => c.spectrum_ref(key, r),
    }
}

impl ConductorDesc {
    pub(super) fn check(&self, c: &mut Checker, key: &str) {
        let alphas = self.roughness.alphas();
        for (i, a) in alphas.iter().enumerate() {
            let k = match self.roughness {
                Roughness::Isotropic(_) => format!("{key}.roughness"),
                Roughness::Anisotropic(_) => format!("{key}.roughness.{i}"),
            };
            c.range_f32(&k, *a, 0.0, 1.0, "a GGX alpha in [0, 1]");
        }
        if let Some(f0) = &self.f0 {
            if self.eta.is_some() || self.k.is_some() {
                c.fail(
                    format!("{key}.f0"),
                    "give either `f0` (Schlick) or `eta` and `k` (a complex index), not both",
                );
            }
            return c.reflectance_ref(&format!("{key}.f0"), f0, false);
        }
        let Some(eta) = &self.eta else {
            return c.fail(
                key,
                "needs `eta` (a metal's name, or a spectrum with `k`) or `f0`",
            );
        };
        check_index(c, &format!("{key}.eta"), eta, true);
        match &self.k {
            Some(k) => check_index(c, &format!("{key}.k"), k, false),
            None => {
                let spectra = c.names.spectra;
                if metal_name(Some(eta), |n| spectra.contains_key(n)).is_none() {
                    c.fail(
                        key,
                        "needs `k` (the absorption index) when `eta` is not a metal's name",
                    );
                }
            }
        }
    }

    pub(super) fn build(&self, b: &Builder, key: &str) -> Result<Material, SceneError> {
        let fresnel = match &self.f0 {
            Some(f0) => {
                let key = format!("{key}.f0");
                let f0 = b.spectra.reflectance(f0, &key)?;
                if f0.max_value() > 1.0 {
                    return Err(b.source.invalid(&key, above_one(f0.max_value() as f64)));
                }
                ConductorFresnel::Schlick { f0 }
            }
            None => {
                let eta = index(b, self.eta.as_ref(), key, "eta", 0)?;
                let k = match &self.k {
                    Some(_) => index(b, self.k.as_ref(), key, "k", 1)?,
                    None => index(b, self.eta.as_ref(), key, "eta", 1)?,
                };
                ConductorFresnel::Complex { eta, k }
            }
        };
        Ok(Material::conductor(
            self.roughness.alphas(),
            fresnel,
            b.grid.n,
        ))
    }
}

/// The spectrum `r` gives at `key.name`, or for a metal's name its column `part` (0: n, 1: k);
/// every bin finite, n > 0 and k >= 0.
fn index(
    b: &Builder,
    r: Option<&SpectrumRef>,
    key: &str,
    name: &str,
    part: usize,
) -> Result<Spectrum, SceneError> {
    let key = format!("{key}.{name}");
    let Some(r) = r else {
        return Err(b.source.invalid(&key, "missing"));
    };
    let s = match metal_name(Some(r), |n| b.spectra.defines(n)) {
        Some(metal) => match metal_index(metal, &b.grid) {
            Some(Ok((n, k))) => [n, k][part],
            Some(Err(e)) => return Err(b.source.invalid(&key, e.to_string())),
            None => return Err(b.source.invalid(&key, format!("no metal `{metal}`"))),
        },
        None => b.spectra.unbounded(r, &key)?,
    };
    let bad = s.as_slice(b.grid.n).iter().find(|&&v| {
        let ok = if part == 0 { v > 0.0 } else { v >= 0.0 };
        !(v.is_finite() && ok)
    });
    if let Some(v) = bad {
        let what = if part == 0 { "> 0" } else { ">= 0" };
        return Err(b.source.invalid(
            &key,
            format!("must be finite and {what} in every bin, got {v}"),
        ));
    }
    Ok(s)
}
