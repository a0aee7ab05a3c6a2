//! Fog and cloud from physical parameters: a droplet size distribution, a number
//! concentration and the refractive index of water give, by Lorenz–Mie theory at load time,
//! the per-bin extinction, albedo and phase function (scene table `[media.NAME.droplets]`).

mod mie;
mod size;
mod water;

use std::path::{Path, PathBuf};
use std::sync::Mutex;

use rayon::prelude::*;
use serde::{Deserialize, Serialize};

pub use mie::{DEFAULT_STEP, EnsembleOptics, ensemble, terms};
pub use size::SizeDistribution;
pub use water::RefractiveIndex;

use super::phase::PhaseTable;
use crate::medium::MediumError;
use crate::spectrum::SpectralGrid;

/// Contrast threshold of the meteorological optical range (WMO): visibility `V = -ln(0.05) /
/// sigma_ext` at 550 nm.
pub const MOR_CONTRAST: f64 = 0.05;
/// Wavelength at which a target visibility is met (nm).
pub const VISIBILITY_NM: f64 = 550.0;
/// Density of liquid water (g/m³), for liquid water content.
const WATER_DENSITY: f64 = 1.0e6;
/// At most this many evenly spaced wavelengths are solved (plus the grid's lines); bins between
/// them are interpolated linearly (distribution-averaged optics are smooth in wavelength: the
/// ripple is averaged out).
pub const MAX_SAMPLES: usize = 8;
/// Most Lorenz-Mie terms (see [`terms`]) a fog may need over all its wavelengths: solving has
/// no progress display and cannot be interrupted, so a fog that would take minutes is refused
/// before it starts. Measured on droplet-fog's 32 bins (8 wavelengths, release build, the
/// project's shared 2-core machine): 5 µm droplets 2.9e7 terms in 7.8 CPU s, 10 µm 1.1e8 in
/// 30 CPU s, ~2.7e-7 CPU s a term; so the limit is ~2.3 CPU minutes, reached at width 1.5 and
/// the default step by an effective radius of about 21 µm (the cost grows as its square).
pub const MAX_TERMS: f64 = 5e8;
/// Smallest effective radius, µm: 10 nm droplets (the smallest haze nuclei) are already far in
/// the Rayleigh regime, and smaller clusters have no bulk refractive index.
pub const MIN_RADIUS: f64 = 0.01;

/// The size distribution's shape (`distribution` key).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum DistributionKind {
    /// Lognormal with geometric standard deviation `width`.
    Lognormal,
    /// Deirmendjian's modified gamma with shape `alpha`, `gamma`.
    ModifiedGamma,
}

/// `[media.NAME.droplets]`: see docs/scene-format.md.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DropletsDesc {
    pub distribution: DistributionKind,
    /// Effective radius `<r³>/<r²>`, µm.
    pub effective_radius: f64,
    /// Lognormal geometric standard deviation σ_g (> 1).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub width: Option<f64>,
    /// Modified gamma α (>= 0) and γ (> 0).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub alpha: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub gamma: Option<f64>,
    /// Droplets per cm³.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub number_density: Option<f64>,
    /// Liquid water content, g/m³.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub liquid_water_content: Option<f64>,
    /// Target visibility (meteorological optical range at 550 nm), m.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub visibility: Option<f64>,
    /// `"water"` (built-in) or a CSV file with columns `wavelength_nm`, `n`, `k`.
    #[serde(default = "water")]
    pub refractive_index: String,
    /// Size-quadrature node spacing in size parameter.
    #[serde(default = "step")]
    pub quadrature_step: f64,
}

fn water() -> String {
    "water".into()
}

fn step() -> f64 {
    DEFAULT_STEP
}

/// Default lognormal width and modified gamma shape.
pub const DEFAULT_WIDTH: f64 = 1.5;
pub const DEFAULT_ALPHA: f64 = 6.0;
pub const DEFAULT_GAMMA: f64 = 1.0;

