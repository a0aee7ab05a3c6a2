//! Sensors: photometric measurements a film accumulates beside its image, with the same exact
//! integer sums as its pixels, so that a sensor's value survives checkpoints, pass ranges and
//! merges bit for bit.
//!
//! Each pass gives each sensor a spectral value (per bin): the film computes a luminance
//! sensor's from the pass's pixels (the mean radiance over its region), the integrator splats
//! an illuminance sensor's (spectral irradiance, W/(m² nm) per bin) into the pass buffer. The
//! film keeps per sensor the fixed-point sum of those values per bin and the sum of squares of
//! their photometric value (cd/m² or lx: K_m = 683 lm/W times the V(λ)-weighted sum), so the
//! standard error is that of the photometric value itself, across passes (not a per-bin
//! approximation).

use serde::{Deserialize, Serialize};
use statrs::distribution::{ContinuousCDF, StudentsT};

use crate::colour::photometry;
use crate::spectrum::SpectralGrid;

/// A sensor as the film (and the integrator) sees it.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Sensor {
    pub name: String,
    #[serde(flatten)]
    pub kind: SensorKind,
}

#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "type", rename_all = "lowercase")]
pub enum SensorKind {
    /// Mean luminance over the pixels `x0 <= x < x1`, `y0 <= y < y1` (`region = [x0, y0, x1,
    /// y1]`): the film computes it from each pass's pixels.
    Luminance { region: [u32; 4] },
    /// Illuminance at `position` on a surface facing `normal` (unit): the integrator splats
    /// the spectral irradiance there (W/(m² nm) per bin) with `PassBuffer::splat_sensor`.
    Illuminance {
        position: [f32; 3],
        normal: [f32; 3],
    },
}

impl SensorKind {
    /// The kind's name as a scene file spells it.
    pub fn name(&self) -> &'static str {
        match self {
            SensorKind::Luminance { .. } => "luminance",
            SensorKind::Illuminance { .. } => "illuminance",
        }
    }

    /// Unit of the photometric value.
    pub fn unit(&self) -> &'static str {
        match self {
            SensorKind::Luminance { .. } => "cd/m2",
            SensorKind::Illuminance { .. } => "lx",
        }
    }

    /// Unit of the spectral values (per nm).
    pub fn spectral_unit(&self) -> &'static str {
        match self {
            SensorKind::Luminance { .. } => "W/(m2 sr nm)",
            SensorKind::Illuminance { .. } => "W/(m2 nm)",
        }
    }
}

/// What a film accumulates beside its image: sensors, and one layer per light when its names
/// are given (empty: no light layers).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct FilmExtras {
    pub sensors: Vec<Sensor>,
    /// Names of the light layers (`light0.spot`, ...), in the order of the scene's lights.
    pub light_layers: Vec<String>,
}

/// One sensor's estimate over the film's passes.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SensorReading {
    pub name: String,
    #[serde(flatten)]
    pub kind: SensorKind,
    pub unit: &'static str,
    pub passes: u64,
    /// Mean photometric value (cd/m² or lx).
    pub value: f64,
    /// Standard error of the mean, from the spread of the per-pass values (None below 2 passes).
    pub std_error: Option<f64>,
    /// 95 % confidence interval of the mean (see [`interval`]): never below zero.
    pub ci95: Option<[f64; 2]>,
    /// Whether the interval can be trusted: false below [`RELIABLE_PASSES`] passes.
    pub ci95_reliable: bool,
    /// Mean spectral value per bin (`spectral_unit`), bin centres in `wavelengths` (nm).
    pub spectral_unit: &'static str,
    pub wavelengths: Vec<f64>,
    pub spectrum: Vec<f64>,
}

/// Per-pass photometric weights of the film's bins (see [`photometry::luminous_weights`]);
/// the embedded observer table always parses, so the fallback (zeros) is never taken.
pub(super) fn weights(grid: &SpectralGrid) -> Vec<f64> {
    photometry::luminous_weights(grid).unwrap_or_else(|_| vec![0.0; grid.n])
}

/// The mean over a luminance sensor's region of a pass's total (medium + surface) values, per
/// bin, summed in pixel order (deterministic).
pub(super) fn region_mean(
    region: [u32; 4],
    width: usize,
    n: usize,
    medium: &[f32],
    surface: &[f32],
    out: &mut [f64],
) {
    out.iter_mut().for_each(|v| *v = 0.0);
    let [x0, y0, x1, y1] = region.map(|v| v as usize);
    let count = ((x1.saturating_sub(x0)) * (y1.saturating_sub(y0))).max(1) as f64;
    for y in y0..y1 {
        for x in x0..x1 {
            let i = (y * width + x) * n;
            if i + n > medium.len() {
                continue;
            }
            for b in 0..n {
                out[b] += medium[i + b] as f64 + surface[i + b] as f64;
            }
        }
    }
    out.iter_mut().for_each(|v| *v /= count);
}

/// Passes below which a sensor's interval is unreliable. Gathered light makes per-pass values
/// skewed (a few forward rays carry much of a pass; docs/study.md, "Strong forward
/// scattering"), so the spread of a few passes underestimates the error and Student's t, exact
/// only for normal values, cannot repair that.
pub const RELIABLE_PASSES: u64 = 10;

/// The 95 % interval of a non-negative mean `value` with standard error `se` over `passes`
/// passes: Student's t with passes - 1 degrees of freedom, `value ± t se`; when that reaches
/// below zero (few passes, or a heavy tail: a 2-pass illuminance printed [-0.45, 19.9] lx),
/// the same interval taken on the logarithm (delta method: `value x exp(± t se / value)`),
/// which respects the sign and is wide on the high side, where a skewed mean's error lies.
pub fn interval(value: f64, se: f64, passes: u64) -> [f64; 2] {
    let t = StudentsT::new(0.0, 1.0, passes.saturating_sub(1).max(1) as f64)
        .map(|d| d.inverse_cdf(0.975))
        .unwrap_or(1.959_964);
    let (lo, hi) = (value - t * se, value + t * se);
    if lo >= 0.0 || value <= 0.0 {
        return [lo.max(0.0), hi];
    }
    let h = t * se / value;
    [value * (-h).exp(), value * h.exp()]
}

/// The reading of a sensor from its sums (fixed point at `sum_scale` and `sq_scale`).
pub(super) fn reading(
    sensor: &Sensor,
    grid: &SpectralGrid,
    passes: u64,
    sums: &[i128],
    sq: i128,
    (sum_scale, sq_scale): (f64, f64),
) -> SensorReading {
    let p = passes.max(1) as f64;
    let spectrum: Vec<f64> = sums.iter().map(|s| *s as f64 / sum_scale / p).collect();
    let value: f64 = spectrum.iter().zip(weights(grid)).map(|(v, w)| v * w).sum();
    let (std_error, ci95) = if passes > 1 {
        let mean_sq = sq as f64 / sq_scale / p;
        let var = ((mean_sq - value * value) * p / (p - 1.0)).max(0.0);
        let se = (var / p).sqrt();
        (Some(se), Some(interval(value, se, passes)))
    } else {
        (None, None)
    };
    SensorReading {
        name: sensor.name.clone(),
        kind: sensor.kind,
        unit: sensor.kind.unit(),
        passes,
        value,
        std_error,
        ci95,
        ci95_reliable: passes >= RELIABLE_PASSES,
        spectral_unit: sensor.kind.spectral_unit(),
        wavelengths: grid.centres(),
        spectrum,
    }
}
