//! From a scene's medium description (spectra already resolved) to the runtime medium, with
//! the checks that need no file (for the scene validator) and the defaults.

use std::path::PathBuf;

use super::droplets::{self, DropletOptics, DropletsDesc};
use super::{HomogeneousMedium, MediumError, Phase, PhaseDesc};
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
}

/// A built medium and, for droplet fog, the Lorenz–Mie results it came from.
#[derive(Clone, Debug)]
pub struct BuiltMedium {
    pub medium: HomogeneousMedium,
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
    has_sigma_s: bool,
    g: Option<f32>,
    phase: Option<&PhaseDesc>,
    droplets: Option<&DropletsDesc>,
    exists: &dyn Fn(&str) -> bool,
) -> Vec<(String, String)> {
    let mut out = Vec::new();
    match (has_sigma_s, droplets.is_some()) {
        (false, false) => out.push((String::new(), "needs `sigma_s` or `[droplets]`".into())),
        (true, true) => out.push((
            "sigma_s".into(),
            "droplets give the scattering coefficient: drop `sigma_s`".into(),
        )),
        (true, false) | (false, true) => {}
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
        let medium = HomogeneousMedium::with_phase(&Spectrum::from_slice(&ss), &sa, phase, n)
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
                _ => "phase",
            };
            (p.build(grid, resolve).map_err(keyed(key))?, key)
        }
        None => (Phase::hg(parts.g.unwrap_or(0.0)).map_err(keyed("g"))?, "g"),
    };
    let zero = Spectrum::ZERO;
    let ss = parts.sigma_s.unwrap_or(&zero);
    let medium = HomogeneousMedium::with_phase(ss, parts.sigma_a, phase, n).map_err(|e| {
        let key = match e {
            MediumError::Coefficient { what, .. } => what,
            _ => key,
        };
        keyed(key)(e)
    })?;
    Ok(BuiltMedium {
        medium,
        droplets: None,
    })
}