impl DropletsDesc {
    /// Each numeric key outside its range: (key, message).
    fn range_problems(&self) -> Vec<(String, String)> {
        type Rule = (&'static str, fn(f64) -> bool, &'static str);
        let rules: [(Option<f64>, Rule); 8] = [
            (
                Some(self.effective_radius),
                (
                    "effective_radius",
                    |v| (MIN_RADIUS..=1e3).contains(&v),
                    "in [0.01, 1000] µm",
                ),
            ),
            (self.width, ("width", |v| v > 1.0 && v <= 5.0, "in (1, 5]")),
            (
                self.alpha,
                ("alpha", |v| (0.0..=100.0).contains(&v), "in [0, 100]"),
            ),
            (
                self.gamma,
                ("gamma", |v| v > 0.0 && v <= 10.0, "in (0, 10]"),
            ),
            (
                self.number_density,
                ("number_density", |v| v > 0.0, "> 0 per cm³"),
            ),
            (
                self.liquid_water_content,
                (
                    "liquid_water_content",
                    |v| v > 0.0 && v < WATER_DENSITY,
                    "in (0, 1e6) g/m³ (below the density of liquid water)",
                ),
            ),
            (self.visibility, ("visibility", |v| v > 0.0, "> 0 m")),
            (
                Some(self.quadrature_step),
                ("quadrature_step", |v| v > 0.0 && v <= 1.0, "in (0, 1]"),
            ),
        ];
        rules
            .iter()
            .filter_map(|&(v, (key, ok, what))| {
                let v = v?;
                (!(v.is_finite() && ok(v)))
                    .then(|| (key.to_string(), format!("must be {what}, got {v}")))
            })
            .collect()
    }

    /// Range checks: (key below `droplets`, message) per problem. `exists` tells whether a
    /// file named in the scene exists.
    pub fn check(&self, exists: &dyn Fn(&str) -> bool) -> Vec<(String, String)> {
        let mut out = self.range_problems();
        let amounts = [
            self.number_density,
            self.liquid_water_content,
            self.visibility,
        ];
        if amounts.iter().flatten().count() != 1 {
            out.push((
                String::new(),
                "give exactly one of number_density, liquid_water_content, visibility".into(),
            ));
        }
        let kind = self.distribution;
        for (key, given, belongs) in [
            (
                "width",
                self.width.is_some(),
                kind == DistributionKind::Lognormal,
            ),
            (
                "alpha",
                self.alpha.is_some(),
                kind == DistributionKind::ModifiedGamma,
            ),
            (
                "gamma",
                self.gamma.is_some(),
                kind == DistributionKind::ModifiedGamma,
            ),
        ] {
            if given && !belongs {
                out.push((
                    key.into(),
                    format!("does not apply to a {kind:?} distribution").to_lowercase(),
                ));
            }
        }
        if self.refractive_index != "water" && !exists(&self.refractive_index) {
            out.push((
                "refractive_index".into(),
                format!(
                    "`{}` is neither `water` nor a CSV file",
                    self.refractive_index
                ),
            ));
        }
        out
    }

    /// The size distribution.
    pub fn size(&self) -> SizeDistribution {
        let r = self.effective_radius;
        match self.distribution {
            DistributionKind::Lognormal => {
                SizeDistribution::lognormal(r, self.width.unwrap_or(DEFAULT_WIDTH))
            }
            DistributionKind::ModifiedGamma => SizeDistribution::modified_gamma(
                r,
                self.alpha.unwrap_or(DEFAULT_ALPHA),
                self.gamma.unwrap_or(DEFAULT_GAMMA),
            ),
        }
    }
}

/// The droplets' optics on a spectral grid.
#[derive(Clone, Debug)]
pub struct DropletOptics {
    /// Per bin (1/m): extinction, scattering, absorption; and the asymmetry parameter.
    pub sigma_ext: Vec<f64>,
    pub sigma_sca: Vec<f64>,
    pub sigma_abs: Vec<f64>,
    pub g: Vec<f64>,
    /// Per-bin phase table (cosines from [`phase_angles`]).
    pub table: PhaseTable,
    /// Droplets per cm³, liquid water content (g/m³), effective radius (µm).
    pub number_density: f64,
    pub liquid_water_content: f64,
    pub effective_radius: f64,
    /// Wavelengths solved (nm) and Lorenz–Mie solutions per wavelength (the largest).
    pub samples: Vec<f64>,
    pub nodes: usize,
    pub refractive_index: String,
}

/// Scattering angles (degrees) of the droplet phase tables: 0, then geometric steps (x1.03)
/// from 0.01° to 10° for the diffraction peak (width ~λ/2r: 0.3-5° for fog and haze), 1°
/// steps to 170°, and 0.5° steps over the glory to 180°. Holds 30, 90, 140 exactly. The table
/// is linear in cos θ between nodes; at this spacing its normalisation differs from the
/// Lorenz-Mie one by < 1e-3 (tests/medium_droplets.rs).
pub fn phase_angles() -> Vec<f64> {
    let mut a = vec![0.0];
    let mut t = 0.01;
    while t < 10.0 {
        a.push(t);
        t *= 1.03;
    }
    a.extend((10..170).map(f64::from));
    a.extend((0..=20).map(|i| 170.0 + 0.5 * i as f64));
    a
}

