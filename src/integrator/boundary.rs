//! The surfaces that bound a camera segment, as planes its integration spheres are clipped by.
//!
//! A sphere of radius R within R of the floor a camera ray ends on reaches through it, where no
//! forward ray travels: the track-length estimator `chord / ((4/3) pi R^3)` then averages a
//! fluence that is zero over the part below, and reads the medium near every opaque surface low
//! (by half at the surface; the 1-2 % deficit of height fog over a floor in docs/media.md). The
//! estimator is unbiased for the mean fluence over ANY region that contains the centre, given
//! the region's volume: `E[sum of chords inside V'] = integral over V' of the fluence`. So a
//! sphere near its segment's bounding surfaces integrates over the ball cut by their tangent
//! planes instead: the forward chords are clipped to the half-spaces on the medium's side, and
//! the weight divides by the cut ball's volume (`V - caps`). Where the planes are the surfaces
//! (flat floors, walls, box faces) the loss is gone; a curved surface is replaced by its tangent
//! plane at the camera ray's hit. docs/media.md, "Spheres at surfaces", has the derivation.
//!
//! The planes are those of the segment's two ends, found by the camera path: where it entered
//! the medium (the surface it left, if any) and where its ray leaves it (the surface it hits).
//! A segment's planes are kept apart from its record, and only for segments with a sphere within
//! the pass's largest radius of one ([`PlaneTable`]); such a sphere carries its scale negated
//! (`VolumeRecord::near_boundary`), so that the gather's hot loop looks the planes up only for
//! it. Inside the segment record (20 bytes more) they cost fog-cube's light pass 12 %.
//!
//! A face through which the gather counts the other side's forward rays (an index-matched
//! boundary of an open medium, method note 8) is no boundary of the fluence: the end looks
//! through it to the next real surface within [`LOOK_THROUGH`] radii (a fog box standing 1 mm
//! above a floor ends at the floor), and such a start is no plane. A sphere near a surface its
//! segment does not end on (a wall beside a grazing ray) is not clipped; cylinders are not
//! clipped at all.

use glam::Vec3;

use super::oct::Oct;
use crate::geometry::{Hit, Ray, spawn};
use crate::world::Scene;

/// How far beyond an index-matched end face (in radii, along the ray) a real surface is looked
/// for: one further away is within a radius of the segment's last sphere only at incidences
/// below 1/8 rad (7 degrees) from its plane.
pub const LOOK_THROUGH: f32 = 8.0;

/// Null faces crossed at most while looking through.
const MAX_FACES: u32 = 4;

/// The smallest fraction of a ball kept: a guard against rounding in a cut of two nearly
/// coincident planes, where the chords inside are tiny too.
const MIN_FRACTION: f32 = 1.0 / 64.0;

/// Slices of the midpoint rule per piece of the volume two caps share.
const OVERLAP_SLICES: u32 = 16;

/// The surface a camera path last left (or crossed): the start plane of its next medium
/// segment.
#[derive(Clone, Copy, Debug)]
pub struct Entered {
    pub p: Vec3,
    /// The surface's normal on the side the path went on to.
    pub n: Vec3,
    /// An index-matched boundary (no material).
    pub null: bool,
}

impl Entered {
    /// The surface of `hit` left along `dir`.
    pub fn new(hit: &Hit, dir: Vec3, null: bool) -> Self {
        let n = if hit.ng.dot(dir) >= 0.0 {
            hit.ng
        } else {
            -hit.ng
        };
        Self { p: hit.p, n, null }
    }
}

/// A camera segment's bounding planes (none: infinite distances). Both normals point into the
/// medium; a point `x` is kept where `n.(x - p) >= 0`.
#[derive(Clone, Copy, Debug)]
pub struct Planes {
    /// `n0 . dir` (> 0) of the start plane, which passes through the segment's origin.
    start_cos: f32,
    start_n: Oct,
    /// Distance along the segment to the end plane's point (its `-n1 . dir` is recomputed
    /// from the normal: 16 bytes per segment keep the gather within 64 bytes per sphere).
    end: f32,
    end_n: Oct,
}

impl Planes {
    /// No plane: spheres are whole balls.
    pub const NONE: Planes = Planes {
        start_cos: f32::INFINITY,
        start_n: Oct::ZERO,
        end: f32::INFINITY,
        end_n: Oct::ZERO,
    };

