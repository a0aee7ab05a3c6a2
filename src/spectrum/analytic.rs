//! Spectra given by formula, reduced to exact bin averages.

use super::{MAX_BINS, SpectralGrid, Spectrum};

/// The same value in every active bin.
pub fn constant(value: f32, grid: &SpectralGrid) -> Spectrum {
    Spectrum::splat(value, grid.n)
}

/// Bin averages of `k * (lambda / lambda_ref)^(-p)` (e.g. scattering that falls off with
/// wavelength: p = 4 for Rayleigh, p around 1 for haze), integrated in closed form.
pub fn power_law(k: f64, lambda_ref: f64, p: f64, grid: &SpectralGrid) -> Spectrum {
    let mut s = Spectrum::ZERO;
    for i in 0..grid.n.min(MAX_BINS) {
        let (a, b) = grid.edges(i);
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
