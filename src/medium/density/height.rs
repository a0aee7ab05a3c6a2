//! Exponential height fog: `rho(h) = exp(-(h - base) / H)` with `h = up . x` and the scale
//! height `H` (1 at `base`, e times thinner every `H` metres up).
//!
//! Integral: `∫_a^b rho = H rho(a) (1 - e^{-(b - a)/H})`, written with `expm1` so that short or
//! nearly level pieces keep their precision. Inverse: the `b` at which that integral is `g` is
//! `a - H ln(1 - g / (H rho(a)))` (`log1p`), which exists going down for every `g` and going up
//! only for `g < H rho(a)`, the whole depth above `a`.

use glam::Vec3;

use super::{Profile, unit};

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Height {
    base: f64,
    scale: f64,
    up: Vec3,
}

impl Height {
    /// `scale_height` > 0 and `up` nonzero (checked by `DensityDesc::check`).
    pub fn new(base: f32, scale_height: f32, up: Vec3) -> Self {
        Self {
            base: base as f64,
            scale: scale_height as f64,
            up: unit(up),
        }
    }

    /// The field in words, for `brume info`.
    pub fn describe(&self) -> String {
        format!(
            "height fog: scale height {} m from base {} m along up {}",
            self.scale, self.base, self.up
        )
    }
}

impl Profile for Height {
    fn up(&self) -> Vec3 {
        self.up
    }

    #[inline]
    fn rho(&self, h: f64) -> f64 {
        (-(h - self.base) / self.scale).exp()
    }

    #[inline]
    fn integral(&self, a: f64, b: f64) -> f64 {
        -self.scale * self.rho(a) * (-(b - a) / self.scale).exp_m1()
    }

    #[inline]
    fn solve(&self, a: f64, g: f64) -> Option<f64> {
        let x = g / (self.scale * self.rho(a));
        (x < 1.0 && x.is_finite()).then(|| a - self.scale * (-x).ln_1p())
    }

    fn range(&self, lo: f64, hi: f64) -> (f64, f64) {
        (self.rho(hi), self.rho(lo))
    }
}
