//! Film pixels (bin radiance) -> working-space RGB.

use crate::spectrum::SpectralGrid;

use super::matrix::{self, Mat3};
use super::{Cat, ColourError, ColourSpace, D65_XY, Observer, XyzWeights};

/// Precomputed per-bin weights straight to the working space: one 3 x n matrix per image.
#[derive(Clone, Debug)]
pub struct FilmToRgb {
    pub xyz: XyzWeights,
    pub xyz_to_rgb: Mat3,
    /// Per bin, the RGB each unit of bin-averaged radiance contributes.
    w: Vec<[f32; 3]>,
}

impl FilmToRgb {
    /// XYZ normalisation: a constant radiance of 1 W/(m^2 sr nm) over the observer's whole
    /// range has Y = 1. The scene's adopted white is D65 (see [`ColourSpace::xyz_to_rgb`]).
    pub fn new(
        space: ColourSpace,
        observer: Observer,
        grid: &SpectralGrid,
        cat: Cat,
    ) -> Result<Self, ColourError> {
        let xyz = XyzWeights::new(observer, grid)?;
        let m = space.xyz_to_rgb(D65_XY, cat);
        let w = xyz
            .w
            .iter()
            .map(|b| matrix::apply(&m, *b).map(|c| c as f32))
            .collect();
        Ok(Self {
            xyz,
            xyz_to_rgb: m,
            w,
        })
    }

    pub fn rgb(&self, bins: &[f32]) -> [f32; 3] {
        let mut rgb = [0.0f32; 3];
        for (v, w) in bins.iter().zip(&self.w) {
            rgb[0] += v * w[0];
            rgb[1] += v * w[1];
            rgb[2] += v * w[2];
        }
        rgb
    }

    /// Standard error of each RGB component from per-bin standard errors, treating bins as
    /// independent (an approximation: bins of one path are correlated, so this can under- or
    /// over-state the true error).
    pub fn rgb_std_error(&self, bin_errors: &[f32]) -> [f32; 3] {
        let mut var = [0.0f32; 3];
        for (e, w) in bin_errors.iter().zip(&self.w) {
            for c in 0..3 {
                var[c] += (e * w[c]) * (e * w[c]);
            }
        }
        var.map(f32::sqrt)
    }
}
