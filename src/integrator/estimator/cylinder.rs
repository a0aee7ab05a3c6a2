//! The integration cylinder of paper eq. 2 (method note 5a): the camera path leaves one cylinder
//! over its whole medium segment and, in `first-extinction` mode, passes through it with the
//! deterministic transmittance `e^{-st_l T}` instead of sampling an extinction. A forward segment
//! whose chord crosses it adds `ss_l f Phi_l / (pi R^2) * ∫_chord e^{-st_l tau(lam)} dlam`. Also
//! the camera side and piece boxes that truncated and long cylinders share (their geometry is
//! `chord.rs`).

use obvhs::aabb::Aabb;
use rand::Rng;
use std::f32::consts::PI;

use super::chord::{CameraAxis, CylinderChord, segment_cylinder};
use super::dense::cylinder_eq2_density;
use super::quadrature::phi1;
use super::{
    CameraSegment, ForwardSegment, VolumeEstimator, capsule_bounds, chord_integral, panels_for,
    times_phase,
};
use crate::integrator::boundary::PlaneTable;
use crate::integrator::record::{SegmentRecord, VolumeRecord};
use crate::medium::{Medium, Mixture, WalkEnd, sample_extinction};
use crate::spectrum::Spectrum;

/// Paper eq. 2: deterministic camera transmittance over the whole segment.
#[derive(Clone, Copy, Debug)]
pub struct Cylinder;

impl VolumeEstimator for Cylinder {
    const WHOLE_FORWARD_SEGMENT: bool = false;
    const PIECES: bool = true;

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
        (seg, _): (&SegmentRecord, &PlaneTable),
        v: &VolumeRecord,
        _w: &[f32],
        med: &Medium,
        radius: f32,
    ) -> Option<Spectrum> {
        let chord = segment_cylinder(&CameraAxis::of(seg, v), radius, f.o, f.d, f.len)?;
        let k = match f.flight {
            _ if !med.density.is_uniform() => {
                let fwd = f.flight.map(|fl| (fl.mixture(), f.along));
                cylinder_eq2_density(med, seg, &chord, fwd, radius)
            }
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

/// Leaves the cylinder over `[0, len]` of a camera segment (`len` in the segment's optical
/// depth at density 1, `CameraSegment::len`) as pieces `(end, start)`, distances along the
/// segment, short enough that their bounding boxes stay tight: a long cylinder at an angle to
/// the axes has a box far larger than itself, which every forward ray nearby must then be
/// tested against (in the fog room, eq. 2 cylinders took minutes per pass). A piece's box grows
/// by `|u_mid| L` across its axis (`u_mid` the middle one of the direction's components): pieces
/// of `L = 4 R / |u_mid|` keep that growth within 4 radii. Axis-aligned cylinders stay whole.
/// The pieces partition the cylinder, so their contributions add up exactly to its own. In a
/// density field the pieces are cut in distance (the box is geometry), through the segment's
/// change of variable.
pub(super) fn leave_pieces(cam: &CameraSegment, len: f32, mut leave: impl FnMut(f32, f32)) {
    let len = if cam.along.is_identity() {
        len
    } else {
        cam.along.distance(len)
    };
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::medium::density::Height;
    use crate::medium::{ChannelPick, Density};
    use glam::Vec3;

    const R: f32 = 0.05;

    /// Height fog whose `up` is tilted from the segment, so that depth and distance differ.
    fn fog() -> Medium {
        let n = 2;
        Medium::new(&Spectrum::splat(0.8, n), &Spectrum::splat(0.2, n), 0.0, n)
            .unwrap()
            .with_density(Density::Height(Height::new(
                0.0,
                0.7,
                Vec3::new(0.0, 0.6, 0.8),
            )))
    }

    /// In a density field the pieces are cut in distance: they tile `[0, distance(len)]`, and
    /// none is longer than the uniform rule allows.
    #[test]
    fn pieces_tile_the_segment_in_distance() {
        let med = fog();
        let (origin, dir) = (
            Vec3::new(0.1, -0.3, 0.2),
            Vec3::new(0.2, 0.3, 1.0).normalize(),
        );
        let along = med.density.along(origin, dir);
        let mix = Mixture::new(ChannelPick::Uniform, &Spectrum::splat(1.0, 2), &med, 0.1);
        let len = 2.5f32;
        let cam = CameraSegment {
            medium: &med,
            medium_id: 0,
            dir,
            radius: R,
            mix: &mix,
            track: None,
            len: along.depth(len),
            along: &along,
            first_extinction: true,
        };
        let mut pieces = Vec::new();
        leave_pieces(&cam, cam.len, |end, start| pieces.push((start, end)));
        let mut c = dir.abs().to_array();
        c.sort_by(f32::total_cmp);
        let longest = 4.0 * R / c[1];
        assert!(pieces.len() > 1);
        assert_eq!(pieces[0].0, 0.0);
        assert!((pieces.last().unwrap().1 - len).abs() < 1e-4 * len);
        for w in pieces.windows(2) {
            assert_eq!(w[0].1, w[1].0);
        }
        for (a, b) in pieces {
            assert!(b > a && b - a <= longest * 1.0001, "{a}..{b}");
        }
    }
}
