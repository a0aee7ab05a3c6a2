//! The geometry every integration cylinder shares: its axis (a camera segment, or a piece of
//! one) and the chord a forward segment cuts through it.

use glam::Vec3;

use crate::integrator::record::{SegmentRecord, VolumeRecord};

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
