//! A tabulated intensity distribution (from an IES file): evaluated by bilinear interpolation in
//! the vertical angle gamma (from the axis, the nadir of a type C file) and the horizontal angle
//! C (about the axis), and sampled exactly in proportion to that interpolant, so that every
//! forward ray carries the same flux.
//!
//! The file's symmetry is expanded once into a full table over C in [0, 360] degrees (LM-63:
//! a single horizontal angle is rotationally symmetric, 0-90 symmetric in each quadrant, 0-180
//! symmetric about the 0-180 plane; a full table that stops short of 360 wraps to 0); the
//! mirrored angles coincide with table angles, so bilinear interpolation of the expanded table
//! equals interpolation of the file's table at the mirrored angle.
//!
//! Sampling: a cell of the table is picked in proportion to its exact flux (the interpolant
//! times sin gamma, integrated in closed form); within it gamma is drawn from its marginal,
//! `(a + b gamma) sin gamma`, by a safeguarded Newton solve of the closed-form CDF, and C from
//! the conditional, which is linear in C, by inverting a quadratic.

use std::f64::consts::TAU;

use glam::{Vec2, Vec3};

use super::ies::IesData;

#[derive(Clone, Debug, PartialEq)]
pub struct Goniometric {
    /// Vertical angles (radians), increasing; nothing is emitted outside `[gamma[0], last]`.
    gamma: Vec<f64>,
    /// Horizontal angles (radians) from 0 to 2 pi.
    c: Vec<f64>,
    /// Intensity (cd) per `[c][gamma]`.
    values: Vec<f64>,
    /// Cumulative flux of the cells `[c][gamma]` (lm), the last entry the total.
    cdf: Vec<f64>,
    /// Largest intensity in the table (cd).
    peak: f64,
    /// Largest gamma with light (radians): the interpolant is zero beyond it.
    cutoff: f64,
}

/// Why a table cannot be used.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ProfileError {
    #[error("the candela table is zero everywhere: the profile emits nothing")]
    Dark,
}

impl Goniometric {
    /// The distribution of a type C file, with absolute intensities (candela x multiplier x
    /// ballast factor).
    pub fn from_ies(d: &IesData) -> Result<Self, ProfileError> {
        let nv = d.vertical.len();
        let column = |h: usize| -> Vec<f64> { (0..nv).map(|v| d.intensity(h, v)).collect() };
        // (angle in degrees, source column) over the full circle.
        let h = &d.horizontal;
        let last = h[h.len() - 1];
        let mut cols: Vec<(f64, usize)> = h.iter().copied().zip(0..).collect();
        if last == 0.0 {
            cols = vec![(0.0, 0), (360.0, 0)];
        } else if last == 90.0 {
            mirror(&mut cols, 180.0);
            mirror(&mut cols, 360.0);
        } else if last == 180.0 {
            mirror(&mut cols, 360.0);
        } else if last < 360.0 {
            cols.push((360.0, 0));
        }
        let mut values = Vec::with_capacity(cols.len() * nv);
        for (_, k) in &cols {
            values.extend(column(*k));
        }
        let g = Self::from_table(
            d.vertical.iter().map(|a| a.to_radians()).collect(),
            cols.iter().map(|(a, _)| a.to_radians()).collect(),
            values,
        );
        if g.total() > 0.0 {
            Ok(g)
        } else {
            Err(ProfileError::Dark)
        }
    }

