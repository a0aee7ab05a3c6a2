use crate::medium::HomogeneousMedium;
use crate::spectrum::Spectrum;
use glam::Vec3;
use std::f32::consts::PI;

/// The axis of an integration cylinder: a camera segment in a medium.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CameraAxis {
    /// Where the camera segment starts (tau = 0).
    pub origin: Vec3,
    /// Unit direction `u` (camera -> scene).
    pub dir: Vec3,
    /// Axial length `T` (finite).
    pub len: f32,
}

/// The part of a forward segment inside a finite, flat-capped cylinder.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CylinderChord {
    /// Entry and exit distances along the forward segment (`lam1 <= lam2`).
    pub lam1: f32,
    pub lam2: f32,
    /// Axial positions (along the camera axis) of the entry and exit points; `tau2 < tau1` when
    /// the forward ray moves towards the camera.
    pub tau1: f32,
    pub tau2: f32,
    /// Signed `u . v`.
    pub uv: f32,
}

impl CylinderChord {
    /// Chord length `lam2 - lam1`.
    pub fn len(&self) -> f32 {
        self.lam2 - self.lam1
    }

    /// True for a zero-length chord.
    pub fn is_empty(&self) -> bool {
        self.lam2 <= self.lam1
    }

    /// `mu = |u . v|`.
    pub fn mu(&self) -> f32 {
        self.uv.abs()
    }

    /// The smaller axial position (the chord's point nearest the camera).
    pub fn tau_min(&self) -> f32 {
        self.tau1.min(self.tau2)
    }
}

/// Below this squared sine the forward ray is treated as parallel to the axis.
const PARALLEL_EPS: f32 = 1e-12;

/// Intersects the forward segment `o + v lam`, `lam in [0, len]` (`v` unit) with the cylinder of
/// radius `r` around `axis` (axial range `[0, axis.len]`). `None` when they do not overlap.
#[inline]
pub fn segment_cylinder(
    axis: &CameraAxis,
    r: f32,
    o: Vec3,
    v: Vec3,
    len: f32,
) -> Option<CylinderChord> {
    let u = axis.dir;
    let d = o - axis.origin;
    let a0 = d.dot(u);
    let uv = v.dot(u);
    let w0 = d - u * a0;
    let wv = v - u * uv;
    let a = wv.length_squared();
    let b = w0.dot(wv);
    let c = w0.length_squared() - r * r;
    let mut lo = 0.0f32;
    let mut hi = len;
    if a > PARALLEL_EPS {
        let disc = b * b - a * c;
        if disc.is_nan() || disc <= 0.0 {
            return None;
        }
        // Cancellation-free roots of a lam² + 2 b lam + c.
        let qq = -(b + disc.sqrt().copysign(b));
        let (r1, r2) = (qq / a, c / qq);
        lo = lo.max(r1.min(r2));
        hi = hi.min(r1.max(r2));
    } else if c > 0.0 {
        return None;
    }
    if uv != 0.0 {
        let inv = 1.0 / uv;
        let l1 = -a0 * inv;
        let l2 = (axis.len - a0) * inv;
        lo = lo.max(l1.min(l2));
        hi = hi.min(l1.max(l2));
    } else if a0 < 0.0 || a0 > axis.len {
        return None;
    }
    if lo.is_nan() || hi.is_nan() || lo >= hi {
        return None;
    }
    Some(CylinderChord {
        lam1: lo,
        lam2: hi,
        tau1: (a0 + uv * lo).clamp(0.0, axis.len),
        tau2: (a0 + uv * hi).clamp(0.0, axis.len),
        uv,
    })
}

/// `(1 - e^{-x}) / x`, accurate for all x >= 0 (and small negative x), 1 at x = 0.
#[inline]
pub(crate) fn phi1(x: f32) -> f32 {
    if x.abs() < 1e-4 {
        1.0 - 0.5 * x
    } else {
        -(-x).exp_m1() / x
    }
}

/// `∫_chord e^{-st tau(lam)} dlam` = `(e^{-st tau1} - e^{-st tau2}) / (st mu)`, evaluated as
/// `e^{-st tau_min} chord (1 - e^{-x}) / x` with `x = st chord mu`: finite and exact in the
/// limits mu -> 0 (a chord at constant depth) and st -> 0 (the chord length).
#[inline]
pub fn eq2_factor(st: f32, chord: &CylinderChord) -> f32 {
    let c = chord.len();
    (-st * chord.tau_min()).exp() * c * phi1(st * c * chord.mu())
}

/// Paper eq. 2 / method note 5a, per bin: `ss_l / (pi R^2) * eq2_factor(st_l)`, i.e.
/// `ss_l (e^{-st_l tau1} - e^{-st_l tau2}) / (st_l pi R^2 mu)`. Multiply by `f(-u.v) Phi_l W_l`.
/// Exact when the forward flux is constant along the chord (monochrome forward flights, or flux
/// that does not depend on position); see `cylinder_eq2_fwd` for colour forward flights.
#[inline]
pub fn cylinder_eq2(medium: &HomogeneousMedium, chord: &CylinderChord, r: f32) -> Spectrum {
    let k = 1.0 / (PI * r * r);
    if medium.grey {
        return medium.sigma_s * (k * eq2_factor(medium.sigma_t.0[0], chord));
    }
    let mut out = Spectrum::ZERO;
    for l in 0..medium.n {
        out.0[l] = medium.sigma_s.0[l] * k * eq2_factor(medium.sigma_t.0[l], chord);
    }
    out
}
