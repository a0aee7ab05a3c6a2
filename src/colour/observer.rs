//! Colour-matching functions reduced to exact bin integrals, and spectrum -> XYZ.

use std::sync::OnceLock;

use super::{ColourError, Observer};
use crate::spectrum::{Extrapolation, PiecewiseLinear, SpectralGrid, Spectrum, builtin_table};

/// The three colour-matching functions of one observer, as tabulated.
pub struct Cmfs {
    pub x: PiecewiseLinear,
    pub y: PiecewiseLinear,
    pub z: PiecewiseLinear,
    /// Integral of y-bar over its whole table: the normalisation that makes a constant
    /// spectrum of 1 have Y = 1 (the convention of pbrt and of colour-science's illuminant E).
    pub y_integral: f64,
}

fn load(name: &str) -> Result<Cmfs, ColourError> {
    let table = builtin_table(name)
        .ok_or_else(|| ColourError::Other(format!("missing built-in {name}")))??;
    let x = table.column(Some("x_bar"))?;
    let y = table.column(Some("y_bar"))?;
    let z = table.column(Some("z_bar"))?;
    let (a, b) = y.range();
    let y_integral = y.integral(a, b, Extrapolation::Zero);
    Ok(Cmfs {
        x,
        y,
        z,
        y_integral,
    })
}

impl Observer {
    /// The observer's tabulated CMFs (parsed once from the embedded CSV).
    pub fn cmfs(self) -> Result<&'static Cmfs, ColourError> {
        static C1931: OnceLock<Result<Cmfs, String>> = OnceLock::new();
        static C1964: OnceLock<Result<Cmfs, String>> = OnceLock::new();
        let (cell, name) = match self {
            Observer::Cie1931 => (&C1931, "cie1931"),
            Observer::Cie1964 => (&C1964, "cie1964"),
        };
        cell.get_or_init(|| load(name).map_err(|e| e.to_string()))
            .as_ref()
            .map_err(|e| ColourError::Other(e.clone()))
    }
}

/// Per-bin weights turning bin-averaged spectral values into XYZ:
/// `XYZ = sum_i value_i * w_i`, with `w_i = (integral of cmf over bin i) / y_integral`; in a
/// line bin the integral is the CMF at the line times the bin's width, so a line's power
/// (value times width) is weighted exactly at its wavelength.
#[derive(Clone, Debug)]
pub struct XyzWeights {
    pub w: Vec<[f64; 3]>,
}

impl XyzWeights {
    pub fn new(observer: Observer, grid: &SpectralGrid) -> Result<Self, ColourError> {
        let c = observer.cmfs()?;
        let zx = c.x.bin_integrals(grid, Extrapolation::Zero);
        let zy = c.y.bin_integrals(grid, Extrapolation::Zero);
        let zz = c.z.bin_integrals(grid, Extrapolation::Zero);
        let k = 1.0 / c.y_integral;
        Ok(Self {
            w: (0..grid.n)
                .map(|i| [zx[i] * k, zy[i] * k, zz[i] * k])
                .collect(),
        })
    }

    pub fn xyz(&self, bins: &[f32]) -> [f64; 3] {
        let mut xyz = [0.0; 3];
        for (v, w) in bins.iter().zip(&self.w) {
            let v = *v as f64;
            xyz[0] += v * w[0];
            xyz[1] += v * w[1];
            xyz[2] += v * w[2];
        }
        xyz
    }

    pub fn xyz_of(&self, s: &Spectrum) -> [f64; 3] {
        self.xyz(s.as_slice(self.w.len()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn constant_spectrum_has_unit_luminance_over_the_full_table() {
        // Over the CMFs' whole range the bin sums are the exact continuous integrals.
        for obs in [Observer::Cie1931, Observer::Cie1964] {
            let g = SpectralGrid::new(47, 360.0, 830.0);
            let w = XyzWeights::new(obs, &g).unwrap();
            let xyz = w.xyz_of(&Spectrum::splat(1.0, g.n));
            assert!((xyz[1] - 1.0).abs() < 1e-12, "{obs:?} {xyz:?}");
        }
    }

    #[test]
    fn bin_integrals_sum_to_the_table_integral_for_any_bin_count() {
        let c = Observer::Cie1931.cmfs().unwrap();
        for n in [1, 7, 16, 64] {
            let g = SpectralGrid::new(n, 360.0, 830.0);
            let s: f64 = c.x.bin_integrals(&g, Extrapolation::Zero).iter().sum();
            // Known value of the CIE 1931 x-bar integral at 1 nm (trapezoid): 106.8654.
            assert!((s - 106.865).abs() < 1e-2, "n={n}: {s}");
        }
    }
}