/// A solved fog: its description, grid and index file.
type Solved = (DropletsDesc, SpectralGrid, PathBuf, DropletOptics);

/// Recent solutions, so that a scene built twice in one process (`brume info` describes the
/// media, then builds the scene; a study loads its scene once per variant) solves its fog
/// once. A handful is kept; each holds a few hundred kB of phase tables.
static SOLVED: Mutex<Vec<Solved>> = Mutex::new(Vec::new());
const KEEP: usize = 8;

/// Solves the droplets for `grid` (index files resolved by `resolve`), or returns the solution
/// of an identical earlier call.
pub fn optics(
    desc: &DropletsDesc,
    grid: &SpectralGrid,
    resolve: &dyn Fn(&str) -> PathBuf,
) -> Result<DropletOptics, MediumError> {
    let file = resolve(&desc.refractive_index);
    {
        let solved = SOLVED.lock().unwrap_or_else(|e| e.into_inner());
        if let Some(s) = solved
            .iter()
            .find(|s| s.0 == *desc && s.1 == *grid && s.2 == file)
        {
            return Ok(s.3.clone());
        }
    }
    let o = solve(desc, grid, &file)?;
    let mut solved = SOLVED.lock().unwrap_or_else(|e| e.into_inner());
    if solved.len() >= KEEP {
        solved.remove(0);
    }
    solved.push((desc.clone(), grid.clone(), file, o.clone()));
    Ok(o)
}

fn solve(
    desc: &DropletsDesc,
    grid: &SpectralGrid,
    file: &Path,
) -> Result<DropletOptics, MediumError> {
    let index = RefractiveIndex::load(&desc.refractive_index, file)?;
    let dist = desc.size();
    let angles = phase_angles();
    // Table nodes run from mu = -1 (180°) to 1 (0°).
    let mut mu: Vec<f64> = angles.iter().rev().map(|a| a.to_radians().cos()).collect();
    let last = mu.len() - 1;
    (mu[0], mu[last]) = (-1.0, 1.0);
    let samples = sample_wavelengths(grid);
    check_cost(desc, &dist, &samples)?;
    let solved = samples
        .par_iter()
        .map(|&l| ensemble(&dist, l / 1000.0, index.at(l), &mu, desc.quadrature_step))
        .collect::<Result<Vec<_>, _>>()?;
    let number_density = concentration(desc, &dist, &index, &samples, &solved)?;
    let liquid_water_content = WATER_DENSITY * number_density * 1e6 * dist.mean_volume() * 1e-18;
    if !(liquid_water_content.is_finite() && liquid_water_content < WATER_DENSITY) {
        return Err(MediumError::Droplets(format!(
            "{number_density:e} droplets per cm³ would hold {liquid_water_content:e} g of water \
             per m³, more than liquid water itself (1e6 g/m³): lower number_density or raise \
             visibility"
        )));
    }
    // Cross sections in µm² times droplets per cm³: 1e-12 m² x 1e6 m^-3 = 1e-6 1/m.
    let scale = number_density * 1e-6;
    let mut o = DropletOptics {
        sigma_ext: Vec::new(),
        sigma_sca: Vec::new(),
        sigma_abs: Vec::new(),
        g: Vec::new(),
        table: PhaseTable::new(vec![-1.0, 1.0], &[vec![1.0, 1.0]], String::new())?,
        number_density,
        liquid_water_content,
        effective_radius: dist.effective_radius(),
        nodes: solved.iter().map(|s| s.nodes).max().unwrap_or(0),
        samples: samples.clone(),
        refractive_index: index.source.clone(),
    };
    let mut lanes = Vec::new();
    for b in 0..grid.n {
        let (i, t) = interpolation(&samples, grid.centre(b));
        let (a, z) = (&solved[i], &solved[(i + 1).min(solved.len() - 1)]);
        let mix = |f: fn(&EnsembleOptics) -> f64| (1.0 - t) * f(a) + t * f(z);
        o.sigma_ext.push(scale * mix(|s| s.c_ext));
        o.sigma_sca.push(scale * mix(|s| s.c_sca));
        o.sigma_abs.push(scale * mix(|s| s.c_abs));
        // The bin's g and phase are scattering-weighted, like the ensemble's own averages.
        let (wa, wz) = ((1.0 - t) * a.c_sca, t * z.c_sca);
        o.g.push((wa * a.g + wz * z.g) / (wa + wz));
        lanes.push(
            a.phase
                .iter()
                .zip(&z.phase)
                .map(|(p, q)| (wa * p + wz * q) / (wa + wz))
                .collect::<Vec<f64>>(),
        );
    }
    let source = format!("Lorenz-Mie droplets, r_eff {} µm", desc.effective_radius);
    o.table = PhaseTable::new(mu, &lanes, source)?;
    Ok(o)
}

