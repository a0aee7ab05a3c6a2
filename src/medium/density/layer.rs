//! A fog bank: `rho(h) = 1` below `top - w/2`, `0` above `top + w/2`, and between them
//! `1 - S(x)` with the smooth step `S(x) = 3x² - 2x³`, `x = (h - top + w/2) / w` (`w` the
//! transition width), so the density and its slope are continuous.
//!
//! Integral: the profile is a polynomial of degree at most 3 on each of its three pieces, so
//! Simpson's rule on each piece of `[a, b]` is exact, and it involves no difference of large
//! antiderivatives (short or nearly level pieces keep their precision). Inverse: the pieces are
//! crossed in order; in a constant piece the answer is linear, in the step it is the root of a
//! monotone quartic, found by bisection to f64 resolution.

use glam::Vec3;

use super::{Profile, unit};

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Layer {
    /// Where the step starts (`top - w/2`) and ends (`top + w/2`).
    lo: f64,
    hi: f64,
    up: Vec3,
}

impl Layer {
    /// `transition` > 0 and `up` nonzero (checked by `DensityDesc::check`).
    pub fn new(top: f32, transition: f32, up: Vec3) -> Self {
        let (top, w) = (top as f64, transition as f64);
        Self {
            lo: top - 0.5 * w,
            hi: top + 0.5 * w,
            up: unit(up),
        }
    }

    /// The field in words, for `brume info`.
    pub fn describe(&self) -> String {
        format!(
            "fog bank: full below {} m, none above {} m along up {}",
            self.lo, self.hi, self.up
        )
    }

    /// `∫_a^b rho` for `a <= b` inside one piece.
    fn simpson(&self, a: f64, b: f64) -> f64 {
        (b - a) / 6.0 * (self.rho(a) + 4.0 * self.rho(0.5 * (a + b)) + self.rho(b))
    }

    /// `∫_a^b rho` for `a <= b`, piece by piece.
    fn forward(&self, a: f64, b: f64) -> f64 {
        let mut total = 0.0;
        let mut x = a;
        for cut in [self.lo, self.hi, f64::INFINITY] {
            if x >= b {
                break;
            }
            if cut <= x {
                continue;
            }
            let y = cut.min(b);
            total += if x >= self.hi {
                0.0
            } else if y <= self.lo {
                y - x
            } else {
                self.simpson(x, y)
            };
            x = y;
        }
        total
    }
}

impl Profile for Layer {
    fn up(&self) -> Vec3 {
        self.up
    }

    #[inline]
    fn rho(&self, h: f64) -> f64 {
        if h <= self.lo {
            1.0
        } else if h >= self.hi {
            0.0
        } else {
            let x = (h - self.lo) / (self.hi - self.lo);
            1.0 - x * x * (3.0 - 2.0 * x)
        }
    }

    fn integral(&self, a: f64, b: f64) -> f64 {
        if b >= a {
            self.forward(a, b)
        } else {
            -self.forward(b, a)
        }
    }

    fn solve(&self, a: f64, g: f64) -> Option<f64> {
        // Going up (g > 0) the density only falls, going down it only rises: cross the pieces
        // in the ray's order.
        let up = g > 0.0;
        let mut left = g.abs();
        let mut x = a;
        let cuts: [f64; 3] = if up {
            [self.lo, self.hi, f64::INFINITY]
        } else {
            [self.hi, self.lo, f64::NEG_INFINITY]
        };
        for cut in cuts {
            let beyond = if up { cut <= x } else { cut >= x };
            if beyond {
                continue;
            }
            let piece = self.integral(x, cut).abs();
            if piece >= left {
                return Some(self.within(x, cut, left, up));
            }
            left -= piece;
            x = cut;
        }
        None
    }

    fn range(&self, lo: f64, hi: f64) -> (f64, f64) {
        (self.rho(hi), self.rho(lo))
    }
}

impl Layer {
    /// The `b` between `x` and `cut` at which `|∫_x^b rho| = left` (known to be reached there).
    fn within(&self, x: f64, cut: f64, left: f64, up: bool) -> f64 {
        if x.max(cut) <= self.lo {
            // The fog below the step: density 1.
            return if up { x + left } else { x - left };
        }
        let (mut a, mut b) = (x, cut);
        for _ in 0..80 {
            let m = 0.5 * (a + b);
            if m == a || m == b {
                break;
            }
            if self.integral(x, m).abs() < left {
                a = m;
            } else {
                b = m;
            }
        }
        0.5 * (a + b)
    }
}
