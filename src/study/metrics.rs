//! Error metrics of an image against a reference, over every pixel and spectral bin.

use crate::film::SpectralImage;

/// Mean squared error over all values.
pub fn mse(x: &[f32], reference: &[f32]) -> f64 {
    if x.is_empty() {
        return 0.0;
    }
    let s: f64 = x
        .iter()
        .zip(reference)
        .map(|(&a, &r)| (a as f64 - r as f64).powi(2))
        .sum();
    s / x.len() as f64
}

/// Mean signed difference (x - reference).
pub fn mean_error(x: &[f32], reference: &[f32]) -> f64 {
    if x.is_empty() {
        return 0.0;
    }
    let s: f64 = x
        .iter()
        .zip(reference)
        .map(|(&a, &r)| a as f64 - r as f64)
        .sum();
    s / x.len() as f64
}

pub fn rmse(x: &[f32], reference: &[f32]) -> f64 {
    mse(x, reference).sqrt()
}

/// Relative MSE: mean of (x - r)^2 / (r^2 + eps^2), with eps = 1 % of the reference's mean
/// absolute value, so dark values neither blow up the mean nor depend on the radiance unit.
pub fn rel_mse(x: &[f32], reference: &[f32]) -> f64 {
    if x.is_empty() {
        return 0.0;
    }
    let mean_abs =
        reference.iter().map(|&r| (r as f64).abs()).sum::<f64>() / reference.len() as f64;
    let eps2 = (0.01 * mean_abs).powi(2).max(f64::MIN_POSITIVE);
    let s: f64 = x
        .iter()
        .zip(reference)
        .map(|(&a, &r)| {
            let (a, r) = (a as f64, r as f64);
            (a - r).powi(2) / (r * r + eps2)
        })
        .sum();
    s / x.len() as f64
}

/// Monte-Carlo efficiency: the inverse of error times cost. Constant in time for an unbiased
/// estimator whose variance falls as 1/time, so variants compare at any budget.
pub fn efficiency(mse: f64, seconds: f64) -> f64 {
    if mse > 0.0 && seconds > 0.0 {
        1.0 / (mse * seconds)
    } else {
        f64::INFINITY
    }
}

/// Mean of the image's per-pixel, per-bin standard error (0 when unknown).
pub fn mean_noise(img: &SpectralImage) -> f64 {
    match &img.noise {
        Some(n) if !n.is_empty() => n.iter().map(|&v| v as f64).sum::<f64>() / n.len() as f64,
        _ => 0.0,
    }
}

/// Errors of one layer: MSE, RMSE, relative MSE.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize)]
pub struct LayerErrors {
    pub mse: f64,
    pub rmse: f64,
    pub rel_mse: f64,
}

pub fn layer_errors(x: &[f32], reference: &[f32]) -> LayerErrors {
    let m = mse(x, reference);
    LayerErrors {
        mse: m,
        rmse: m.sqrt(),
        rel_mse: rel_mse(x, reference),
    }
}
