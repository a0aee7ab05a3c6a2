use super::hg::HenyeyGreenstein;
use crate::medium::MediumError;

/// Two-term Henyey–Greenstein: `w HG(g1) + (1 - w) HG(g2)`, usually a forward lobe (g1 > 0)
/// and a backward one (g2 < 0), the classic fit of cloud and haze phase functions with a
/// back-scattering tail that one HG lobe lacks (Kattawar 1975; Haltrin 2002).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TwoTermHg {
    first: HenyeyGreenstein,
    second: HenyeyGreenstein,
    w: f32,
}

impl TwoTermHg {
    /// `g1`, `g2` in (-1, 1) and the first lobe's weight `w` in [0, 1].
    pub fn new(g1: f32, g2: f32, w: f32) -> Result<Self, MediumError> {
        if !(w.is_finite() && (0.0..=1.0).contains(&w)) {
            return Err(MediumError::PhaseParameter {
                what: "weight",
                value: w,
                range: "[0, 1]",
            });
        }
        Ok(Self {
            first: HenyeyGreenstein::new(g1)?,
            second: HenyeyGreenstein::new(g2)?,
            w,
        })
    }

    /// Mean cosine: the weighted mean of the lobes' `g`.
    pub fn g(&self) -> f32 {
        self.w * self.first.g() + (1.0 - self.w) * self.second.g()
    }

    /// Evaluated in f64: the lobes are often strongly peaked (see `HenyeyGreenstein::eval64`).
    #[inline]
    pub fn eval(&self, cos: f32) -> f32 {
        let (mu, w) = (cos as f64, self.w as f64);
        (w * self.first.eval64(mu) + (1.0 - w) * self.second.eval64(mu)) as f32
    }

    /// Picks a lobe with `xi` and reuses the rest of `xi`, rescaled to [0, 1), to invert that
    /// lobe's CDF: the mixture is then sampled exactly with one random number.
    #[inline]
    pub fn sample_cos(&self, xi: f32) -> f32 {
        let (lobe, xi) = split(xi, self.w);
        let lobe = if lobe { &self.first } else { &self.second };
        lobe.sample_cos64(xi as f64) as f32
    }
}

/// Chooses the first component of a two-part mixture with probability `w` from one uniform
/// `xi` in [0, 1), and returns a fresh uniform in [0, 1) from what is left of `xi`.
#[inline]
pub(crate) fn split(xi: f32, w: f32) -> (bool, f32) {
    if xi < w {
        (true, (xi / w).min(ONE_BELOW))
    } else {
        (false, ((xi - w) / (1.0 - w)).clamp(0.0, ONE_BELOW))
    }
}

/// The largest f32 below 1: rescaled uniforms stay in [0, 1).
pub(crate) const ONE_BELOW: f32 = 1.0 - f32::EPSILON / 2.0;
