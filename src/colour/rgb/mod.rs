//! RGB -> spectrum for textures and RGB-given material values (Jakob and Hanika 2019), with
//! the three treatments pbrt-v4 distinguishes: bounded reflectances, unbounded values such as
//! extinction coefficients, and emission (illuminant-scaled).

mod fit;
mod sigmoid;
mod table;

use std::sync::OnceLock;

pub use fit::FitContext;
pub use sigmoid::SigmoidPolynomial;
pub use table::CoefficientTable;

use crate::spectrum::{Extrapolation, PiecewiseLinear, SpectralGrid, Spectrum, resolve};

/// How an RGB triple (linear sRGB / Rec.709, D65) is turned into a spectrum.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RgbKind {
    /// A reflectance or albedo: components clamped to [0, 1], spectrum bounded to [0, 1].
    Reflectance,
    /// Any non-negative value (e.g. an extinction coefficient): the colour is fitted at half
    /// the largest component and the spectrum scaled back, so it is not bounded by 1.
    Unbounded,
    /// Emitted radiance: an unbounded spectrum times D65 normalised to Y = 1, so that RGB
    /// (1, 1, 1) is a D65 emitter of luminance Y = 1 and renders as RGB (1, 1, 1).
    Illuminant,
}

#[derive(Debug, thiserror::Error)]
#[error("RGB -> spectrum tables unavailable: built-in colour data failed to load")]
pub struct RgbTableError;

fn d65_unit() -> Option<&'static PiecewiseLinear> {
    static D65: OnceLock<Option<PiecewiseLinear>> = OnceLock::new();
    D65.get_or_init(|| {
        let d = resolve("D65", None, false).ok()?;
        let cmfs = super::Observer::Cie1931.cmfs().ok()?;
        // Y of D65 with the film's normalisation: integral(D65 ybar) / integral(ybar).
        let (a, b) = cmfs.y.range();
        let n = ((b - a) as usize).max(1);
        let h = (b - a) / n as f64;
        let y: f64 = (0..n)
            .map(|k| {
                let l = a + (k as f64 + 0.5) * h;
                d.eval(l, Extrapolation::Clamp) * cmfs.y.eval(l, Extrapolation::Zero) * h
            })
            .sum::<f64>()
            / cmfs.y_integral;
        let values = d.values.iter().map(|v| v / y).collect();
        Some(PiecewiseLinear::new(d.wavelengths.clone(), values))
    })
    .as_ref()
}

/// Scale and coefficients of an RGB value (the spectrum is `scale * sigmoid polynomial`).
pub fn rgb_coefficients(
    rgb: [f32; 3],
    kind: RgbKind,
) -> Result<(f64, SigmoidPolynomial), RgbTableError> {
    let table = CoefficientTable::srgb().ok_or(RgbTableError)?;
    let rgb = rgb.map(|v| (v as f64).max(0.0));
    Ok(match kind {
        RgbKind::Reflectance => (1.0, table.lookup(rgb)),
        RgbKind::Unbounded | RgbKind::Illuminant => {
            let m = rgb[0].max(rgb[1]).max(rgb[2]);
            if m == 0.0 {
                (0.0, SigmoidPolynomial::constant(0.0))
            } else {
                let scale = 2.0 * m;
                (scale, table.lookup(rgb.map(|v| v / scale)))
            }
        }
    })
}

/// The bin averages of the spectrum for `rgb` (linear sRGB) on `grid`. The first call fits
/// the coefficient table (about a second); later calls only interpolate it.
pub fn rgb_to_spectrum(
    rgb: [f32; 3],
    kind: RgbKind,
    grid: &SpectralGrid,
) -> Result<Spectrum, RgbTableError> {
    let (scale, sp) = rgb_coefficients(rgb, kind)?;
    let s = sp.bin_averages(grid) * scale as f32;
    Ok(match kind {
        RgbKind::Illuminant => {
            // Bin average of the product taken as the product of bin averages: both vary
            // slowly across a bin except D65's fine structure, which the bins average anyway.
            s * d65_unit()
                .ok_or(RgbTableError)?
                .bin_averages(grid, Extrapolation::Clamp)
        }
        _ => s,
    })
}
