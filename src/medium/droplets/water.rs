//! Complex refractive index of the droplets' material as a function of wavelength.

use std::path::Path;

use num_complex::Complex;

use crate::medium::MediumError;
use crate::spectrum::{Extrapolation, PiecewiseLinear, SpectralTable};

/// Liquid water at 25 °C, Hale & Querry 1973 (source in spectra/README.md).
const WATER: &str = include_str!("../../../spectra/water_hale_querry_1973.csv");
const WATER_NAME: &str = "spectra/water_hale_querry_1973.csv";

/// `n(λ) + i k(λ)`, each linear in wavelength between the tabulated points (held constant
/// beyond them).
#[derive(Clone, Debug)]
pub struct RefractiveIndex {
    n: PiecewiseLinear,
    k: PiecewiseLinear,
    pub source: String,
}

impl RefractiveIndex {
    /// The built-in water table.
    pub fn water() -> Result<Self, MediumError> {
        Self::from_text(WATER, WATER_NAME)
    }

    /// `water` or a CSV file (columns `wavelength_nm`, `n`, `k`).
    pub fn load(name: &str, path: &Path) -> Result<Self, MediumError> {
        if name == "water" {
            return Self::water();
        }
        let text = std::fs::read_to_string(path).map_err(|e| MediumError::Read {
            file: path.to_path_buf(),
            message: e.to_string(),
        })?;
        Self::from_text(&text, &path.display().to_string())
    }

    fn from_text(text: &str, source: &str) -> Result<Self, MediumError> {
        let bad = |e: crate::spectrum::SpectrumError| MediumError::Droplets(e.to_string());
        let t = SpectralTable::parse(text, source, false).map_err(bad)?;
        Ok(Self {
            n: t.column(Some("n")).map_err(bad)?,
            k: t.column(Some("k")).map_err(bad)?,
            source: source.to_string(),
        })
    }

    /// The index at `lambda_nm`; the imaginary part is the absorbing one (k >= 0).
    pub fn at(&self, lambda_nm: f64) -> Complex<f64> {
        Complex::new(
            self.n.eval(lambda_nm, Extrapolation::Clamp),
            self.k.eval(lambda_nm, Extrapolation::Clamp),
        )
    }
}
