//! Fitting sigmoid-polynomial coefficients to sRGB colours (Jakob and Hanika 2019): for each
//! target, Gauss-Newton on the CIELAB difference between the target and the spectrum's colour
//! as a reflectance under D65 (sRGB's white), with the CIE 1931 observer.

use std::sync::OnceLock;

use super::super::matrix::{self, Mat3};
use super::super::{ColourSpace, Observer};
use super::sigmoid::{LAMBDA_HI, LAMBDA_LO, SigmoidPolynomial, normalised};
use crate::spectrum::{Extrapolation, resolve};

/// Quadrature samples over 360-830 nm (midpoint rule, ~3.9 nm apart).
const SAMPLES: usize = 120;
/// Largest coefficient magnitude the fit may reach (the paper's value; 2000 was tried and
/// gains under 3e-3 in the worst round trip while making spectra too sharp for bin averaging).
const LIMIT: f64 = 200.0;

/// What the fit needs: per sample, the normalised wavelength and the XYZ weight of a unit
/// reflectance under D65 (so that the perfect white has Y = 1), the white, and RGB -> XYZ.
pub struct FitContext {
    t: [f64; SAMPLES],
    w: [[f64; 3]; SAMPLES],
    white: [f64; 3],
    rgb_to_xyz: Mat3,
}

impl FitContext {
    /// The sRGB / D65 context, built once. `None` only if the embedded data failed to parse,
    /// which the unit tests rule out.
    pub fn srgb() -> Option<&'static FitContext> {
        static CTX: OnceLock<Option<FitContext>> = OnceLock::new();
        CTX.get_or_init(Self::build).as_ref()
    }

    fn build() -> Option<FitContext> {
        let cmfs = Observer::Cie1931.cmfs().ok()?;
        let d65 = resolve("D65", None, false).ok()?;
        let h = (LAMBDA_HI - LAMBDA_LO) / SAMPLES as f64;
        let mut t = [0.0; SAMPLES];
        let mut w = [[0.0; 3]; SAMPLES];
        let mut white = [0.0; 3];
        let ext = Extrapolation::Zero;
        for k in 0..SAMPLES {
            let l = LAMBDA_LO + (k as f64 + 0.5) * h;
            t[k] = normalised(l);
            let e = d65.eval(l, Extrapolation::Clamp) * h;
            w[k] = [
                cmfs.x.eval(l, ext) * e,
                cmfs.y.eval(l, ext) * e,
                cmfs.z.eval(l, ext) * e,
            ];
            for c in 0..3 {
                white[c] += w[k][c];
            }
        }
        let norm = 1.0 / white[1];
        for wk in w.iter_mut() {
            *wk = wk.map(|v| v * norm);
        }
        let white = white.map(|v| v * norm);
        let rgb_to_xyz = matrix::invert(&ColourSpace::Srgb.xyz_to_rgb_unadapted());
        Some(FitContext {
            t,
            w,
            white,
            rgb_to_xyz,
        })
    }

    /// XYZ of the reflectance `sp` under D65 (white Y = 1).
    pub fn xyz(&self, sp: &SigmoidPolynomial) -> [f64; 3] {
        let mut xyz = [0.0; 3];
        for (t, w) in self.t.iter().zip(&self.w) {
            let v = sp.eval_t(*t);
            for c in 0..3 {
                xyz[c] += v * w[c];
            }
        }
        xyz
    }

    pub fn rgb_of(&self, sp: &SigmoidPolynomial) -> [f64; 3] {
        matrix::apply(&matrix::invert(&self.rgb_to_xyz), self.xyz(sp))
    }

    fn lab(&self, xyz: [f64; 3]) -> [f64; 3] {
        let f = |v: f64| {
            const D: f64 = 6.0 / 29.0;
            if v > D * D * D {
                v.cbrt()
            } else {
                v / (3.0 * D * D) + 4.0 / 29.0
            }
        };
        let [fx, fy, fz] = [0, 1, 2].map(|c| f(xyz[c] / self.white[c]));
        [116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz)]
    }

    fn residual(&self, c: [f64; 3], target_lab: [f64; 3]) -> [f64; 3] {
        let lab = self.lab(self.xyz(&SigmoidPolynomial { c }));
        [0, 1, 2].map(|i| lab[i] - target_lab[i])
    }

    /// Coefficients whose reflectance under D65 has linear sRGB `rgb` (each in [0, 1]),
    /// starting the Gauss-Newton iteration from `start`.
    pub fn fit(&self, rgb: [f64; 3], start: [f64; 3]) -> [f64; 3] {
        let target = self.lab(matrix::apply(&self.rgb_to_xyz, rgb));
        let norm = |r: [f64; 3]| r.iter().map(|v| v * v).sum::<f64>();
        let clamp = |c: [f64; 3]| {
            // Keep the polynomial in a range where f64 stays accurate (as the paper's code).
            let m = c.iter().fold(0.0f64, |a, v| a.max(v.abs()));
            if m > LIMIT {
                c.map(|v| v * LIMIT / m)
            } else {
                c
            }
        };
        let mut c = start;
        let mut r = self.residual(c, target);
        for _ in 0..30 {
            if norm(r) < 1e-10 {
                break;
            }
            // Forward-difference Jacobian, columns d r / d c_j.
            let mut jac = [[0.0; 3]; 3];
            for j in 0..3 {
                let mut cp = c;
                let eps = 1e-5 * c[j].abs().max(1.0);
                cp[j] += eps;
                let rp = self.residual(cp, target);
                for i in 0..3 {
                    jac[i][j] = (rp[i] - r[i]) / eps;
                }
            }
            let step = matrix::apply(&matrix::invert(&jac), r);
            if !step.iter().all(|s| s.is_finite()) {
                break;
            }
            // Backtracking: a full Gauss-Newton step can overshoot from a poor start (dark,
            // saturated targets), so halve it until the residual goes down.
            let mut t = 1.0;
            let mut improved = false;
            for _ in 0..12 {
                let cn = clamp([0, 1, 2].map(|j| c[j] - t * step[j]));
                let rn = self.residual(cn, target);
                if norm(rn) < norm(r) {
                    (c, r, improved) = (cn, rn, true);
                    break;
                }
                t *= 0.5;
            }
            if !improved {
                break;
            }
        }
        c
    }
}