    /// The planes of the camera segment along `ray` in medium `m`, which ends at `end` (None:
    /// the world's edge) and starts at `from` (None: the camera, or a scattering in the
    /// medium); `radius` is the pass's largest gather radius.
    pub fn of_segment(
        scene: &Scene,
        m: u32,
        ray: &Ray,
        (from, end): (Option<&Entered>, Option<&Hit>),
        radius: f32,
    ) -> Planes {
        let open = scene.open_medium(m);
        let mut planes = Planes::NONE;
        if let Some(f) = from.filter(|f| !(f.null && open)) {
            let cos = f.n.dot(ray.d);
            if cos > 0.0 {
                planes.start_cos = cos;
                planes.start_n = Oct::encode(f.n);
            }
        }
        if let Some((t, ng)) = end.and_then(|h| end_surface(scene, open, ray, h, radius)) {
            let n = if ng.dot(ray.d) <= 0.0 { ng } else { -ng };
            let cos = -n.dot(ray.d);
            if cos > 0.0 {
                planes.end = t;
                planes.end_n = Oct::encode(n);
            }
        }
        planes
    }

    /// The distances of a sphere at `s` along the segment along `dir` from the start and end
    /// planes (NaN or infinite without one: never within a radius).
    #[inline]
    fn distances(&self, s: f32, dir: Vec3) -> (f32, f32) {
        let d1 = if self.end.is_finite() {
            (self.end - s) * -self.end_n.decode().dot(dir)
        } else {
            f32::INFINITY
        };
        (s * self.start_cos, d1)
    }

    /// Whether a sphere at `s` along the segment along `dir` lies within `r` of a plane.
    #[inline]
    pub fn near(&self, s: f32, dir: Vec3, r: f32) -> bool {
        let (d0, d1) = self.distances(s, dir);
        d0 < r || d1 < r
    }

    /// Clips the forward chord `[lam_in, lam_out]` of `o + d lam` in the sphere of radius `r`
    /// at `s` along the segment from `origin` along `dir`: the chord inside the kept
    /// half-spaces and the kept fraction of the ball's volume, or None when nothing is left.
    #[inline]
    pub fn clip(
        &self,
        (origin, dir, s): (Vec3, Vec3, f32),
        (o, d): (Vec3, Vec3),
        (lam_in, lam_out): (f32, f32),
        r: f32,
    ) -> Option<(f32, f32, f32)> {
        let (d0, d1) = self.distances(s, dir);
        let (cut0, cut1) = (d0 < r, d1 < r);
        if !cut0 && !cut1 {
            return Some((lam_in, lam_out, 1.0));
        }
        let (mut lo, mut hi, mut fraction) = (lam_in, lam_out, 1.0);
        let n0 = cut0.then(|| self.start_n.decode());
        let n1 = cut1.then(|| self.end_n.decode());
        if let Some(n0) = n0 {
            (lo, hi) = keep(n0, origin, (o, d), (lo, hi));
            fraction -= cap_fraction(d0 / r);
        }
        if let Some(n1) = n1 {
            (lo, hi) = keep(n1, origin + dir * self.end, (o, d), (lo, hi));
            fraction -= cap_fraction(d1 / r);
        }
        if let (Some(n0), Some(n1)) = (n0, n1) {
            // Both caps were taken away: add back the part they share.
            fraction += overlap_fraction((d0 / r, n0), (d1 / r, n1));
        }
        (lo < hi).then_some((lo, hi, fraction.max(MIN_FRACTION)))
    }
}

/// The planes of the segments that have a sphere near one (`VolumeRecord::near_boundary`),
/// by segment index: only such spheres read them, and most segments have none, so they are
/// kept sparse (at q = 1 a dense table would cost the gather 16 of its 64 bytes per sphere).
#[derive(Clone, Debug, Default)]
pub struct PlaneTable(Vec<(u32, Planes)>);

impl PlaneTable {
    /// Adds segment `segment`'s planes; segments come in increasing order.
    pub fn push(&mut self, segment: u32, planes: Planes) {
        debug_assert!(self.0.last().is_none_or(|&(s, _)| s < segment));
        self.0.push((segment, planes));
    }

    /// Appends `other`, whose segments are numbered from `base` on in this table's numbering.
    pub fn append(&mut self, other: PlaneTable, base: u32) {
        self.0
            .extend(other.0.into_iter().map(|(s, p)| (s + base, p)));
    }

    /// Renumbers the segments (`new_index[old]`, u32::MAX for one that is dropped).
    pub fn renumber(&mut self, new_index: &[u32]) {
        self.0.retain_mut(|(s, _)| {
            *s = new_index.get(*s as usize).copied().unwrap_or(u32::MAX);
            *s != u32::MAX
        });
        self.0.sort_unstable_by_key(|&(s, _)| s);
    }

    /// The planes of `segment` (none if it has none).
    #[inline]
    pub fn of(&self, segment: u32) -> &Planes {
        match self.0.binary_search_by_key(&segment, |&(s, _)| s) {
            Ok(i) => &self.0[i].1,
            Err(_) => &Planes::NONE,
        }
    }

