//! The blend of two radii for scattered light, chosen from the film itself.
//!
//! A larger radius for scattered light (`integrator.radius_indirect = "auto"`, two pixel
//! footprints' worth more than the direct radius) gathers more of that light per forward ray,
//! so it has less noise, but it blurs: a bias the pilots, which see a few passes of noise,
//! cannot measure. Every forward segment that meets a ball of the smaller radius also meets the
//! larger ball around the same centre, so a pass can form both radii's estimates from the same
//! hits and keep their difference `D = E_small - E_large` per layer, pixel and bin (the pass
//! buffer's `blend` layers), with per-pixel sums of `D^2` and of `T D` (`T` the pass's total,
//! at the larger radius) for its noise.
//!
//! Whichever image the film outputs is `E_large + w D` with one weight `w` in [0, 1] for the
//! whole image, chosen at output from the film's sums ([`weight`]) to minimise the image's
//! mean square error estimated from them. With a ball's blur of order R^2 (a smooth field:
//! the bias is `R^2 / 10` times the Laplacian for a uniform ball in 3D) the larger radius's
//! bias is 4 times the smaller's, `b_large = -(4/3) E[D]`; the weighted image's bias is then
//! `E[D] (w - 4/3)` and its variance `(V_T + 2 w C + w^2 V_D) / n` over `n` passes, so
//!
//!   `w = ((4/3) A - C) / (A + B)`, with `A = sum E[D]^2`, `B = sum V_D / n`, `C = sum C_TD / n`
//!
//! over pixels and bins, clamped to [0, 1]. `A` is estimated without bias as
//! `sum (mean_D^2 - V_D / n)` (and taken as 0 when that is negative: no blur resolved). While
//! the blur is buried in noise, `w` is the variance-minimising mix (a small positive weight:
//! the smaller ball's hits are also the larger's); once the difference is resolved, `w` moves
//! to 1, the smaller radius's image. The choice is a function of the film's sums only, so a
//! film merged from pass ranges, resumed from a checkpoint or rendered in one run outputs the
//! same bits.

use rayon::prelude::*;

use super::fixed::{MAX_SAMPLE, SQ_SCALE, SUM_SCALE, to_fixed};
use super::layer::LAYERS;

/// The film's sums of the difference layers (see the module comment).
#[derive(Clone, Debug, PartialEq)]
pub struct BlendSums {
    /// `[layer][pixel][bin]` sums of `D`, fixed point at `SUM_SCALE`.
    pub sum: Vec<i128>,
    /// `[pixel][bin]` sums of the squared total difference `D^2`, at `SQ_SCALE`.
    pub sq: Vec<i128>,
    /// `[pixel][bin]` sums of `T D` (`T` the pass's total estimate), at `SQ_SCALE`.
    pub cross: Vec<i128>,
}

/// The weight the film chose and the terms it was chosen from (for reports).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Blend {
    /// The smaller radius's weight: the image is `E_large + w (E_small - E_large)`.
    pub w: f64,
    /// `sum E[D]^2` (clamped at 0), `sum V_D / n`, `sum C_TD / n` over pixels and bins.
    pub blur: f64,
    pub noise: f64,
    pub cross: f64,
}

/// The larger radius's bias over `E[D]` for a blur of order R^2 at twice the radius:
/// `b_large = 4 b_small`, `E[D] = b_small - b_large`.
const LARGE_BIAS_OVER_DIFFERENCE: f64 = 4.0 / 3.0;

impl BlendSums {
    /// Empty sums for `values` pixel-bins.
    pub fn new(values: usize) -> Self {
        Self {
            sum: vec![0; LAYERS * values],
            sq: vec![0; values],
            cross: vec![0; values],
        }
    }

    /// Number of i128 sums (for the film file).
    pub fn len(values: usize) -> usize {
        (LAYERS + 2) * values
    }

