//! The integration-volume estimators (the paper, method notes 1-5), one file each:
//!
//! - `spheres.rs`: stochastic spheres along the camera segment, control parameter q (q = 1 is
//!   the single sphere at the extinction);
//! - `chord.rs`: the geometry the cylinders share (axis, chord of a forward segment);
//! - `cylinder.rs`: the cylinder over the whole segment with deterministic transmittance
//!   (paper eq. 2), and the camera side the other cylinders share;
//! - `truncated.rs`: the cylinder ending at the sampled extinction (note 5b);
//! - `long.rs`: paper eq. 3 in exact form (deterministic attenuation along forward segments);
//! - `dense.rs`: the three cylinders' gather weights in a medium with a density field.
//!
//! Each provides the three pieces of [`VolumeEstimator`]: what the camera side leaves on a medium
//! segment, the bounds the gather structure indexes, and what one forward segment contributes
//! to one volume. [`Estimator`] is the closed set; dispatching on it once per forward segment
//! (not per volume) keeps the per-volume code monomorphic.
//!
//! Conventions: the camera ray direction `u` points from the camera into the scene; a forward
//! ray travels along `v`; distances along the forward segment are `lam` (from its origin), along
//! the camera segment `tau`. The phase function is evaluated at `cos = -u.v` (light turning from
//! `v` towards the camera). The weight functions exclude the phase function, the forward flux
//! and the camera throughput unless they say otherwise.

mod chord;
mod cylinder;
mod dense;
mod long;
mod quadrature;
mod spheres;
mod truncated;

use glam::Vec3;
use obvhs::aabb::Aabb;
use rand::Rng;

use super::boundary::PlaneTable;
use super::record::{SegmentRecord, VolumeRecord};
use super::settings::{IntegratorDesc, VolumeKind};
use crate::medium::{Along, ForwardFlight, Medium, MediumError, Mixture, Tracker, WalkEnd};
use crate::spectrum::Spectrum;

pub use chord::{CameraAxis, CylinderChord, segment_cylinder};
pub use cylinder::{Cylinder, cylinder_eq2, cylinder_eq2_fwd, eq2_factor};
pub use dense::{cylinder_eq2_density, cylinder_truncated_density, long_eq3_density};
pub use long::{LongCylinder, long_eq3_exact};
pub use quadrature::{GL4_NODES, GL4_WEIGHTS, chord_integral, panels_for};
pub use spheres::{
    SphereChord, Spheres, crossing_density, segment_sphere, sphere_weight, track_length_density,
};
pub use truncated::{TruncatedCylinder, cylinder_truncated};

/// One camera segment in a medium, as the camera side of an estimator sees it.
pub struct CameraSegment<'a> {
    pub medium: &'a Medium,
    /// The medium's index in the scene.
    pub medium_id: u32,
    /// The segment's unit direction (camera -> scene).
    pub dir: Vec3,
    /// The pass's gather radius.
    pub radius: f32,
    /// The segment's spectral mixture (method note 3).
    pub mix: &'a Mixture,
    /// The null-collision tracker of a tracked medium (`medium::tracking`), None for the exact
    /// change of variable.
    pub track: Option<&'a Tracker<'a>>,
    /// Length to the surface or boundary ahead (may be `+inf`): in optical depth at density 1
    /// (the distance in a uniform medium), or the distance itself when `track` is Some.
    pub len: f32,
    /// The segment's change of variable `s -> u` (the identity in a uniform or tracked
    /// medium): cylinders cut their pieces in distance through it.
    pub along: &'a Along,
    /// The camera path ends at its first real extinction (`first-extinction` mode) rather than
    /// scattering on through the medium (`see-through`).
    pub first_extinction: bool,
}

/// A forward segment `o + d lam`, `lam in [0, len]`, being gathered.
pub struct ForwardSegment<'a> {
    pub o: Vec3,
    pub d: Vec3,
    pub len: f32,
    /// Flux at the segment's start.
    pub flux: &'a Spectrum,
    /// The flight when the flux changes along the segment (a colour flight in a chromatic
    /// medium); None for grey flights and outside media, where the flux is constant.
    pub flight: Option<&'a ForwardFlight>,
    /// The change of variable of the flight's medium along the segment (the flight samples
    /// in optical depth at density 1).
    pub along: &'a Along,
}

impl ForwardSegment<'_> {
    /// The flux at distance `lam` along the segment.
    #[inline]
    pub fn flux_at(&self, lam: f32) -> Spectrum {
        self.flight.map_or(*self.flux, |fl| {
            fl.flux_at(self.flux, self.along.depth(lam))
        })
    }
}

/// The three pieces every integration volume provides.
pub trait VolumeEstimator {
    /// Forward segments count along their whole length (not only up to their sampled
    /// collision), and only in the volume's own medium: paper eq. 3 integrates the forward
    /// attenuation itself.
    const WHOLE_FORWARD_SEGMENT: bool;