/// Refuses a fog whose solution would need more than [`MAX_TERMS`] Lorenz-Mie terms.
fn check_cost(
    desc: &DropletsDesc,
    dist: &SizeDistribution,
    samples: &[f64],
) -> Result<(), MediumError> {
    let step = desc.quadrature_step;
    let need: f64 = samples.iter().map(|l| terms(dist, l / 1000.0, step)).sum();
    if need <= MAX_TERMS {
        return Ok(());
    }
    let larger = step * need / MAX_TERMS;
    let or_step = if larger <= 1.0 {
        format!(", or a quadrature_step of at least {larger:.3} (the time falls as its inverse)")
    } else {
        String::new()
    };
    Err(MediumError::Droplets(format!(
        "effective_radius {} µm would need ~{need:.1e} Lorenz-Mie terms at {} wavelengths, over \
         the {MAX_TERMS:.0e} solved at load time (~2 CPU minutes; the time grows as the square \
         of the radius): use smaller droplets, a narrower distribution, fewer bins{or_step}",
        desc.effective_radius,
        samples.len(),
    )))
}

/// The wavelengths to solve: every bin centre (a line bin's is its line) if there are at most
/// `MAX_SAMPLES` bins, else `MAX_SAMPLES` wavelengths evenly from the first to the last bin
/// centre plus every line, so that a line's bin holds the droplets' optics at the line itself.
fn sample_wavelengths(grid: &SpectralGrid) -> Vec<f64> {
    if grid.n <= MAX_SAMPLES {
        return grid.centres();
    }
    let (a, z) = (grid.centre(0), grid.centre(grid.n - 1));
    let mut s: Vec<f64> = (0..MAX_SAMPLES)
        .map(|i| a + (z - a) * i as f64 / (MAX_SAMPLES - 1) as f64)
        .chain(grid.lines().iter().copied())
        .collect();
    s.sort_by(f64::total_cmp);
    s.dedup();
    s
}

/// The sample interval holding `lambda` and the position in it.
fn interpolation(samples: &[f64], lambda: f64) -> (usize, f64) {
    if samples.len() < 2 {
        return (0, 0.0);
    }
    let k = samples
        .partition_point(|&s| s <= lambda)
        .clamp(1, samples.len() - 1);
    let t = (lambda - samples[k - 1]) / (samples[k] - samples[k - 1]);
    (k - 1, t.clamp(0.0, 1.0))
}

/// Droplets per cm³ from whichever amount the description gives.
/// A target visibility uses the extinction at 550 nm interpolated from the solved wavelengths
/// when they span it (as the bins there are), else a solution at 550 nm.
fn concentration(
    desc: &DropletsDesc,
    dist: &SizeDistribution,
    index: &RefractiveIndex,
    samples: &[f64],
    solved: &[EnsembleOptics],
) -> Result<f64, MediumError> {
    if let Some(n) = desc.number_density {
        return Ok(n);
    }
    if let Some(lwc) = desc.liquid_water_content {
        // lwc = rho N <V>, N per m³ = 1e6 per cm³, <V> in µm³ = 1e-18 m³.
        return Ok(lwc / (WATER_DENSITY * dist.mean_volume() * 1e-18) / 1e6);
    }
    let v = desc.visibility.ok_or_else(|| {
        MediumError::Droplets("give one of number_density, liquid_water_content, visibility".into())
    })?;
    let at = VISIBILITY_NM;
    let spanned = samples.len() > 1 && samples[0] <= at && at <= samples[samples.len() - 1];
    let c_ext = if spanned {
        let (i, t) = interpolation(samples, at);
        (1.0 - t) * solved[i].c_ext + t * solved[i + 1].c_ext
    } else {
        let mu = [1.0];
        ensemble(dist, at / 1000.0, index.at(at), &mu, desc.quadrature_step)?.c_ext
    };
    let sigma = -MOR_CONTRAST.ln() / v;
    Ok(sigma / (c_ext * 1e-6))
}

/// Meteorological optical range (m) for an extinction (1/m).
pub fn visibility(sigma_ext: f64) -> f64 {
    -MOR_CONTRAST.ln() / sigma_ext
}

/// Whether `path` names a file (for `DropletsDesc::check`).
pub fn file_exists(path: &Path) -> bool {
    path.is_file()
}
