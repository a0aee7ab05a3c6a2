use super::MediumError;
use crate::spectrum::{Bin, SpectralGrid, Spectrum};

/// Per-bin coefficients of the power law `sigma(lambda) = k (lambda / lambda0)^(-p)` (1/m), each
/// band holding the exact average of the law over it and each line bin its value at the line
/// (the grid's bin convention). `p = 4` is
/// Rayleigh-like, `p ~ 0..1.5` hazes and fogs, `p = 0` grey.
pub fn power_law(
    grid: &SpectralGrid,
    k: f32,
    lambda0_nm: f32,
    p: f32,
) -> Result<Spectrum, MediumError> {
    if k.is_nan() || k.is_infinite() || k < 0.0 {
        return Err(MediumError::Coefficient {
            what: "power-law k",
            bin: 0,
            value: k,
        });
    }
    let bad_l0 = lambda0_nm.is_nan() || lambda0_nm.is_infinite() || lambda0_nm <= 0.0;
    if bad_l0 || !p.is_finite() || grid.lambda_min <= 0.0 {
        return Err(MediumError::PowerLaw {
            lambda0: lambda0_nm,
            p,
        });
    }
    let (k, l0, p) = (k as f64, lambda0_nm as f64, p as f64);
    let mut s = Spectrum::ZERO;
    for i in 0..grid.n {
        let (a, b) = match grid.bin(i) {
            Bin::Band { lo, hi } => (lo, hi),
            Bin::Line { lambda, .. } => {
                s.0[i] = (k * (lambda / l0).powf(-p)) as f32;
                continue;
            }
        };
        // ∫_a^b (x/l0)^-p dx / (b - a), with x = lambda.
        let integral = if (p - 1.0).abs() < 1e-9 {
            l0 * (b / a).ln()
        } else {
            l0.powf(p) * (b.powf(1.0 - p) - a.powf(1.0 - p)) / (1.0 - p)
        };
        s.0[i] = (k * integral / (b - a)) as f32;
    }
    Ok(s)
}
