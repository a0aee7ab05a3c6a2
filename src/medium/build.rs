//! From a scene's medium description (spectra already resolved) to the runtime medium, with
//! the checks that need no file (for the scene validator) and the defaults.

use std::path::PathBuf;

use super::droplets::{self, DropletOptics, DropletsDesc};
use super::{Medium, MediumError, Phase, PhaseDesc};
use crate::spectrum::{SpectralGrid, Spectrum};

/// A medium description's parts: `sigma_s`/`sigma_a` resolved to bins, and its phase keys.
#[derive(Clone, Copy, Debug)]
pub struct MediumParts<'a> {
    pub sigma_s: Option<&'a Spectrum>,
    pub sigma_a: &'a Spectrum,
    /// The short form `g = ...` (Henyey–Greenstein).
    pub g: Option<f32>,
    pub phase: Option<&'a PhaseDesc>,
    pub droplets: Option<&'a DropletsDesc>,
    /// Grey fog given by its meteorological optical range (m) and single-scattering albedo:
    /// replaces `sigma_s` and `sigma_a`.
    pub visibility: Option<Visibility>,
}

/// A grey medium given by its visibility: extinction ln(20) / `metres` in every bin (the
/// meteorological optical range of a grey medium, whatever the lamp), `albedo` of it
/// scattered (default 1: all scattering, as for water fog), the rest absorbed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Visibility {
    pub metres: f32,
    pub albedo: f32,
}

impl Visibility {
    /// `sigma_t` (1/m) of a grey medium of this visibility.
    pub fn sigma_t(&self) -> f32 {
        (20f64.ln() / self.metres as f64) as f32
    }
}

/// What a medium's description gives its coefficients by, for the checks.
#[derive(Clone, Copy, Debug, Default)]
pub struct CoefficientKeys {
    pub sigma_s: bool,
    /// `sigma_a` given and not zero.
    pub sigma_a: bool,
    pub visibility: Option<f32>,
    pub albedo: Option<f32>,
}

/// A built medium and, for droplet fog, the Lorenz–Mie results it came from.
#[derive(Clone, Debug)]
pub struct BuiltMedium {
    pub medium: Medium,
    pub droplets: Option<DropletOptics>,
}

/// An error with the key it is about, relative to the medium (`phase.file`, `droplets`, ...).
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("{error}")]
pub struct KeyedError {
    pub key: String,
    pub error: MediumError,
}

fn keyed(key: &str) -> impl Fn(MediumError) -> KeyedError + '_ {
    move |error| KeyedError {
        key: key.to_string(),
        error,
    }
}

/// Problems a medium description has on its face: (key relative to the medium, message).
/// `exists` tells whether a file named in the scene exists.
pub fn check(
    keys: CoefficientKeys,
    g: Option<f32>,
    phase: Option<&PhaseDesc>,
    droplets: Option<&DropletsDesc>,
    exists: &dyn Fn(&str) -> bool,
) -> Vec<(String, String)> {
    let mut out = check_visibility(keys, droplets.is_some());
    match (keys.sigma_s, droplets.is_some()) {
        (false, false) if keys.visibility.is_none() => out.push((
            String::new(),
            "needs `sigma_s`, `visibility` or `[droplets]`".into(),
        )),
        (true, true) => out.push((
            "sigma_s".into(),
            "droplets give the scattering coefficient: drop `sigma_s`".into(),
        )),
        (false, false) | (true, false) | (false, true) => {}
    }
    if let Some(g) = g {
        if !(g.is_finite() && g.abs() < 1.0) {
            out.push(("g".into(), format!("must be in (-1, 1), got {g}")));
        }
        if phase.is_some() {
            out.push((
                "g".into(),
                "give either `g` (Henyey-Greenstein) or `phase`".into(),
            ));
        }
    }
    if droplets.is_some() && (g.is_some() || phase.is_some()) {
        let key = if g.is_some() { "g" } else { "phase" };
        out.push((
            key.into(),
            "droplets give the phase function (Lorenz-Mie)".into(),
        ));
    }
    if let Some(p) = phase {
        for (k, m) in p.check() {
            out.push((format!("phase.{k}"), m));
        }
        if let PhaseDesc::Tabulated { file } = p
            && !exists(file)
        {
            out.push(("phase.file".into(), format!("file not found: {file}")));
        }
    }
    if let Some(d) = droplets {
        for (k, m) in d.check(exists) {
            let key = if k.is_empty() {
                "droplets".into()
            } else {
                format!("droplets.{k}")
            };
            out.push((key, m));
        }
    }
    out
}

