use crate::medium::MediumError;
use glam::Vec3;
use std::f32::consts::PI;

/// Henyey–Greenstein phase function.
///
/// Convention: `cos` is the cosine of the angle between the *propagation* directions of light
/// before and after scattering (so `g > 0` is forward scattering and `E[cos] = g`). For a camera
/// ray of direction `u` (camera -> scene) gathering a forward ray of direction `v`, light turns
/// from `v` into `-u`, so the value to use is `eval(-u.dot(v))` (see [`HenyeyGreenstein::eval_uv`]).
/// The density is normalised over the sphere of directions: `∫ f dω = 1`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HenyeyGreenstein {
    g: f32,
}

/// Switch between the two forms of the inverse CDF (see `sample_cos`); at this |g| both are
/// accurate to ~1e-6 in cos.
const G_SMALL: f32 = 0.05;

impl HenyeyGreenstein {
    /// `g` must be finite with |g| < 1.
    pub fn new(g: f32) -> Result<Self, MediumError> {
        if g.is_finite() && g.abs() < 1.0 {
            Ok(Self { g })
        } else {
            Err(MediumError::PhaseG(g))
        }
    }

    /// Asymmetry parameter (mean cosine).
    pub fn g(&self) -> f32 {
        self.g
    }

    /// Density per steradian for the cosine between propagation directions.
    #[inline]
    pub fn eval(&self, cos: f32) -> f32 {
        let g = self.g;
        let denom = (1.0 + g * g - 2.0 * g * cos).max(1e-12);
        (1.0 - g) * (1.0 + g) / (4.0 * PI * denom * denom.sqrt())
    }

    /// [`HenyeyGreenstein::eval`] in f64: accurate at the forward peak of |g| -> 1, where the f32
    /// form loses digits in `1 + g² - 2 g cos` (mixtures that carry such lobes use this).
    #[inline]
    pub fn eval64(&self, mu: f64) -> f64 {
        let g = self.g as f64;
        let denom = (1.0 + g * g - 2.0 * g * mu).max(1e-300);
        (1.0 - g) * (1.0 + g) / (4.0 * std::f64::consts::PI * denom * denom.sqrt())
    }

    /// The exact inverse CDF in f64 (the textbook form, which is well conditioned in f64 for
    /// every |g| >= 1e-6; below that the uniform cosine, exact to 1e-12).
    #[inline]
    pub fn sample_cos64(&self, xi: f64) -> f64 {
        let g = self.g as f64;
        if g.abs() < 1e-6 {
            return (2.0 * xi - 1.0).clamp(-1.0, 1.0);
        }
        let s = (1.0 - g) * (1.0 + g) / (1.0 - g + 2.0 * g * xi);
        ((1.0 + g * g - s * s) / (2.0 * g)).clamp(-1.0, 1.0)
    }

    /// Value for a camera ray of direction `u` gathering light that travels along `v`.
    #[inline]
    pub fn eval_uv(&self, u: Vec3, v: Vec3) -> f32 {
        self.eval(-u.dot(v))
    }

    /// Samples the cosine from a uniform `xi` in [0, 1), exactly (inverse CDF).
    ///
    /// Two algebraically equal forms of the inverse, each used where it is well conditioned:
    /// the textbook `(1 + g² - s²)/(2g)`, `s = (1-g²)/(1-g+2g xi)`, cancels for small |g| (error
    /// ~ eps/|g|), so below `G_SMALL` it is rearranged (t = 2 xi - 1) into a form without the
    /// 1/g that is continuous at g = 0 (`cos = t`); that form in turn cancels near cos = 1 when
    /// |g| -> 1, where the textbook form is accurate.
    #[inline]
    pub fn sample_cos(&self, xi: f32) -> f32 {
        let g = self.g;
        let t = 2.0 * xi - 1.0;
        let c = if g.abs() < G_SMALL {
            let d = 1.0 + g * t;
            (t + 0.5 * g * (3.0 - g * g + t * t * (1.0 + g * g) + 2.0 * g * t)) / (d * d)
        } else {
            let s = (1.0 - g) * (1.0 + g) / (1.0 + g * t);
            (1.0 + g * g - s * s) / (2.0 * g)
        };
        c.clamp(-1.0, 1.0)
    }

    /// Samples a new propagation direction given the incoming propagation direction `w`
    /// (unit). The pdf of the result is `eval(w.dot(result))`. The same routine serves camera
    /// paths (pass the camera ray direction: HG is symmetric under reversing both directions).
    #[inline]
    pub fn sample_dir(&self, w: Vec3, xi1: f32, xi2: f32) -> Vec3 {
        let cos = self.sample_cos(xi1);
        let sin = (1.0 - cos * cos).max(0.0).sqrt();
        let (a, b) = w.any_orthonormal_pair();
        let phi = 2.0 * PI * xi2;
        let (sp, cp) = phi.sin_cos();
        (w * cos + a * (sin * cp) + b * (sin * sp)).normalize()
    }
}
