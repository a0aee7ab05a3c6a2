//! Spectra given by formula, reduced to exact bin averages.

use super::{Bin, MAX_BINS, SpectralGrid, Spectrum};

/// The same value in every active bin.
pub fn constant(value: f32, grid: &SpectralGrid) -> Spectrum {
    Spectrum::splat(value, grid.n)
}

/// Bin averages of `k * (lambda / lambda_ref)^(-p)` (e.g. scattering that falls off with
/// wavelength: p = 4 for Rayleigh, p around 1 for haze), integrated in closed form; a line
/// bin holds the law's value at its line.
pub fn power_law(k: f64, lambda_ref: f64, p: f64, grid: &SpectralGrid) -> Spectrum {
    let mut s = Spectrum::ZERO;
    for i in 0..grid.n.min(MAX_BINS) {
        let (a, b) = match grid.bin(i) {
            Bin::Band { lo, hi } => (lo, hi),
            Bin::Line { lambda, .. } => {
                s.0[i] = (k * (lambda / lambda_ref).powf(-p)) as f32;
                continue;
            }
        };
        // Antiderivative of (l / lr)^-p is lr^p * l^(1-p) / (1-p), or lr * ln(l) when p = 1.
        let integral = if (p - 1.0).abs() < 1e-12 {
            lambda_ref * (b / a).ln()
        } else {
            lambda_ref.powf(p) * (b.powf(1.0 - p) - a.powf(1.0 - p)) / (1.0 - p)
        };
        s.0[i] = (k * integral / (b - a)) as f32;
    }
    s
}

/// Spectral lines `(nm, power)` as bin values: each line's power spread over its narrow bin
/// (a density per nm, so value times width is the power). `Err` gives a line the grid has no
/// bin for (a grid made without it).
pub fn lines(lines: &[(f64, f64)], grid: &SpectralGrid) -> Result<Spectrum, f64> {
    let mut s = Spectrum::ZERO;
    for &(lambda, power) in lines {
        let bin = grid.line_bin(lambda).ok_or(lambda)?;
        s.0[bin] += (power / grid.bin_width(bin)) as f32;
    }
    Ok(s)
}