    /// Bytes held.
    pub fn bytes(&self) -> usize {
        self.0.len() * size_of::<(u32, Planes)>()
    }
}

/// The distance along `ray` and the normal of the surface that bounds the fluence of medium
/// `m` at the segment's end `hit`: the hit itself, unless it is an index-matched face of an
/// open medium, which is looked through (up to `LOOK_THROUGH` radii) to the next surface with a
/// material.
fn end_surface(
    scene: &Scene,
    open: bool,
    ray: &Ray,
    hit: &Hit,
    radius: f32,
) -> Option<(f32, Vec3)> {
    let real = |h: &Hit| scene.geometry.shape(h.shape).material.is_some();
    if real(hit) || !open {
        return Some((hit.t, hit.ng));
    }
    let (mut t, mut left) = (hit.t, LOOK_THROUGH * radius);
    let mut next = spawn(hit.p, hit.ng, ray.d);
    for _ in 0..MAX_FACES {
        let h = scene.geometry.intersect(&next, left)?;
        t += h.t;
        if real(&h) {
            return Some((t, h.ng));
        }
        left -= h.t;
        next = spawn(h.p, h.ng, ray.d);
    }
    None
}

/// The part of `[lo, hi]` along `o + d lam` where `n.(x - p) >= 0`.
#[inline]
fn keep(n: Vec3, p: Vec3, (o, d): (Vec3, Vec3), (lo, hi): (f32, f32)) -> (f32, f32) {
    let g0 = n.dot(o - p);
    let gd = n.dot(d);
    if gd > 0.0 {
        (lo.max(-g0 / gd), hi)
    } else if gd < 0.0 {
        (lo, hi.min(-g0 / gd))
    } else if g0 >= 0.0 {
        (lo, hi)
    } else {
        (hi, hi)
    }
}

/// The fraction of a ball's volume in the cap beyond a plane at `delta` radii from its centre
/// (`pi h^2 (3R - h) / 3` over `(4/3) pi R^3`, `h = R (1 - delta)`): 1/2 at the centre, 0 at
/// a radius.
#[inline]
pub fn cap_fraction(delta: f32) -> f32 {
    let delta = delta.clamp(0.0, 1.0);
    let e = 1.0 - delta;
    e * e * (2.0 + delta) * 0.25
}

/// The fraction of a unit ball beyond both planes `n0.x = -delta0` and `n1.x = -delta1` (each
/// cap the side its normal points away from), by slices across the first cap: at depth `h`
/// into it the slice is a disc of radius `sqrt(1 - h^2)`, and the second plane cuts a segment
/// of it whose area has a closed form. The segment's area has kinks where the second plane
/// touches the slice's disc (`h = -a delta1 +- b sqrt(1 - delta1^2)`), so the depth range is cut
/// there and each piece takes a midpoint rule. Zero when the caps do not meet.
fn overlap_fraction((delta0, n0): (f32, Vec3), (delta1, n1): (f32, Vec3)) -> f32 {
    let u = -n0;
    // n1 = a u + b w, w a unit vector across u.
    let a = n1.dot(u);
    let b = (1.0 - a * a).max(0.0).sqrt().max(1e-6);
    let (delta0, delta1) = (delta0.clamp(0.0, 1.0), delta1.clamp(0.0, 1.0));
    let slice = |h: f32| {
        let rho2 = 1.0 - h * h;
        if rho2 <= 0.0 {
            return 0.0;
        }
        // Beyond the second plane: n1.x = a h + b (w.y) < -delta1, i.e. w.y < c.
        let c = (-delta1 - a * h) / b;
        rho2 * disc_below(c / rho2.sqrt())
    };
    let half = b * (1.0 - delta1 * delta1).sqrt();
    let mut cuts = [delta0, -a * delta1 - half, -a * delta1 + half, 1.0];
    for c in &mut cuts[1..3] {
        *c = c.clamp(delta0, 1.0);
    }
    let mut sum = 0.0;
    for piece in cuts.windows(2) {
        let step = (piece[1] - piece[0]) / OVERLAP_SLICES as f32;
        for i in 0..OVERLAP_SLICES {
            sum += slice(piece[0] + (i as f32 + 0.5) * step) * step;
        }
    }
    sum * 3.0 / (4.0 * std::f32::consts::PI)
}

/// The area of the unit disc where `x < t`.
#[inline]
fn disc_below(t: f32) -> f32 {
    let t = t.clamp(-1.0, 1.0);
    t * (1.0 - t * t).max(0.0).sqrt() + t.asin() + std::f32::consts::FRAC_PI_2
}

#[cfg(test)]
mod tests;
