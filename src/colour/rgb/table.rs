//! The coefficient table: fitted once on first use (a second or so), then interpolated.

use std::sync::OnceLock;

use rayon::prelude::*;

use super::fit::FitContext;
use super::sigmoid::SigmoidPolynomial;

/// The table fitted ahead of time and shipped with brume (see [`CoefficientTable::srgb`]).
static SHIPPED: &[u8] = include_bytes!("../../../spectra/srgb-coefficients.bin");

/// Table resolution per axis.
pub const RES: usize = 32;

/// Coefficients indexed by the largest RGB component (3 tables), then by z (that component's
/// value, on a smoothstep-squared scale dense near 0 and 1), y and x (the other two components
/// divided by the largest, in cyclic order).
pub struct CoefficientTable {
    z_scale: Vec<f64>,
    data: Vec<[f64; 3]>,
}

fn smoothstep(x: f64) -> f64 {
    x * x * (3.0 - 2.0 * x)
}

fn index(l: usize, k: usize, j: usize, i: usize) -> usize {
    ((l * RES + k) * RES + j) * RES + i
}

impl CoefficientTable {
    /// The shared sRGB table: the one shipped in `spectra/srgb-coefficients.bin` (written by
    /// `cargo run --release --example make_rgb_table`), or fitted on first use if that file is
    /// missing or malformed.
    pub fn srgb() -> Option<&'static CoefficientTable> {
        static TABLE: OnceLock<Option<CoefficientTable>> = OnceLock::new();
        TABLE
            .get_or_init(|| {
                Self::from_bytes(SHIPPED).or_else(|| FitContext::srgb().map(Self::compute))
            })
            .as_ref()
    }

    fn z_scale() -> Vec<f64> {
        (0..RES)
            .map(|k| smoothstep(smoothstep(k as f64 / (RES - 1) as f64)))
            .collect()
    }

    /// The coefficients as little-endian f64, in index order (the shipped file's format).
    pub fn to_bytes(&self) -> Vec<u8> {
        self.data
            .iter()
            .flat_map(|c| c.iter().flat_map(|v| v.to_le_bytes()))
            .collect()
    }

    /// Reads [`Self::to_bytes`]'s format; None if the size is wrong or a value is not finite.
    pub fn from_bytes(bytes: &[u8]) -> Option<Self> {
        if bytes.len() != 3 * RES * RES * RES * 3 * 8 {
            return None;
        }
        let values: Vec<f64> = bytes
            .chunks_exact(8)
            .map(|b| f64::from_le_bytes(b.try_into().unwrap_or([0; 8])))
            .collect();
        if values.iter().any(|v| !v.is_finite()) {
            return None;
        }
        let data = values.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect();
        Some(Self {
            z_scale: Self::z_scale(),
            data,
        })
    }

    /// Largest absolute difference between two tables' coefficients.
    pub fn max_difference(&self, other: &Self) -> f64 {
        self.data
            .iter()
            .zip(&other.data)
            .flat_map(|(a, b)| (0..3).map(move |n| (a[n] - b[n]).abs()))
            .fold(0.0, f64::max)
    }

    pub fn compute(ctx: &FitContext) -> Self {
        let z_scale = Self::z_scale();
        let start_k = RES / 5;
        // One task per (largest component, x column); each walks y, and from a mid z outwards
        // in both directions, warm-starting every fit from its neighbour's solution.
        let columns: Vec<Vec<(usize, [f64; 3])>> = (0..3 * RES)
            .into_par_iter()
            .map(|task| {
                let (l, i) = (task / RES, task % RES);
                let x = i as f64 / (RES - 1) as f64;
                let mut out = Vec::with_capacity(RES * RES);
                for j in 0..RES {
                    let y = j as f64 / (RES - 1) as f64;
                    let mut fit_at = |k: usize, start: [f64; 3]| {
                        let b = z_scale[k];
                        let mut rgb = [0.0; 3];
                        rgb[l] = b;
                        rgb[(l + 1) % 3] = x * b;
                        rgb[(l + 2) % 3] = y * b;
                        let c = ctx.fit(rgb, start);
                        out.push((index(l, k, j, i), c));
                        c
                    };
                    let mid = fit_at(start_k, [0.0; 3]);
                    let mut c = mid;
                    for k in start_k + 1..RES {
                        c = fit_at(k, c);
                    }
                    c = mid;
                    for k in (0..start_k).rev() {
                        c = fit_at(k, c);
                    }
                }
                out
            })
            .collect();
        let mut data = vec![[0.0; 3]; 3 * RES * RES * RES];
        for (idx, c) in columns.into_iter().flatten() {
            data[idx] = c;
        }
        Self { z_scale, data }
    }

    /// Coefficients for linear sRGB `rgb` with components in [0, 1] (trilinear interpolation).
    pub fn lookup(&self, rgb: [f64; 3]) -> SigmoidPolynomial {
        let rgb = rgb.map(|v| v.clamp(0.0, 1.0));
        if rgb[0] == rgb[1] && rgb[1] == rgb[2] {
            return SigmoidPolynomial::constant(rgb[0]);
        }
        let l = if rgb[0] >= rgb[1] && rgb[0] >= rgb[2] {
            0
        } else if rgb[1] >= rgb[2] {
            1
        } else {
            2
        };
        let z = rgb[l];
        let scale = (RES - 1) as f64;
        let x = rgb[(l + 1) % 3] / z * scale;
        let y = rgb[(l + 2) % 3] / z * scale;
        let k = self.z_scale.partition_point(|&s| s <= z).clamp(1, RES - 1) - 1;
        let fz = ((z - self.z_scale[k]) / (self.z_scale[k + 1] - self.z_scale[k])).clamp(0.0, 1.0);
        let i = (x as usize).min(RES - 2);
        let j = (y as usize).min(RES - 2);
        let (fx, fy) = (x - i as f64, y - j as f64);
        let mut c = [0.0; 3];
        for (dk, wk) in [(0, 1.0 - fz), (1, fz)] {
            for (dj, wj) in [(0, 1.0 - fy), (1, fy)] {
                for (di, wi) in [(0, 1.0 - fx), (1, fx)] {
                    let w = wk * wj * wi;
                    let v = self.data[index(l, k + dk, j + dj, i + di)];
                    for n in 0..3 {
                        c[n] += w * v[n];
                    }
                }
            }
        }
        SigmoidPolynomial { c }
    }
}
