use std::f32::consts::PI;

/// Rayleigh scattering of unpolarised light by particles much smaller than the wavelength:
/// `p(cos) = 3 (1 + cos²) / (16 π)` (Chandrasekhar 1950; Bohren & Huffman 1983, eq. 5.9).
/// Symmetric, so its mean cosine is 0.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Rayleigh;

impl Rayleigh {
    #[inline]
    pub fn eval(&self, cos: f32) -> f32 {
        3.0 / (16.0 * PI) * (1.0 + cos * cos)
    }

    /// Exact inverse CDF. The CDF in `mu` is `(3/8) (mu + 1 + (mu³ + 1) / 3)`, so the sampled
    /// cosine is the real root of the depressed cubic `mu³ + 3 mu + (4 - 8 xi) = 0`, which
    /// Cardano's formula gives directly (its discriminant `q²/4 + 1` is always positive).
    #[inline]
    pub fn sample_cos(&self, xi: f32) -> f32 {
        let q = 4.0 - 8.0 * xi as f64;
        let d = (0.25 * q * q + 1.0).sqrt();
        // u - v with u = cbrt(d - q/2), v = cbrt(d + q/2) and u v = 1; written as u - 1/u where
        // u is the larger root term so that there is no cancellation between two cube roots.
        let mu = if q <= 0.0 {
            let u = (d - 0.5 * q).cbrt();
            u - 1.0 / u
        } else {
            let v = (d + 0.5 * q).cbrt();
            1.0 / v - v
        };
        (mu as f32).clamp(-1.0, 1.0)
    }
}
