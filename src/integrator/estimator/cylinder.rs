//! The integration cylinder of paper eq. 2 (method note 5a): the camera path leaves one cylinder
//! over its whole medium segment and, in `first-extinction` mode, passes through it with the
//! deterministic transmittance `e^{-st_l T}` instead of sampling an extinction. A forward segment
//! whose chord crosses it adds `ss_l f Phi_l / (pi R^2) * ∫_chord e^{-st_l tau(lam)} dlam`. Also
//! the cylinder geometry that truncated and long cylinders share.

use glam::Vec3;
use obvhs::aabb::Aabb;
use rand::Rng;
use std::f32::consts::PI;

use super::{
    CameraSegment, ForwardSegment, VolumeEstimator, capsule_bounds, chord_integral, panels_for,
    times_phase,
};
use crate::integrator::record::{SegmentRecord, VolumeRecord};
use crate::medium::{Medium, Mixture, WalkEnd, sample_extinction};
use crate::spectrum::Spectrum;

/// Paper eq. 2: deterministic camera transmittance over the whole segment.
#[derive(Clone, Copy, Debug)]
pub struct Cylinder;

impl VolumeEstimator for Cylinder {
    const WHOLE_FORWARD_SEGMENT: bool = false;

    #[inline]
    fn camera_segment<R: Rng + ?Sized>(
        &self,
        cam: &CameraSegment,
        rng: &mut R,
        leave: impl FnMut(f32, f32),
    ) -> WalkEnd {
        whole_segment(cam, rng, leave)
    }

    #[inline]
    fn bounds(&self, seg: &SegmentRecord, v: &VolumeRecord, radius: f32) -> Aabb {
        piece_bounds(seg, v, radius)
    }

    #[inline]
    fn contribution(
        &self,
        f: &ForwardSegment,
        seg: &SegmentRecord,
        v: &VolumeRecord,
        _w: &[f32],
        med: &Medium,
        radius: f32,
    ) -> Option<Spectrum> {
        let chord = segment_cylinder(&CameraAxis::of(seg, v), radius, f.o, f.d, f.len)?;
        let k = match f.flight {
            Some(fl) => cylinder_eq2_fwd(med, fl.mixture(), &chord, radius),
            None => cylinder_eq2(med, &chord, radius),
        };
        Some(times_phase(*f.flux * k, med, -f.d.dot(seg.dir)))
    }
}

/// The camera side of the cylinders over whole segments (eq. 2 and eq. 3): one cylinder over
/// `[0, len]`; the path passes through with the deterministic transmittance in
/// `first-extinction` mode, and samples where it scatters on in `see-through` mode (where the
/// cylinder gathers only class C light and the path goes on gathering nothing).
#[inline]
pub(super) fn whole_segment<R: Rng + ?Sized>(
    cam: &CameraSegment,
    rng: &mut R,
    leave: impl FnMut(f32, f32),
) -> WalkEnd {
    leave_pieces(cam, cam.len, leave);
    if cam.first_extinction {
        WalkEnd::Transmitted {
            weight: cam.medium.sigma_t.transmittance(cam.len, cam.medium.n),
        }
    } else {
        sample_extinction(cam.medium, (cam.mix, cam.track), cam.len, rng)
    }
}

/// Most pieces one cylinder is cut into (a bound for absurd radii; see `leave_pieces`).
const MAX_PIECES: usize = 4096;

