//! How much one pilot configuration lowered the variance below another's, and whether the
//! pilots resolve it.

/// How many standard errors a difference between two pilots' variances must reach to be
/// acted on: below it the pilots cannot tell the settings apart, and the base values stay
/// (rare bright samples, as of a laser seen through fog, make the variance itself noisy).
pub const Z_SIGNIFICANT: f64 = 2.0;

/// The gain of one pilot over another: the difference of their variances per pass, with its
/// standard error, from their per-pixel estimates `d = (x1 - x2)^2 / 2` taken pixel by pixel.
///
/// Pilots outside the film draw the same random numbers in every configuration
/// (`Tuner::random_pass`): the forward rays of the Base pair are, ray for ray, those of the
/// Medium pair (and the first of the Rays pair's). Their noise, most of a pilot's variance at
/// the base budgets, then cancels in the per-pixel difference, and the standard error is that
/// of the difference alone. Compared as two independent variances instead (the sum of their
/// standard errors in quadrature), height-fog's Base and Medium pilots, 12 500 forward rays
/// each, could not resolve q = 0.25's gain on 2 seeds of 16, which then kept q = 1 and passes
/// of 30 % more error (docs/performance.md, "The automatic choice on height-fog").
#[derive(Clone, Copy, Debug)]
pub(super) struct Gain {
    pub(super) gain: f64,
    pub(super) se: f64,
}

impl Gain {
    /// The gain of `after` over `before` (per-pixel `d` on the same pixels, each already scaled
    /// to the whole image: `Tuner::record`). The standard error is estimated by the sum of the
    /// squared per-pixel differences: pixels are taken as independent, as in `Measure::se`, and
    /// the estimate errs high by the sum of the squared per-pixel mean gains.
    pub(super) fn paired(before: &[f64], after: &[f64]) -> Self {
        Self::combined(&[(before, 1.0), (after, -1.0)])
    }

    /// The sum over pixels of `sum_i w_i d_i` for pilots' per-pixel `d_i` and weights `w_i`,
    /// with its standard error taken as `paired`'s (pixel by pixel, pixels independent).
    pub(super) fn combined(terms: &[(&[f64], f64)]) -> Self {
        let pixels = terms.iter().map(|(d, _)| d.len()).min().unwrap_or(0);
        let (mut gain, mut sq) = (0.0, 0.0);
        for p in 0..pixels {
            let e: f64 = terms.iter().map(|(d, w)| w * d[p]).sum();
            gain += e;
            sq += e * e;
        }
        Gain {
            gain,
            se: sq.sqrt(),
        }
    }

    /// The gain when it is significant and positive: what the choice may act on.
    pub(super) fn resolved(self) -> Option<f64> {
        let g = self.significant();
        (g > 0.0).then_some(g)
    }

    /// The gain if it exceeds `Z_SIGNIFICANT` standard errors, else 0.
    pub(super) fn significant(&self) -> f64 {
        if self.gain > Z_SIGNIFICANT * self.se {
            self.gain
        } else {
            0.0
        }
    }
}
