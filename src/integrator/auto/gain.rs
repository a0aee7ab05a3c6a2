//! How much one pilot configuration lowered the variance below another's, and whether the
//! pilots resolve it.

/// How many standard errors a difference between two pilots' variances must reach to be
/// acted on: below it the pilots cannot tell the settings apart, and the base values stay
/// (rare bright samples, as of a laser seen through fog, make the variance itself noisy).
pub const Z_SIGNIFICANT: f64 = 2.0;

/// The share of pixels, those of the largest per-pixel differences, that the bulk's test
/// leaves out (`Gain::bulk`). chromatic-fog's pilots (one pixel of 4: 8 192) put nearly all
/// their variance in a few pixels where the spot's beam enters the fog: the Samples pilot's
/// gain is 1.43e4 +- 1.09e4 over every pixel on seed 1 (not resolved), 321 +- 63 without the
/// largest 0.2 % (17 pixels).
pub const TAIL_SHARE: f64 = 0.002;

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
    /// The gain and its standard error without the `TAIL_SHARE` of pixels whose differences
    /// are largest, scaled to every pixel: the bulk's evidence (`Gain::resolved_or_bulk`).
    pub(super) bulk: (f64, f64),
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
        let mut e: Vec<f64> = (0..pixels)
            .map(|p| terms.iter().map(|(d, w)| w * d[p]).sum())
            .collect();
        let (gain, sq) = sums(&e);
        // The bulk: the largest |e| left out (at least one pixel when there are several).
        let tail = ((pixels as f64 * TAIL_SHARE).ceil() as usize).min(pixels.saturating_sub(1));
        e.sort_unstable_by(|a, b| b.abs().total_cmp(&a.abs()));
        let (bulk_gain, bulk_sq) = sums(&e[tail..]);
        let scale = pixels as f64 / (pixels - tail).max(1) as f64;
        Gain {
            gain,
            se: sq.sqrt(),
            bulk: (bulk_gain * scale, (bulk_sq * scale).sqrt()),
        }
    }

    /// A gain of `gain +- se` with no separate bulk (every pixel alike).
    pub(super) fn uniform(gain: f64, se: f64) -> Self {
        Gain {
            gain,
            se,
            bulk: (gain, se),
        }
    }

    /// The gain when it is significant and positive: what the choice may act on.
    pub(super) fn resolved(self) -> Option<f64> {
        let g = self.significant();
        (g > 0.0).then_some(g)
    }

    /// A budget pilot's gain as the budgets' choice takes it: resolved over every pixel, or
    /// in the bulk, positive over every pixel and beyond `Z_SIGNIFICANT` standard errors
    /// without the tail (`TAIL_SHARE`). Where the variance is in a few pixels that two passes
    /// cannot measure (chromatic-fog's beam entering the fog), the rest of the image still
    /// says which way a budget goes, and the gain over every pixel says how far. The terms
    /// of the noise split (`choose::bounded`) keep `resolved`: there the bulk's evidence
    /// moved the parallel-light cubes' choices away from their best (docs/performance.md).
    pub(super) fn resolved_or_bulk(self) -> Option<f64> {
        self.resolved().or_else(|| {
            let (g, se) = self.bulk;
            (self.gain > 0.0 && g > Z_SIGNIFICANT * se).then_some(self.gain)
        })
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

/// The sum of `e` and of its squares.
fn sums(e: &[f64]) -> (f64, f64) {
    e.iter().fold((0.0, 0.0), |(s, q), x| (s + x, q + x * x))
}
