//! Photometry: radiometric quantities weighted by the CIE 1931 photopic luminous efficiency
//! function V(λ) (= the 1931 observer's y-bar) and K_m = 683 lm/W, the blackbody of a given
//! temperature, and the meteorological optical range of a medium (CIE 17.4 / WMO: the distance
//! over which a collimated beam of a 2700 K lamp loses 95 % of its luminous flux).
//!
//! Everything here works on the film's bins: a quantity given as bin averages (W/nm, W/(m² nm),
//! W/(m² sr nm)) becomes lm, lx or cd/m² as `K_m * sum_i value_i * integral of V over bin i`,
//! exactly the sum the film applies to its own bins, so a light given in lumens renders with
//! that luminous flux whatever the bin count.

use super::{ColourError, Observer};
use crate::spectrum::{Extrapolation, SpectralGrid};

/// Maximum luminous efficacy of radiation for photopic vision, lm/W (CIE; SI definition of the
/// candela at 540 THz, with the 1931 V(λ)).
pub const K_M: f64 = 683.0;

/// Colour temperature of the lamp in the CIE definition of the meteorological optical range.
pub const MOR_TEMPERATURE: f64 = 2700.0;

/// Fraction of the luminous flux left at the meteorological optical range (5 %).
pub const MOR_FRACTION: f64 = 0.05;

/// Per bin, the photometric weight of a bin-averaged spectral value: `K_m` times the integral
/// of V(λ) over the bin (lm/W times nm). `sum_i value_i * w_i` is the photometric quantity.
pub fn luminous_weights(grid: &SpectralGrid) -> Result<Vec<f64>, ColourError> {
    let c = Observer::Cie1931.cmfs()?;
    Ok(c.y
        .bin_integrals(grid, Extrapolation::Zero)
        .into_iter()
        .map(|v| K_M * v)
        .collect())
}

/// The photometric value (lm, lx or cd/m²) of a bin-averaged radiometric spectrum.
pub fn photometric(weights: &[f64], bins: &[f32]) -> f64 {
    bins.iter().zip(weights).map(|(v, w)| *v as f64 * w).sum()
}

/// Luminous efficacy (lm/W) of a spectrum: its luminous flux per watt of radiant power over the
/// grid's range. None when the spectrum carries no power.
pub fn luminous_efficacy(weights: &[f64], bins: &[f32], grid: &SpectralGrid) -> Option<f64> {
    let power: f64 = (bins.iter().enumerate())
        .map(|(i, v)| *v as f64 * grid.bin_width(i))
        .sum();
    (power > 0.0 && power.is_finite()).then(|| photometric(weights, bins) / power)
}

/// What a film's Y (normalised so that a constant radiance of 1 over the observer's table has
/// Y = 1) is multiplied by to give cd/m² (for the 1931 observer: K_m times the integral of
/// y-bar, 683 x 106.857 = 72 983).
pub fn luminance_scale(observer: Observer) -> Result<f64, ColourError> {
    Ok(K_M * observer.cmfs()?.y_integral)
}

/// Planck's law: spectral radiance of a blackbody at `temperature` K and wavelength `lambda`
/// nm, in W/(m² sr nm).
pub fn planck(lambda_nm: f64, temperature: f64) -> f64 {
    // Second radiation constant c2 = hc/k = 1.438 776 877e-2 m K (CODATA 2018), first
    // constant for radiance c1L = 2hc^2 = 1.191 042 972e-16 W m^2 / sr.
    const C1L: f64 = 1.191_042_972e-16;
    const C2: f64 = 1.438_776_877e-2;
    let l = lambda_nm * 1e-9;
    let per_m = C1L / (l.powi(5) * ((C2 / (l * temperature)).exp_m1()));
    per_m * 1e-9
}

/// Per bin, the integral over the bin of the blackbody at `temperature` times V(λ), by a
/// midpoint rule on 0.25 nm steps (the integrand is smooth and V is piecewise linear on 1 nm).
pub fn blackbody_luminous_bins(
    grid: &SpectralGrid,
    temperature: f64,
) -> Result<Vec<f64>, ColourError> {
    let v = &Observer::Cie1931.cmfs()?.y;
    Ok((0..grid.n)
        .map(|i| {
            let (a, b) = grid.edges(i);
            let steps = ((b - a) / 0.25).ceil().max(1.0) as usize;
            let h = (b - a) / steps as f64;
            (0..steps)
                .map(|k| {
                    let l = a + (k as f64 + 0.5) * h;
                    planck(l, temperature) * v.eval(l, Extrapolation::Zero) * h
                })
                .sum()
        })
        .collect())
}

/// The meteorological optical range (m) of a medium of extinction `sigma_t` (1/m per bin): the
/// distance d at which `sum_i w_i exp(-sigma_t_i d) = 0.05`, with `w` the 2700 K blackbody
/// times V(λ) per bin, normalised. Exact for a chromatic medium (the luminous flux of the
/// beam, not of one wavelength). None when the medium does not dim the beam (no extinction
/// where V(λ) is non-zero).
pub fn meteorological_optical_range(
    sigma_t: &[f32],
    grid: &SpectralGrid,
) -> Result<Option<f64>, ColourError> {
    let w = blackbody_luminous_bins(grid, MOR_TEMPERATURE)?;
    Ok(transmission_distance(&w, sigma_t, MOR_FRACTION))
}