/// Leaves the cylinder over `[0, len]` of a camera segment as pieces `(end, start)` short
/// enough that their bounding boxes stay tight: a long cylinder at an angle to the axes has a
/// box far larger than itself, which every forward ray nearby must then be tested against (in
/// the fog room, eq. 2 cylinders took minutes per pass). A piece's box grows by `|u_mid| L`
/// across its axis (`u_mid` the middle one of the direction's components): pieces of
/// `L = 4 R / |u_mid|` keep that growth within 4 radii. Axis-aligned cylinders stay whole. The
/// pieces partition the cylinder, so their contributions add up exactly to its own.
pub(super) fn leave_pieces(cam: &CameraSegment, len: f32, mut leave: impl FnMut(f32, f32)) {
    let mut c = cam.dir.abs().to_array();
    c.sort_by(f32::total_cmp);
    let n = if cam.radius > 0.0 && len.is_finite() {
        ((len * c[1] / (4.0 * cam.radius)).ceil() as usize).clamp(1, MAX_PIECES)
    } else {
        1
    };
    let step = len / n as f32;
    for k in 0..n {
        let end = if k + 1 == n {
            len
        } else {
            (k + 1) as f32 * step
        };
        leave(end, k as f32 * step);
    }
}

/// The box of a cylinder piece (`v.scale` its start along the segment, `v.s` its end).
#[inline]
pub(super) fn piece_bounds(seg: &SegmentRecord, v: &VolumeRecord, radius: f32) -> Aabb {
    capsule_bounds(seg.at(v.scale), seg.at(v.s), radius)
}

/// The axis of an integration cylinder (or a piece of one): a camera segment in a medium.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CameraAxis {
    /// Where the camera segment starts (tau = 0).
    pub origin: Vec3,
    /// Unit direction `u` (camera -> scene).
    pub dir: Vec3,
    /// Axial range `[start, len]` of the cylinder (finite; `start = 0` for a whole one).
    pub start: f32,
    pub len: f32,
}

impl CameraAxis {
    /// The axis of the cylinder piece `v` of camera segment `seg`: `[v.scale, v.s]` along it.
    #[inline]
    pub fn of(seg: &SegmentRecord, v: &VolumeRecord) -> Self {
        Self {
            origin: seg.origin,
            dir: seg.dir,
            start: v.scale,
            len: v.s,
        }
    }
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
/// radius `r` around `axis` (axial range `[axis.start, axis.len]`). `None` when they do not
/// overlap.
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
        let l1 = (axis.start - a0) * inv;
        let l2 = (axis.len - a0) * inv;
        lo = lo.max(l1.min(l2));
        hi = hi.min(l1.max(l2));
    } else if a0 < axis.start || a0 > axis.len {
        return None;
    }
    if lo.is_nan() || hi.is_nan() || lo >= hi {
        return None;
    }
    Some(CylinderChord {
        lam1: lo,
        lam2: hi,
        tau1: (a0 + uv * lo).clamp(axis.start, axis.len),
        tau2: (a0 + uv * hi).clamp(axis.start, axis.len),
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
pub fn cylinder_eq2(medium: &Medium, chord: &CylinderChord, r: f32) -> Spectrum {
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

/// Eq. 2 (deterministic camera transmittance `e^{-st_l tau}`) for a colour forward flight whose
/// flux at `lam` is `Phi_l e^{-st_l lam} / Tmix_fwd(lam)` (see `medium::ForwardFlight`): the
/// closed form of `cylinder_eq2` assumes constant flux along the chord and is biased by
/// O(chord x sigma_t spread) here. Composite Gauss–Legendre.
#[inline]
pub fn cylinder_eq2_fwd(medium: &Medium, fwd: &Mixture, chord: &CylinderChord, r: f32) -> Spectrum {
    if fwd.sigma_t_span() == 0.0 {
        // Grey forward flight: its flux is constant along the chord, eq. 2's closed form is exact.
        return cylinder_eq2(medium, chord, r);
    }
    let k = 1.0 / (PI * r * r);
    let c = chord.len();
    let st_max = medium.sigma_t.max_value();
    let span = st_max * (chord.tau2 - chord.tau1).abs() + fwd.sigma_t_span() * c;
    let n = medium.n;
    let integral = chord_integral(c, panels_for(span), |x| {
        let tau = chord.tau1 + chord.uv * x;
        let mut cw = medium.sigma_t.transmittance(tau, n);
        cw *= fwd.survival_weight(chord.lam1 + x);
        cw
    });
    medium.sigma_s * integral * k
}