    /// Adds one pass: `data` its `[layer][pixel][bin]` estimate (at the larger radius), `diff`
    /// its `[layer][pixel][bin]` difference layers. Values the film drops (beyond
    /// `MAX_SAMPLE`, or not finite) are left out here too, so that the sums describe the same
    /// passes as the image's.
    pub fn add(&mut self, data: &[f32], diff: &[f32]) {
        let values = self.sq.len();
        let (m, s) = data.split_at(values);
        let (dm, ds) = diff.split_at(values);
        let (sum_m, sum_s) = self.sum.split_at_mut(values);
        const BLOCK: usize = 1 << 12;
        sum_m
            .par_chunks_mut(BLOCK)
            .zip(sum_s.par_chunks_mut(BLOCK))
            .zip(
                self.sq
                    .par_chunks_mut(BLOCK)
                    .zip(self.cross.par_chunks_mut(BLOCK)),
            )
            .enumerate()
            .for_each(|(k, ((sum_m, sum_s), (sq, cross)))| {
                let at = k * BLOCK;
                for i in 0..sum_m.len() {
                    let j = at + i;
                    let (a, b) = (dm[j] as f64, ds[j] as f64);
                    let (x, y) = (m[j] as f64, s[j] as f64);
                    if !([a, b, x, y].iter().all(|v| v.abs() <= MAX_SAMPLE)) {
                        continue;
                    }
                    let t = x + y;
                    let d = a + b;
                    sum_m[i] = sum_m[i].wrapping_add(to_fixed(a, SUM_SCALE));
                    sum_s[i] = sum_s[i].wrapping_add(to_fixed(b, SUM_SCALE));
                    sq[i] = sq[i].wrapping_add(to_fixed(d * d, SQ_SCALE));
                    cross[i] = cross[i].wrapping_add(to_fixed(t * d, SQ_SCALE));
                }
            });
    }

    /// Adds another film's sums (pass ranges merged).
    pub fn merge(&mut self, other: &BlendSums) {
        for (mine, theirs) in [
            (&mut self.sum, &other.sum),
            (&mut self.sq, &other.sq),
            (&mut self.cross, &other.cross),
        ] {
            for (a, b) in mine.iter_mut().zip(theirs) {
                *a = a.wrapping_add(*b);
            }
        }
    }

    /// The sums in file order (difference layers, squares, cross terms).
    pub fn all(&self) -> impl Iterator<Item = &i128> {
        self.sum.iter().chain(&self.sq).chain(&self.cross)
    }

    /// The sums from file order (see [`Self::all`]); None unless `sums` holds `len(values)`.
    pub fn from_all(mut sums: Vec<i128>, values: usize) -> Option<Self> {
        if sums.len() != Self::len(values) {
            return None;
        }
        let cross = sums.split_off((LAYERS + 1) * values);
        let sq = sums.split_off(LAYERS * values);
        Some(Self {
            sum: sums,
            sq,
            cross,
        })
    }

    /// The per-value statistics over `passes` passes at value `i`, given the image's total sum
    /// there (`total`, fixed point): the mean difference, its per-pass variance and the
    /// per-pass covariance with the total.
    fn stats(&self, i: usize, total: i128, passes: f64) -> (f64, f64, f64) {
        let values = self.sq.len();
        let d = self.sum[i].wrapping_add(self.sum[values + i]) as f64 / SUM_SCALE;
        let (m_d, m_t) = (d / passes, total as f64 / SUM_SCALE / passes);
        let dn = (passes - 1.0).max(1.0);
        let v_d = ((self.sq[i] as f64 / SQ_SCALE - passes * m_d * m_d) / dn).max(0.0);
        let c = (self.cross[i] as f64 / SQ_SCALE - passes * m_t * m_d) / dn;
        (m_d, v_d, c)
    }

    /// The weight the image takes (module comment), from these sums and the image's total sums
    /// `total(i)` over `passes` passes: 0 (the larger radius's image) below two passes.
    pub fn weight(&self, total: impl Fn(usize) -> i128, passes: u64) -> Blend {
        let p = passes as f64;
        let (mut blur, mut noise, mut cross) = (0.0, 0.0, 0.0);
        if passes >= 2 {
            for i in 0..self.sq.len() {
                let (m_d, v_d, c) = self.stats(i, total(i), p);
                blur += m_d * m_d - v_d / p;
                noise += v_d / p;
                cross += c / p;
            }
        }
        let blur = blur.max(0.0);
        let w = if passes >= 2 && blur + noise > 0.0 {
            ((LARGE_BIAS_OVER_DIFFERENCE * blur - cross) / (blur + noise)).clamp(0.0, 1.0)
        } else {
            0.0
        };
        Blend {
            w,
            blur,
            noise,
            cross,
        }
    }

    /// At value `i`: what the weight `w` adds to the medium and surface layers' means, and the
    /// variance per pass it adds to the total's (`2 w C + w^2 V_D`).
    pub fn shift(&self, i: usize, total: i128, passes: u64, w: f64) -> (f64, f64, f64) {
        let values = self.sq.len();
        let p = passes.max(1) as f64;
        let (_, v_d, c) = self.stats(i, total, p);
        let m = self.sum[i] as f64 / SUM_SCALE / p;
        let s = self.sum[values + i] as f64 / SUM_SCALE / p;
        (w * m, w * s, 2.0 * w * c + w * w * v_d)
    }
}

#[cfg(test)]
#[path = "blend_tests.rs"]
mod tests;
