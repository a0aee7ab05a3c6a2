use std::f64::consts::PI;

use crate::medium::MediumError;

/// Draine's phase function (Draine 2003, ApJ 598, eq. 4):
/// `p(mu) = (1 - g²) (1 + α mu²) / (4π (1 + α (1 + 2g²)/3) (1 + g² - 2 g mu)^{3/2})`.
/// α = 0 is Henyey–Greenstein, α = 1 with g = 0 is Rayleigh-like (Cornette & Shanks 1992 use
/// a similar form); Jendersie & d'Eon 2023 use it as the backward/side part of droplet phases.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Draine {
    g: f64,
    alpha: f64,
    /// `(1 - g²) / (4π (1 + α (1 + 2 g²) / 3))`.
    norm: f64,
}

/// Below this |g| the closed-form CDF cancels (its terms grow like α/g³); there a Gauss–Legendre
/// rule integrates the (then nearly polynomial) density instead, exact to rounding.
const G_SMALL: f64 = 0.05;

/// 10-point Gauss–Legendre nodes and weights on [-1, 1] (Abramowitz & Stegun 25.4.30).
const GL_X: [f64; 5] = [
    0.148_874_338_981_631_2,
    0.433_395_394_129_247_2,
    0.679_409_568_299_024_4,
    0.865_063_366_688_984_5,
    0.973_906_528_517_171_7,
];
const GL_W: [f64; 5] = [
    0.295_524_224_714_752_9,
    0.269_266_719_309_996_4,
    0.219_086_362_515_982,
    0.149_451_349_150_580_6,
    0.066_671_344_308_688_1,
];

impl Draine {
    /// `g` in (-1, 1), `alpha` >= 0 (finite).
    pub fn new(g: f32, alpha: f32) -> Result<Self, MediumError> {
        if !(g.is_finite() && g.abs() < 1.0) {
            return Err(MediumError::PhaseG(g));
        }
        if !(alpha.is_finite() && alpha >= 0.0) {
            return Err(MediumError::PhaseParameter {
                what: "alpha",
                value: alpha,
                range: "[0, inf)",
            });
        }
        let (g, alpha) = (g as f64, alpha as f64);
        let norm = (1.0 - g * g) / (4.0 * PI * (1.0 + alpha * (1.0 + 2.0 * g * g) / 3.0));
        Ok(Self { g, alpha, norm })
    }

    /// Mean cosine, from the moments of HG (`<mu> = g`, `<mu³> = g (3 + 2 g²) / 5`):
    /// `g (1 + α (3 + 2g²)/5) / (1 + α (1 + 2g²)/3)` (Draine 2003, eq. 6).
    pub fn g(&self) -> f32 {
        let (g, a) = (self.g, self.alpha);
        (g * (1.0 + a * (3.0 + 2.0 * g * g) / 5.0) / (1.0 + a * (1.0 + 2.0 * g * g) / 3.0)) as f32
    }

    /// The `g` parameter (not the mean cosine unless alpha = 0).
    pub fn g_param(&self) -> f32 {
        self.g as f32
    }

    pub fn alpha(&self) -> f32 {
        self.alpha as f32
    }

    pub fn eval64(&self, mu: f64) -> f64 {
        let g = self.g;
        let u = (1.0 + g * g - 2.0 * g * mu).max(1e-300);
        self.norm * (1.0 + self.alpha * mu * mu) / (u * u.sqrt())
    }

    #[inline]
    pub fn eval(&self, cos: f32) -> f32 {
        self.eval64(cos as f64) as f32
    }

    /// `2π ∫_{-1}^{mu} p` : the CDF of the cosine.
    pub fn cdf(&self, mu: f64) -> f64 {
        if self.g.abs() < G_SMALL {
            let (h, c) = (0.5 * (mu + 1.0), 0.5 * (mu - 1.0));
            let s: f64 = GL_X
                .iter()
                .zip(GL_W)
                .map(|(&x, w)| w * (self.eval64(c + h * x) + self.eval64(c - h * x)))
                .sum();
            return 2.0 * PI * h * s;
        }
        2.0 * PI * self.norm * (self.antiderivative(mu) - self.antiderivative(-1.0))
    }

    /// An antiderivative in mu of `(1 + α mu²) u^{-3/2}`, `u = 1 + g² - 2 g mu`: with
    /// `mu = (A - u)/(2g)`, `A = 1 + g²`, the integrand becomes a sum of powers of u.
    fn antiderivative(&self, mu: f64) -> f64 {
        let g = self.g;
        let a = 1.0 + g * g;
        let u = (a - 2.0 * g * mu).max(1e-300);
        let s = u.sqrt();
        let k = self.alpha / (4.0 * g * g);
        let inner = -2.0 / s + k * (-2.0 * a * a / s - 4.0 * a * s + (2.0 / 3.0) * u * s);
        -inner / (2.0 * g)
    }

    /// Inverts the exact CDF by Newton's method kept inside a shrinking bracket (bisection when
    /// a step would leave it), started from the HG sample with the same `xi`; converges to
    /// ~1e-12 in a handful of steps, so evaluation and sampling agree to rounding.
    pub fn sample_cos(&self, xi: f32) -> f32 {
        let target = xi as f64;
        let (mut lo, mut hi) = (-1.0f64, 1.0f64);
        let mut mu = hg_inverse(self.g, target);
        for _ in 0..60 {
            let f = self.cdf(mu) - target;
            if f.abs() < 1e-13 {
                break;
            }
            if f > 0.0 {
                hi = mu;
            } else {
                lo = mu;
            }
            let step = mu - f / (2.0 * PI * self.eval64(mu));
            mu = if step > lo && step < hi {
                step
            } else {
                0.5 * (lo + hi)
            };
            if hi - lo < 1e-15 {
                break;
            }
        }
        (mu as f32).clamp(-1.0, 1.0)
    }
}

/// HG inverse CDF in f64 (a starting point only).
fn hg_inverse(g: f64, xi: f64) -> f64 {
    if g.abs() < 1e-6 {
        return 2.0 * xi - 1.0;
    }
    let s = (1.0 - g * g) / (1.0 - g + 2.0 * g * xi);
    ((1.0 + g * g - s * s) / (2.0 * g)).clamp(-1.0, 1.0)
}