    /// The volumes are cylinder pieces: `leave(end, start)` gets both ends as distances along
    /// the segment. Otherwise (spheres) `leave(s, scale)` gets the sphere's optical depth at
    /// density 1 (`CameraSegment::len`'s unit), which the camera pass maps to its distance.
    const PIECES: bool;

    /// Leaves the volumes of one camera segment through `leave(s, scale)` (see `PIECES`: a
    /// position along the segment and a scalar the record keeps) and says how the path goes on.
    fn camera_segment<R: Rng + ?Sized>(
        &self,
        cam: &CameraSegment,
        rng: &mut R,
        leave: impl FnMut(f32, f32),
    ) -> WalkEnd;

    /// The box the gather structure indexes one volume by.
    fn bounds(&self, seg: &SegmentRecord, v: &VolumeRecord, radius: f32) -> Aabb;

    /// What forward segment `f` adds to volume `v` of camera segment `seg` (with the pass's
    /// table of bounding planes, which spheres near them read) in medium `med`, per bin, before the camera
    /// throughput `w` (which truncated cylinders also read); None when it misses the volume.
    fn contribution(
        &self,
        f: &ForwardSegment,
        seg: (&SegmentRecord, &PlaneTable),
        v: &VolumeRecord,
        w: &[f32],
        med: &Medium,
        radius: f32,
    ) -> Option<Spectrum>;

    /// [`Self::contribution`] at the radius `small`, below `large`, for a forward segment
    /// whose contribution at `large` is `at_large` (the blend of two radii, `film::blend`): an
    /// estimator may derive one from the other where they differ by a scalar.
    #[inline(always)]
    fn contribution_within(
        &self,
        f: &ForwardSegment,
        seg: (&SegmentRecord, &PlaneTable),
        v: &VolumeRecord,
        (w, med): (&[f32], &Medium),
        (large, at_large): (f32, &Spectrum),
        small: f32,
    ) -> Option<Spectrum> {
        let _ = (large, at_large);
        self.contribution(f, seg, v, w, med, small)
    }
}

/// The integration volume of a render (`integrator.volume`, with `q` for spheres).
#[derive(Clone, Debug)]
pub enum Estimator {
    Spheres(Spheres),
    Cylinder(Cylinder),
    TruncatedCylinder(TruncatedCylinder),
    LongCylinder(LongCylinder),
}

impl Estimator {
    /// The estimator the settings name, for a scene with `media` (spheres with `q[m]` in
    /// medium `m`).
    pub fn from_desc(
        desc: &IntegratorDesc,
        q: &[f32],
        media: &[Medium],
    ) -> Result<Self, MediumError> {
        Ok(match desc.volume {
            VolumeKind::Spheres => Estimator::Spheres(Spheres::new(q, media, desc.placement())?),
            VolumeKind::Cylinder => Estimator::Cylinder(Cylinder),
            VolumeKind::CylinderTruncated => {
                Estimator::TruncatedCylinder(TruncatedCylinder::new(desc.channels()))
            }
            VolumeKind::CylinderLong => Estimator::LongCylinder(LongCylinder),
        })
    }

    /// See [`VolumeEstimator::WHOLE_FORWARD_SEGMENT`].
    pub fn whole_forward_segment(&self) -> bool {
        match self {
            Estimator::Spheres(_) => Spheres::WHOLE_FORWARD_SEGMENT,
            Estimator::Cylinder(_) => Cylinder::WHOLE_FORWARD_SEGMENT,
            Estimator::TruncatedCylinder(_) => TruncatedCylinder::WHOLE_FORWARD_SEGMENT,
            Estimator::LongCylinder(_) => LongCylinder::WHOLE_FORWARD_SEGMENT,
        }
    }

    /// Bounds of a volume (for building the gather structure).
    pub fn bounds(&self, seg: &SegmentRecord, v: &VolumeRecord, radius: f32) -> Aabb {
        match self {
            Estimator::Spheres(e) => e.bounds(seg, v, radius),
            Estimator::Cylinder(e) => e.bounds(seg, v, radius),
            Estimator::TruncatedCylinder(e) => e.bounds(seg, v, radius),
            Estimator::LongCylinder(e) => e.bounds(seg, v, radius),
        }
    }
}

/// `value` times the phase function of `med` at `cos` (light along the forward ray turning
/// towards the camera: `cos = -u.v`): one number for all bins, or each bin's own when the
/// phase varies per bin (droplet fog, per-wavelength tables).
#[inline]
pub(crate) fn times_phase(value: Spectrum, med: &Medium, cos: f32) -> Spectrum {
    if med.phase.varies_per_bin() {
        value * med.phase_bins(cos)
    } else {
        value * med.phase.eval(cos)
    }
}

/// The box of the capsule around `[a, b]` (cylinders) or of the sphere at `b` (`a = b`).
pub(crate) fn capsule_bounds(a: Vec3, b: Vec3, radius: f32) -> Aabb {
    let r = glam::Vec3A::splat(radius);
    let (a, b) = (glam::Vec3A::from(a), glam::Vec3A::from(b));
    Aabb::new(a.min(b) - r, a.max(b) + r)
}
