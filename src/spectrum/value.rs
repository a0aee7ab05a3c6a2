use std::ops::{Add, AddAssign, Div, DivAssign, Index, IndexMut, Mul, MulAssign, Sub};

/// Largest number of spectral bins a scene may ask for.
pub const MAX_BINS: usize = 64;

/// A spectral quantity: one value per bin of the scene's [`super::SpectralGrid`].
///
/// The storage is a fixed `MAX_BINS` array so that arithmetic is branch-free and vectorises;
/// lanes past the scene's bin count stay zero (every constructor that takes a count zeroes them),
/// so sums over all lanes equal sums over the active bins.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Spectrum(pub [f32; MAX_BINS]);

impl Default for Spectrum {
    fn default() -> Self {
        Self::ZERO
    }
}

impl Spectrum {
    pub const ZERO: Spectrum = Spectrum([0.0; MAX_BINS]);

    /// `v` in the first `n` bins, zero elsewhere.
    pub fn splat(v: f32, n: usize) -> Self {
        let mut s = Self::ZERO;
        s.0[..n.min(MAX_BINS)].fill(v);
        s
    }

    /// A spectrum that is `v` in bin `i` only.
    pub fn single(i: usize, v: f32) -> Self {
        let mut s = Self::ZERO;
        s.0[i] = v;
        s
    }

    pub fn from_slice(v: &[f32]) -> Self {
        let mut s = Self::ZERO;
        let n = v.len().min(MAX_BINS);
        s.0[..n].copy_from_slice(&v[..n]);
        s
    }

    pub fn as_slice(&self, n: usize) -> &[f32] {
        &self.0[..n]
    }

    pub fn sum(&self) -> f32 {
        self.0.iter().sum()
    }

    pub fn max_value(&self) -> f32 {
        self.0.iter().copied().fold(0.0, f32::max)
    }

    pub fn is_zero(&self) -> bool {
        self.0.iter().all(|&x| x == 0.0)
    }

    pub fn is_finite(&self) -> bool {
        self.0.iter().all(|x| x.is_finite())
    }

    pub fn map(&self, f: impl Fn(f32) -> f32) -> Self {
        let mut s = *self;
        s.0.iter_mut().for_each(|x| *x = f(*x));
        s
    }

    /// Elementwise `exp(-self * t)` over the first `n` bins (zero past them).
    pub fn transmittance(&self, t: f32, n: usize) -> Self {
        self.map_runs(n, |x| (-x * t).exp())
    }

    /// `f` of each of the first `n` bins (zero past them), evaluated once per run of bins with
    /// the same bits: a grey medium repeats one coefficient in every bin, and its transmittance
    /// then costs one exp instead of n. The values are those of a bin-by-bin loop.
    #[inline]
    pub fn map_runs(&self, n: usize, f: impl Fn(f32) -> f32) -> Self {
        let mut s = Self::ZERO;
        let mut last: Option<(u32, f32)> = None;
        for i in 0..n {
            let x = self.0[i];
            let v = match last {
                Some((bits, v)) if bits == x.to_bits() => v,
                Some(_) | None => {
                    let v = f(x);
                    last = Some((x.to_bits(), v));
                    v
                }
            };
            s.0[i] = v;
        }
        s
    }

    /// Division that maps x/0 to 0, for weights where a zero denominator means "no contribution".
    pub fn safe_div(&self, rhs: &Spectrum) -> Self {
        let mut s = Self::ZERO;
        for i in 0..MAX_BINS {
            if rhs.0[i] != 0.0 {
                s.0[i] = self.0[i] / rhs.0[i];
            }
        }
        s
    }
}

impl Index<usize> for Spectrum {
    type Output = f32;
    fn index(&self, i: usize) -> &f32 {
        &self.0[i]
    }
}

impl IndexMut<usize> for Spectrum {
    fn index_mut(&mut self, i: usize) -> &mut f32 {
        &mut self.0[i]
    }
}

macro_rules! elementwise {
    ($tr:ident, $f:ident, $tra:ident, $fa:ident, $op:tt) => {
        // One macro serves + * /, so the binary operator is spelled out, not its `op=` form.
        #[allow(clippy::assign_op_pattern)]
        impl $tr for Spectrum {
            type Output = Spectrum;
            #[inline]
            fn $f(mut self, rhs: Spectrum) -> Spectrum {
                for i in 0..MAX_BINS {
                    self.0[i] = self.0[i] $op rhs.0[i];
                }
                self
            }
        }
        #[allow(clippy::assign_op_pattern)]
        impl $tr<f32> for Spectrum {
            type Output = Spectrum;
            #[inline]
            fn $f(mut self, rhs: f32) -> Spectrum {
                for x in self.0.iter_mut() {
                    *x = *x $op rhs;
                }
                self
            }
        }
        impl $tra for Spectrum {
            #[inline]
            fn $fa(&mut self, rhs: Spectrum) {
                *self = *self $op rhs;
            }
        }
        impl $tra<f32> for Spectrum {
            #[inline]
            fn $fa(&mut self, rhs: f32) {
                *self = *self $op rhs;
            }
        }
    };
}

elementwise!(Add, add, AddAssign, add_assign, +);
elementwise!(Mul, mul, MulAssign, mul_assign, *);
elementwise!(Div, div, DivAssign, div_assign, /);

impl Sub for Spectrum {
    type Output = Spectrum;
    #[inline]
    fn sub(mut self, rhs: Spectrum) -> Spectrum {
        for i in 0..MAX_BINS {
            self.0[i] -= rhs.0[i];
        }
        self
    }
}

impl Mul<Spectrum> for f32 {
    type Output = Spectrum;
    #[inline]
    fn mul(self, rhs: Spectrum) -> Spectrum {
        rhs * self
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `map_runs` gives the bits of a bin-by-bin loop: on runs of equal coefficients (grey and
    /// piecewise-grey spectra), on a coefficient that comes back after another, on -0.0 beside
    /// 0.0 (different bits, each evaluated), and zero past `n`. A cache keyed on value rather
    /// than bits fails at the -0.0 / 0.0 pair (`signum` tells them apart), one that is never
    /// refreshed at the first change of coefficient. (0 x inf is a NaN either way; its sign bit
    /// is the compiler's choice, so NaNs only need to be NaNs.)
    #[test]
    fn map_runs_matches_the_loop() {
        let mut s = Spectrum::ZERO;
        let coeffs = [0.5, 0.5, 0.5, 2.0, 2.0, 0.5, -0.0, 0.0, 1e-3, 1e-3, 7.0];
        s.0[..coeffs.len()].copy_from_slice(&coeffs);
        for t in [0.0, 0.37, 5.0, f32::INFINITY] {
            let n = coeffs.len() - 1;
            let got = s.map_runs(n, |x| (-x * t).exp() + x.signum());
            let tr = s.transmittance(t, n);
            let same = |a: f32, b: f32| a.to_bits() == b.to_bits() || a.is_nan() && b.is_nan();
            for (i, (&g, &x)) in got.0.iter().zip(&s.0).enumerate() {
                let want = if i < n {
                    (-x * t).exp() + x.signum()
                } else {
                    0.0
                };
                assert!(same(g, want), "bin {i} at t = {t}: {g} against {want}");
                let tr_want = if i < n { (-x * t).exp() } else { 0.0 };
                assert!(same(tr.0[i], tr_want), "transmittance, bin {i} at t = {t}");
            }
        }
    }
}
