use glam::Vec3;
use std::f32::consts::PI;

/// The part of a forward segment inside a sphere, in distances along the segment.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SphereChord {
    /// Entry, clipped to the segment (`>= 0`).
    pub lam_in: f32,
    /// Exit, clipped to the segment (`<= len`).
    pub lam_out: f32,
    /// True when the segment passes right through (starts and ends outside the sphere).
    pub full: bool,
}

impl SphereChord {
    /// Length of the part inside.
    pub fn len(&self) -> f32 {
        self.lam_out - self.lam_in
    }

    /// True for a zero-length chord.
    pub fn is_empty(&self) -> bool {
        self.lam_out <= self.lam_in
    }

    /// A point of the chord to evaluate position-dependent factors at (its middle).
    pub fn mid(&self) -> f32 {
        0.5 * (self.lam_in + self.lam_out)
    }
}

/// Intersects the forward segment `o + v lam`, `lam in [0, len]` (`v` unit) with the sphere of
/// centre `c` and radius `r`. `None` if they do not overlap.
#[inline]
pub fn segment_sphere(o: Vec3, v: Vec3, len: f32, c: Vec3, r: f32) -> Option<SphereChord> {
    let oc = o - c;
    let b = oc.dot(v);
    // Distance² of the line from the centre, computed from the perpendicular part directly so that
    // far-away origins do not cancel.
    let perp = oc - v * b;
    let h2 = r * r - perp.length_squared();
    if h2.is_nan() || h2 <= 0.0 {
        return None;
    }
    let h = h2.sqrt();
    let t0 = -b - h;
    let t1 = -b + h;
    let lam_in = t0.max(0.0);
    let lam_out = t1.min(len);
    if lam_in.is_nan() || lam_out.is_nan() || lam_in >= lam_out {
        return None;
    }
    Some(SphereChord {
        lam_in,
        lam_out,
        full: t0 >= 0.0 && t1 <= len,
    })
}

/// Fluence weight of one forward segment for a sphere of radius `r`, track-length form:
/// `chord_in / ((4/3) pi R^3)`. THE DEFAULT (method note 1, decided by
/// `tests/estimator_sphere_policy.rs`): its mean is exactly the ball-averaged fluence, for full
/// crossings, segments that end inside (forward extinctions) and segments that start inside
/// alike, so the only bias left is the O((sigma_t R)^2) blur of averaging over the ball. Its
/// cost over counting crossings: chord-length noise, +1/8 relative variance per full crossing.
#[inline]
pub fn track_length_density(chord: &SphereChord, r: f32) -> f32 {
    chord.len() * 3.0 / (4.0 * PI * r * r * r)
}

/// Fluence weight, crossing form: a full crossing counts `1/(pi R^2)`, a segment that starts or
/// ends inside counts its track length `chord/((4/3) pi R^3)`. Lower variance than
/// [`track_length_density`] but biased at first order: rays must survive to the far side to
/// count as crossings, so with forward extinction the mean is off by about `+0.08 sigma_t R`
/// (relative; +3% at sigma_t R = 0.5, measured in the policy test). Counting only full
/// crossings is off by about `-0.6 sigma_t R`, counting every overlap as a crossing by
/// `+0.7 sigma_t R`. Use only where `sigma_t R` is tiny.
#[inline]
pub fn crossing_density(chord: &SphereChord, r: f32) -> f32 {
    if chord.full {
        1.0 / (PI * r * r)
    } else {
        track_length_density(chord, r)
    }
}
