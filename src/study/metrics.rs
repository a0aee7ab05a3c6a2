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

/// A reference fitted to an image by one scale factor: `k` minimises the squared difference
/// between the image and k x reference (k = sum x r / sum r^2), and `mse`/`rmse` are the error
/// that remains with k applied. For references whose units or exposure differ from brume's
/// (another renderer's image); the unscaled error is always reported beside it.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct ScaleFit {
    pub k: f64,
    pub mse: f64,
    pub rmse: f64,
}

/// The least-squares scale of `reference` to `x`; None when the reference is zero everywhere.
pub fn fit_scale(x: &[f32], reference: &[f32]) -> Option<ScaleFit> {
    let (xr, rr) = x
        .iter()
        .zip(reference)
        .fold((0.0f64, 0.0f64), |(xr, rr), (&a, &r)| {
            let (a, r) = (a as f64, r as f64);
            (xr + a * r, rr + r * r)
        });
    if rr.is_nan() || rr <= 0.0 || x.is_empty() {
        return None;
    }
    let k = xr / rr;
    let s: f64 = x
        .iter()
        .zip(reference)
        .map(|(&a, &r)| (a as f64 - k * r as f64).powi(2))
        .sum();
    let mse = s / x.len() as f64;
    Some(ScaleFit {
        k,
        mse,
        rmse: mse.sqrt(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn scale_fit_recovers_a_known_scale() {
        let r: Vec<f32> = (0..64).map(|i| 0.1 + (i % 7) as f32 * 0.3).collect();
        // Exactly proportional: k found, nothing left.
        let x: Vec<f32> = r.iter().map(|v| v * 2.5).collect();
        let f = fit_scale(&x, &r).expect("fit");
        assert!((f.k - 2.5).abs() < 1e-6, "{f:?}");
        assert!(f.mse < 1e-10);
        // A reference 3 times too dark: k = 3 brings it onto the image.
        let dark: Vec<f32> = x.iter().map(|v| v / 3.0).collect();
        assert!((fit_scale(&x, &dark).expect("fit").k - 3.0).abs() < 1e-6);
        // Noise orthogonal to the reference leaves k exact; the remaining error is the noise's.
        let e: Vec<f32> = (0..64)
            .map(|i| if i % 2 == 0 { 0.05 } else { -0.05 })
            .collect();
        let r2 = vec![1.0f32; 64];
        let x2: Vec<f32> = r2.iter().zip(&e).map(|(r, e)| 0.7 * r + e).collect();
        let f2 = fit_scale(&x2, &r2).expect("fit");
        assert!((f2.k - 0.7).abs() < 1e-6, "{f2:?}");
        assert!((f2.mse - 0.0025).abs() < 1e-7, "{f2:?}");
        assert!((f2.rmse - 0.05).abs() < 1e-6);
        // The fit never does worse than no scale (k = 1).
        assert!(f2.mse <= mse(&x2, &r2));
        // A black reference has no scale.
        assert!(fit_scale(&x, &vec![0.0; 64]).is_none());
        assert!(fit_scale(&[], &[]).is_none());
    }
}
