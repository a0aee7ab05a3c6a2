use super::CylinderChord;
use super::cylinder::phi1;
use crate::medium::HomogeneousMedium;
use crate::spectrum::Spectrum;
use std::f32::consts::PI;

/// Paper eq. 3 exactly as printed ("long" forward segment with deterministic attenuation
/// `e^{-st t}` along it, `t` from the forward segment's origin), per bin:
/// `ss (e^{-st(tau1+t1)} - e^{-st(tau2+t2)}) / (st pi R^2 (1 + |u.v|))`, with point 1 the chord
/// end of smaller `tau`. Multiply by `f Phi_l W_l` (Phi at the forward origin, unattenuated).
///
/// NOT FOR RENDERING: `tests/estimator_long.rs` shows it agrees with eq. 2 only when the forward
/// ray moves away from the camera (`u.v >= 0`); for `u.v < 0` the right denominator is
/// `1 - |u.v|`, see [`long_eq3_exact`]. (Pairing point 1 with the forward entry instead does not
/// save it: the sign is then right but the value is off by `(1 - |u.v|)/(1 + |u.v|)`.)
pub fn long_eq3_paper(medium: &HomogeneousMedium, chord: &CylinderChord, r: f32) -> Spectrum {
    let (ta, la, tb, lb) = if chord.tau1 <= chord.tau2 {
        (chord.tau1, chord.lam1, chord.tau2, chord.lam2)
    } else {
        (chord.tau2, chord.lam2, chord.tau1, chord.lam1)
    };
    let (a, b) = (ta + la, tb + lb);
    let k = 1.0 / (PI * r * r * (1.0 + chord.mu()));
    let mut out = Spectrum::ZERO;
    for l in 0..medium.n {
        let st = medium.sigma_t.0[l];
        // (e^{-st a} - e^{-st b}) / st without cancellation.
        let diff = (-st * a).exp() * (b - a) * phi1(st * (b - a));
        out.0[l] = medium.sigma_s.0[l] * k * diff;
    }
    out
}

/// The "long" estimator derived from its definition, `ss/(pi R^2) ∫_chord e^{-st (tau(lam) +
/// lam)} dlam`: `e^{-st (tau1 + lam1)} chord (1 - e^{-x}) / x` with `x = st chord (1 + u.v)`
/// (signed `u.v`). Equals eq. 3 for `u.v >= 0`, and stays finite for a forward ray travelling
/// straight at the camera (`u.v = -1`, where `tau + lam` is constant).
pub fn long_eq3_exact(medium: &HomogeneousMedium, chord: &CylinderChord, r: f32) -> Spectrum {
    let c = chord.len();
    let k = 1.0 / (PI * r * r);
    let mut out = Spectrum::ZERO;
    for l in 0..medium.n {
        let st = medium.sigma_t.0[l];
        let v = (-st * (chord.tau1 + chord.lam1)).exp() * c * phi1(st * c * (1.0 + chord.uv));
        out.0[l] = medium.sigma_s.0[l] * k * v;
    }
    out
}