    /// `values[c][gamma]` on the full-circle grid.
    fn from_table(gamma: Vec<f64>, c: Vec<f64>, values: Vec<f64>) -> Self {
        let nv = gamma.len();
        let mut cdf = Vec::with_capacity((c.len() - 1) * (nv - 1));
        let mut acc = 0.0;
        for j in 0..c.len() - 1 {
            for i in 0..nv - 1 {
                let at = |jj: usize, ii: usize| values[jj * nv + ii];
                let a = 0.5 * (at(j, i) + at(j + 1, i));
                let b = 0.5 * (at(j, i + 1) + at(j + 1, i + 1));
                acc += (c[j + 1] - c[j]) * linear_sin_integral(a, b, gamma[i], gamma[i + 1], 1.0);
                cdf.push(acc);
            }
        }
        let peak = values.iter().fold(0.0f64, |m, v| m.max(*v));
        // The first vertical angle from which every row is dark: the interpolant vanishes there.
        let dark_from = (0..nv)
            .rev()
            .take_while(|&i| (0..c.len()).all(|j| values[j * nv + i] == 0.0))
            .last()
            .unwrap_or(nv - 1);
        Self {
            cutoff: gamma[dark_from],
            gamma,
            c,
            values,
            cdf,
            peak,
        }
    }

    /// Total flux of the table (lm for candela): the integral of the interpolant over the
    /// sphere.
    pub fn total(&self) -> f64 {
        self.cdf.last().copied().unwrap_or(0.0)
    }

    /// Largest intensity of the table.
    pub fn peak(&self) -> f64 {
        self.peak
    }

    /// Cosine of the largest angle from the axis with light, when the table has a hard
    /// cut-off before the zenith (None when light may leave in any direction).
    pub fn cone_cos(&self) -> Option<f32> {
        (self.cutoff < std::f64::consts::PI - 1e-9).then(|| self.cutoff.cos() as f32)
    }

    /// The interpolated intensity towards the local direction `d` (unit; axis +Z, C = 0 along
    /// +X, C = 90 along +Y).
    pub fn eval(&self, d: Vec3) -> f64 {
        let z = (d.z as f64).clamp(-1.0, 1.0);
        let gamma = z.acos();
        let mut c = (d.y as f64).atan2(d.x as f64);
        if c < 0.0 {
            c += TAU;
        }
        self.eval_angles(gamma, c)
    }

    /// The interpolant at vertical angle `gamma` and horizontal angle `c` (radians).
    pub fn eval_angles(&self, gamma: f64, c: f64) -> f64 {
        let (g, nv) = (&self.gamma, self.gamma.len());
        if !(gamma >= g[0] && gamma <= g[nv - 1]) {
            return 0.0;
        }
        let i = segment(g, gamma);
        let j = segment(&self.c, c.clamp(0.0, TAU));
        let s = ((gamma - g[i]) / (g[i + 1] - g[i])).clamp(0.0, 1.0);
        let t = ((c - self.c[j]) / (self.c[j + 1] - self.c[j])).clamp(0.0, 1.0);
        let at = |jj: usize, ii: usize| self.values[jj * nv + ii];
        let lo = at(j, i) * (1.0 - t) + at(j + 1, i) * t;
        let hi = at(j, i + 1) * (1.0 - t) + at(j + 1, i + 1) * t;
        lo * (1.0 - s) + hi * s
    }

    /// A local direction with density `eval(d) / total()` per steradian, from two uniforms.
    pub fn sample(&self, u: Vec2) -> Vec3 {
        let total = self.total();
        let nv = self.gamma.len();
        let pick = (u.x as f64) * total;
        let k = self
            .cdf
            .partition_point(|&c| c <= pick)
            .min(self.cdf.len() - 1);
        let below = if k == 0 { 0.0 } else { self.cdf[k - 1] };
        let mass = self.cdf[k] - below;
        let v = if mass > 0.0 {
            ((pick - below) / mass).clamp(0.0, 1.0)
        } else {
            0.5
        };
        let (j, i) = (k / (nv - 1), k % (nv - 1));
        let at = |jj: usize, ii: usize| self.values[jj * nv + ii];
        let (g0, g1) = (self.gamma[i], self.gamma[i + 1]);
        let a = 0.5 * (at(j, i) + at(j + 1, i));
        let b = 0.5 * (at(j, i + 1) + at(j + 1, i + 1));
        let gamma = sample_linear_sin(a, b, g0, g1, v);
        // Given gamma, the intensity is linear in C across the cell.
        let s = ((gamma - g0) / (g1 - g0)).clamp(0.0, 1.0);
        let p = at(j, i) * (1.0 - s) + at(j, i + 1) * s;
        let q = at(j + 1, i) * (1.0 - s) + at(j + 1, i + 1) * s;
        let w = u.y as f64;
        let t = if p + q > 0.0 {
            w * (p + q) / (p + (p * p * (1.0 - w) + q * q * w).sqrt())
        } else {
            w
        };
        let c = self.c[j] + t.clamp(0.0, 1.0) * (self.c[j + 1] - self.c[j]);
        let (sg, cg) = gamma.sin_cos();
        Vec3::new((sg * c.cos()) as f32, (sg * c.sin()) as f32, cg as f32)
    }
}

