use super::{CylinderChord, chord_integral, panels_for};
use crate::medium::{HomogeneousMedium, Mixture};
use crate::spectrum::Spectrum;
use std::f32::consts::PI;

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
    medium: &HomogeneousMedium,
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

/// Eq. 2 (deterministic camera transmittance `e^{-st_l tau}`) for a colour forward flight whose
/// flux at `lam` is `Phi_l e^{-st_l lam} / Tmix_fwd(lam)` (see `medium::ForwardFlight`): the
/// closed form of `cylinder_eq2` assumes constant flux along the chord and is biased by
/// O(chord x sigma_t spread) here. Composite Gauss–Legendre.
#[inline]
pub fn cylinder_eq2_fwd(
    medium: &HomogeneousMedium,
    fwd: &Mixture,
    chord: &CylinderChord,
    r: f32,
) -> Spectrum {
    if fwd.sigma_t_span() == 0.0 {
        // Grey forward flight: its flux is constant along the chord, eq. 2's closed form is exact.
        return super::cylinder_eq2(medium, chord, r);
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