/// The distance at which the weighted transmittance `sum w_i exp(-s_i d) / sum w_i` falls to
/// `fraction`: bracketed by doubling, then bisected to the last bit (the function is monotone).
pub fn transmission_distance(w: &[f64], sigma: &[f32], fraction: f64) -> Option<f64> {
    let total: f64 = w.iter().sum();
    if !(total > 0.0 && total.is_finite()) {
        return None;
    }
    // Flux that never decays (bins without extinction) bounds the transmittance from below.
    let floor: f64 = w
        .iter()
        .zip(sigma)
        .filter(|(_, s)| s.partial_cmp(&&0.0) != Some(std::cmp::Ordering::Greater))
        .map(|(w, _)| w)
        .sum::<f64>()
        / total;
    if floor >= fraction {
        return None;
    }
    let t = |d: f64| {
        w.iter()
            .zip(sigma)
            .map(|(w, s)| w * (-(*s as f64).max(0.0) * d).exp())
            .sum::<f64>()
            / total
    };
    let max_sigma = sigma.iter().fold(0.0f32, |m, s| m.max(*s)) as f64;
    let mut hi = (-fraction.ln()) / max_sigma;
    while t(hi) > fraction {
        hi *= 2.0;
        if !hi.is_finite() {
            return None;
        }
    }
    let mut lo = 0.0;
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if t(mid) > fraction {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    Some(0.5 * (lo + hi))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn planck_matches_known_values() {
        // Wien's displacement law: the peak of B(λ, T) lies at b / T, b = 2.897 771 955e-3 m K.
        let t = 2700.0;
        let peak = 2.897_771_955e6 / t;
        let (a, b) = (planck(peak - 1.0, t), planck(peak + 1.0, t));
        let p = planck(peak, t);
        assert!(p > a && p > b);
        // Stefan-Boltzmann: pi * integral of B over all wavelengths = sigma T^4.
        let mut total = 0.0;
        let mut l = 10.0;
        while l < 200_000.0 {
            total += planck(l + 0.05, t) * 0.1;
            l += 0.1;
        }
        let sigma = 5.670_374_419e-8;
        let expect = sigma * t.powi(4) / std::f64::consts::PI;
        assert!((total / expect - 1.0).abs() < 1e-3, "{total} vs {expect}");
    }

    #[test]
    fn monochromatic_555_nm_has_efficacy_near_683() {
        // A 1 nm wide bin at 555 nm, where V = 1.
        let g = SpectralGrid::new(1, 554.5, 555.5);
        let w = luminous_weights(&g).unwrap();
        let e = luminous_efficacy(&w, &[1.0], &g).unwrap();
        assert!((e - 683.0).abs() < 0.1, "{e}");
    }

    /// Bins wider than 1 nm, of two widths: a flat spectrum's efficacy is K_m times the mean
    /// of V over the range (the same whatever the bins), and the power it divides by counts
    /// each bin's width.
    #[test]
    fn efficacy_counts_the_bin_widths() {
        let y = &Observer::Cie1931.cmfs().unwrap().y;
        let want = K_M * y.integral(400.0, 700.0, Extrapolation::Zero) / 300.0;
        // The 1931 y-bar integrates to 106.794 over 400-700 nm (trapezoid of its 1 nm table).
        assert!(
            (want / (683.0 * 106.794 / 300.0) - 1.0).abs() < 1e-4,
            "{want}"
        );
        for n in [5, 12] {
            let g = SpectralGrid::new(n, 400.0, 700.0);
            let w = luminous_weights(&g).unwrap();
            let e = luminous_efficacy(&w, &vec![2.5; n], &g).unwrap();
            assert!((e / want - 1.0).abs() < 1e-9, "{n} bins: {e} vs {want}");
        }
    }

    #[test]
    fn grey_medium_mor_is_ln20_over_sigma() {
        let g = SpectralGrid::new(32, 380.0, 780.0);
        for st in [0.001f32, 0.06, 3.0] {
            let mor = meteorological_optical_range(&[st; 32], &g)
                .unwrap()
                .unwrap();
            let expect = 20f64.ln() / st as f64;
            assert!((mor / expect - 1.0).abs() < 1e-6, "{mor} vs {expect}");
        }
        assert_eq!(meteorological_optical_range(&[0.0; 32], &g).unwrap(), None);
    }

    /// A chromatic medium: more extinction in the blue; the MOR lies between the grey values of
    /// its smallest and largest extinction, and where its own definition says.
    #[test]
    fn chromatic_mor_solves_its_definition() {
        let g = SpectralGrid::new(16, 380.0, 780.0);
        let sigma: Vec<f32> = (0..16).map(|i| 0.2 - 0.01 * i as f32).collect();
        let d = meteorological_optical_range(&sigma, &g).unwrap().unwrap();
        let w = blackbody_luminous_bins(&g, MOR_TEMPERATURE).unwrap();
        let tw: f64 = w.iter().sum();
        let t: f64 = w
            .iter()
            .zip(&sigma)
            .map(|(w, s)| w * (-(*s as f64) * d).exp())
            .sum::<f64>()
            / tw;
        assert!((t - 0.05).abs() < 1e-12, "{t}");
        assert!(d > 20f64.ln() / 0.2 && d < 20f64.ln() / 0.05);
    }
}