/// The checks of `visibility` and `albedo`.
fn check_visibility(keys: CoefficientKeys, droplets: bool) -> Vec<(String, String)> {
    let mut out = Vec::new();
    let Some(v) = keys.visibility else {
        if keys.albedo.is_some() {
            out.push((
                "albedo".into(),
                "goes with `visibility` (give `sigma_s` and `sigma_a` otherwise)".into(),
            ));
        }
        return out;
    };
    if !(v.is_finite() && v > 0.0) {
        out.push((
            "visibility".into(),
            format!("must be a distance > 0 m, got {v}"),
        ));
    }
    for (given, key, instead) in [
        (
            keys.sigma_s,
            "sigma_s",
            "`visibility` gives the extinction: drop `sigma_s`",
        ),
        (
            keys.sigma_a,
            "sigma_a",
            "`visibility` gives the extinction: use `albedo` for absorption",
        ),
        (
            droplets,
            "droplets",
            "give the fog by `visibility` or by `[droplets]` (which has its own `visibility`)",
        ),
    ] {
        if given {
            out.push((key.into(), instead.into()));
        }
    }
    if let Some(a) = keys.albedo
        && !(0.0..=1.0).contains(&a)
    {
        out.push(("albedo".into(), format!("must be in [0, 1], got {a}")));
    }
    out
}

/// Builds the medium for `grid`; files are resolved by `resolve`. Defaults: no phase keys
/// means isotropic HG (g = 0); droplets add their absorption to `sigma_a`.
pub fn build(
    parts: MediumParts<'_>,
    grid: &SpectralGrid,
    resolve: &dyn Fn(&str) -> PathBuf,
) -> Result<BuiltMedium, KeyedError> {
    let n = grid.n;
    if let Some(d) = parts.droplets {
        let o = droplets::optics(d, grid, resolve).map_err(keyed("droplets"))?;
        let ss: Vec<f32> = o.sigma_sca.iter().map(|&v| v as f32).collect();
        let mut sa = *parts.sigma_a;
        for (l, v) in o.sigma_abs.iter().enumerate() {
            sa.0[l] += *v as f32;
        }
        let phase = Phase::Tabulated(super::phase_intern(o.table.clone()));
        let medium = Medium::with_phase(&Spectrum::from_slice(&ss), &sa, phase, n)
            .map_err(keyed("droplets"))?;
        return Ok(BuiltMedium {
            medium,
            droplets: Some(o),
        });
    }
    let (phase, key) = match parts.phase {
        Some(p) => {
            let key = match p {
                PhaseDesc::Tabulated { .. } => "phase.file",
                PhaseDesc::Hg { .. }
                | PhaseDesc::TwoTermHg { .. }
                | PhaseDesc::Rayleigh
                | PhaseDesc::Draine { .. }
                | PhaseDesc::HgDraine { .. } => "phase",
            };
            (p.build(grid, resolve).map_err(keyed(key))?, key)
        }
        None => (Phase::hg(parts.g.unwrap_or(0.0)).map_err(keyed("g"))?, "g"),
    };
    let zero = Spectrum::ZERO;
    let (ss, sa) = match parts.visibility {
        Some(v) => {
            let st = v.sigma_t();
            let ss = Spectrum::splat(st * v.albedo, n);
            (ss, Spectrum::splat(st - ss.0[0], n))
        }
        None => (*parts.sigma_s.unwrap_or(&zero), *parts.sigma_a),
    };
    let medium = Medium::with_phase(&ss, &sa, phase, n).map_err(|e| {
        let key = match e {
            MediumError::Coefficient { what, .. } => what,
            MediumError::PhaseG(_)
            | MediumError::PhaseParameter { .. }
            | MediumError::PhaseTable(_)
            | MediumError::PhaseFile { .. }
            | MediumError::Read { .. }
            | MediumError::Droplets(_)
            | MediumError::BinCount { .. }
            | MediumError::PowerLaw { .. }
            | MediumError::Q(_)
            | MediumError::PhaseLanes { .. } => key,
        };
        keyed(key)(e)
    })?;
    Ok(BuiltMedium {
        medium,
        droplets: None,
    })
}
