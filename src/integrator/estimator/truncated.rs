//! The truncated integration cylinder (method note 5b): the camera side samples its real
//! extinction as a single-sphere path would and leaves a cylinder from the segment's start to
//! it (to the segment's end when transmitted); dividing by the survival probability, a forward
//! chord adds `ss_l f Phi_l / (pi R^2) * ∫_chord e^{-st_l tau} / Tmix(tau) dlam`. It is the
//! q -> 0 limit of multiple spheres.

use obvhs::aabb::Aabb;
use rand::Rng;
use std::f32::consts::PI;

use super::cylinder::{leave_pieces, piece_bounds};
use super::dense::cylinder_truncated_density;
use super::{
    CameraAxis, CameraSegment, CylinderChord, ForwardSegment, VolumeEstimator, chord_integral,
    panels_for, segment_cylinder, times_phase,
};
use crate::integrator::boundary::PlaneTable;
use crate::integrator::record::{SegmentRecord, VolumeRecord};
use crate::integrator::settings::Channels;
use crate::medium::{Medium, Mixture, WalkEnd, sample_extinction};
use crate::spectrum::Spectrum;

/// Cylinders ending at the sampled extinction; the gather rebuilds each camera segment's
/// mixture from its throughput with the camera pass's rule.
#[derive(Clone, Copy, Debug)]
pub struct TruncatedCylinder {
    channels: Channels,
}

impl TruncatedCylinder {
    pub fn new(channels: Channels) -> Self {
        Self { channels }
    }
}

impl VolumeEstimator for TruncatedCylinder {
    const WHOLE_FORWARD_SEGMENT: bool = false;
    const PIECES: bool = true;

    #[inline]
    fn camera_segment<R: Rng + ?Sized>(
        &self,
        cam: &CameraSegment,
        rng: &mut R,
        leave: impl FnMut(f32, f32),
    ) -> WalkEnd {
        let end = sample_extinction(cam.medium, (cam.mix, cam.track), cam.len, rng);
        let len = match end {
            WalkEnd::Scattered { s, .. } | WalkEnd::Absorbed { s } => s,
            WalkEnd::Transmitted { .. } => cam.len,
        };
        leave_pieces(cam, len, leave);
        end
    }

    #[inline]
    fn bounds(&self, seg: &SegmentRecord, v: &VolumeRecord, radius: f32) -> Aabb {
        piece_bounds(seg, v, radius)
    }

    #[inline]
    fn contribution(
        &self,
        f: &ForwardSegment,
        (seg, _): (&SegmentRecord, &PlaneTable),
        v: &VolumeRecord,
        w: &[f32],
        med: &Medium,
        radius: f32,
    ) -> Option<Spectrum> {
        let chord = segment_cylinder(&CameraAxis::of(seg, v), radius, f.o, f.d, f.len)?;
        let cam = self.channels.mixture(&Spectrum::from_slice(w), med);
        let k = if med.density.is_uniform() {
            let fwd = f.flight.map(|fl| fl.mixture());
            cylinder_truncated(med, &cam, fwd, &chord, radius)
        } else {
            let fwd = f.flight.map(|fl| (fl.mixture(), f.along));
            cylinder_truncated_density(med, seg, &cam, fwd, &chord, radius)
        };
        Some(times_phase(*f.flux * k, med, -f.d.dot(seg.dir)))
    }
}

/// Truncated cylinder (method note 5b), per bin: `ss_l / (pi R^2) * ∫_chord Tr_l(tau) B_l(lam)
/// dlam` with the camera-side `Tr_l(tau) = e^{-st_l tau} / Tmix(tau)` of the camera segment's
/// mixture `cam` (the cylinder ends at the sampled extinction, or at T if transmitted) and the
/// forward-side factor `B_l(lam) = e^{-st_l lam} / Tmix_fwd(lam)` if `fwd` is given (a colour
/// forward flight, `lam` measured from the forward segment's origin), else 1. Multiply by
/// `f(-u.v) Phi_l W_l` (Phi at the forward segment's start).
///
/// When both sides are grey (all bins share sigma_t) this is the exact `ss chord / (pi R^2)`;
/// otherwise composite 4-point Gauss–Legendre.
#[inline]
pub fn cylinder_truncated(
    medium: &Medium,
    cam: &Mixture,
    fwd: Option<&Mixture>,
    chord: &CylinderChord,
    r: f32,
) -> Spectrum {
    let k = 1.0 / (PI * r * r);
    let c = chord.len();
    let (cam_span, fwd_span) = (cam.sigma_t_span(), fwd.map_or(0.0, |m| m.sigma_t_span()));
    if cam_span == 0.0 && fwd_span == 0.0 {
        // Grey: every survival ratio is 1.
        return medium.sigma_s * (k * c);
    }
    let span = cam_span * (chord.tau2 - chord.tau1).abs() + fwd_span * c;
    let integral = chord_integral(c, panels_for(span), |x| {
        let tau = chord.tau1 + chord.uv * x;
        let cw = cam.survival_weight(tau);
        match fwd {
            Some(m) => cw * m.survival_weight(chord.lam1 + x),
            None => cw,
        }
    });
    medium.sigma_s * integral * k
}