/// Appends the mirror images `about - angle` of the columns (in increasing angle, without
/// repeating the mirror line).
fn mirror(cols: &mut Vec<(f64, usize)>, about: f64) {
    let back: Vec<(f64, usize)> = cols
        .iter()
        .rev()
        .skip(1)
        .map(|&(a, k)| (about - a, k))
        .collect();
    cols.extend(back);
}

/// Index `i` of the segment `[x[i], x[i+1]]` holding `v` (clamped to the ends).
fn segment(x: &[f64], v: f64) -> usize {
    x.partition_point(|&a| a <= v).clamp(1, x.len() - 1) - 1
}

/// `integral over [g0, g] of (a + (b - a) s) sin(gamma) d gamma`, with s = (gamma - g0) / (g1 -
/// g0) and g = g0 + frac (g1 - g0).
fn linear_sin_integral(a: f64, b: f64, g0: f64, g1: f64, frac: f64) -> f64 {
    let h = g1 - g0;
    let beta = (b - a) / h;
    let alpha = a - beta * g0;
    // Antiderivative of (alpha + beta x) sin x: -alpha cos x + beta (sin x - x cos x).
    let f = |x: f64| -alpha * x.cos() + beta * (x.sin() - x * x.cos());
    f(g0 + frac * h) - f(g0)
}

/// Gamma in `[g0, g1]` whose CDF under the density `(a + (b - a) s) sin gamma` is `v`.
fn sample_linear_sin(a: f64, b: f64, g0: f64, g1: f64, v: f64) -> f64 {
    let total = linear_sin_integral(a, b, g0, g1, 1.0);
    if total.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
        return g0 + v * (g1 - g0);
    }
    let target = v * total;
    let (mut lo, mut hi) = (0.0f64, 1.0f64);
    let mut x = v;
    for _ in 0..60 {
        let f = linear_sin_integral(a, b, g0, g1, x) - target;
        if f > 0.0 {
            hi = x;
        } else {
            lo = x;
        }
        let g = g0 + x * (g1 - g0);
        let dens = (a + (b - a) * x) * g.sin() * (g1 - g0);
        let mut next = if dens > 0.0 { x - f / dens } else { -1.0 };
        if !(next > lo && next < hi) {
            next = 0.5 * (lo + hi);
        }
        if (next - x).abs() < 1e-15 {
            x = next;
            break;
        }
        x = next;
    }
    g0 + x.clamp(0.0, 1.0) * (g1 - g0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn closed_form_integral_matches_quadrature() {
        let (a, b, g0, g1) = (3.0, 0.5, 0.3, 1.1);
        let n = 100_000;
        let q: f64 = (0..n)
            .map(|k| {
                let s = (k as f64 + 0.5) / n as f64;
                let g = g0 + s * (g1 - g0);
                (a + (b - a) * s) * g.sin() * (g1 - g0) / n as f64
            })
            .sum();
        assert!((linear_sin_integral(a, b, g0, g1, 1.0) - q).abs() < 1e-9);
        for v in [0.0, 0.1, 0.5, 0.93, 1.0] {
            let g = sample_linear_sin(a, b, g0, g1, v);
            let f = linear_sin_integral(a, b, g0, g1, (g - g0) / (g1 - g0));
            assert!((f / q - v).abs() < 1e-9, "{v}: {}", f / q);
        }
    }
}
