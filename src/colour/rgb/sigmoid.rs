//! The sigmoid-polynomial spectrum of Jakob and Hanika (2019).

use crate::spectrum::{Bin, MAX_BINS, SpectralGrid, Spectrum};

/// Wavelength range the polynomial's variable is normalised over (the CMFs' range).
pub const LAMBDA_LO: f64 = 360.0;
pub const LAMBDA_HI: f64 = 830.0;

/// Sub-samples per bin when averaging the (smooth) sigmoid over a bin.
const SUBSAMPLES: usize = 8;

/// `s(lambda) = S(c0 t^2 + c1 t + c2)` with `t = (lambda - 360) / 470` and
/// `S(x) = 1/2 + x / (2 sqrt(1 + x^2))`: smooth, bounded to (0, 1), three parameters.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SigmoidPolynomial {
    pub c: [f64; 3],
}

pub fn sigmoid(x: f64) -> f64 {
    if x.is_infinite() {
        return if x > 0.0 { 1.0 } else { 0.0 };
    }
    0.5 + x / (2.0 * (1.0 + x * x).sqrt())
}

pub fn normalised(lambda: f64) -> f64 {
    (lambda - LAMBDA_LO) / (LAMBDA_HI - LAMBDA_LO)
}

impl SigmoidPolynomial {
    /// The constant spectrum `v` (0 <= v <= 1), exactly.
    pub fn constant(v: f64) -> Self {
        let c2 = if v <= 0.0 {
            f64::NEG_INFINITY
        } else if v >= 1.0 {
            f64::INFINITY
        } else {
            // Inverse of S: x = (v - 1/2) / sqrt(v (1 - v)).
            (v - 0.5) / (v * (1.0 - v)).sqrt()
        };
        Self { c: [0.0, 0.0, c2] }
    }

    pub fn eval_t(&self, t: f64) -> f64 {
        if self.c[2].is_infinite() && self.c[0] == 0.0 && self.c[1] == 0.0 {
            return sigmoid(self.c[2]);
        }
        sigmoid((self.c[0] * t + self.c[1]) * t + self.c[2])
    }

    pub fn eval(&self, lambda: f64) -> f64 {
        self.eval_t(normalised(lambda))
    }

    /// Band averages (midpoint rule with a few sub-samples: the curve is smooth at bin scale)
    /// and, in a line bin, the value at the line.
    pub fn bin_averages(&self, grid: &SpectralGrid) -> Spectrum {
        let mut s = Spectrum::ZERO;
        for i in 0..grid.n.min(MAX_BINS) {
            let (a, b) = match grid.bin(i) {
                Bin::Band { lo, hi } => (lo, hi),
                Bin::Line { lambda, .. } => {
                    s.0[i] = self.eval(lambda) as f32;
                    continue;
                }
            };
            let h = (b - a) / SUBSAMPLES as f64;
            let sum: f64 = (0..SUBSAMPLES)
                .map(|k| self.eval(a + (k as f64 + 0.5) * h))
                .sum();
            s.0[i] = (sum / SUBSAMPLES as f64) as f32;
        }
        s
    }
}
