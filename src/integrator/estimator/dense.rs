//! The three cylinders (eq. 2, truncated, eq. 3 long) in a medium with a density field, under
//! the exact transport (docs/media.md, "Cylinders in a density field"). With
//! `sigma(x) = rho(x) sigma` the single-scattering integrand along the camera axis is
//! `rho(tau) ss_l e^{-st_l D(tau)} L_in(tau)`, `D(tau) = ∫_0^tau rho` the axis's optical depth
//! at density 1. The cylinder's kernel estimates `L_in` over its disc as in a uniform medium;
//! the density and the transmittance are the axis point's, so a chord from `tau_a` to `tau_b`
//! (`mu = |u.v|`, `dlam = dtau / mu`) adds
//!
//! - eq. 2: `ss_l / (pi R^2) ∫ rho e^{-st_l D} dlam = ss_l (e^{-st_l D(tau_a)} -
//!   e^{-st_l D(tau_b)}) / (st_l mu pi R^2)`: the uniform closed form with `tau` replaced by
//!   `D(tau)` (`d/dtau e^{-st D} = -st rho e^{-st D}`);
//! - truncated: `ss_l / (pi R^2) ∫ rho e^{-st_l D} / Tmix(D) dlam`: the walk runs in `u = D`, so a
//!   point of the axis is inside the cylinder with probability `Tmix(D(tau))`; grey, this is
//!   `ss c rho_bar / (pi R^2)` with `rho_bar` the mean density over the chord's axial range;
//! - long: `ss_l / (pi R^2) ∫ rho e^{-st_l (D(tau) + D_fwd(lam))} dlam`, `D_fwd` the forward
//!   ray's depth from its origin (no closed form: two fields; Gauss–Legendre).
//!
//! Each is the uniform estimator's formula at `rho = 1`. The depths are recomputed here from
//! the record's segment (as spheres' are in chromatic media), so records keep their size.

use std::f32::consts::PI;

use glam::Vec3;

use super::quadrature::phi1;
use super::{CylinderChord, chord_integral, panels_for};
use crate::integrator::record::SegmentRecord;
use crate::medium::{Along, Density, Medium, Mixture};
use crate::spectrum::Spectrum;

/// The optical depth at density 1 along a camera axis, from its segment's start, for points at
/// or beyond `tau0` (a chord's nearer end): one depth from the start, then short ones.
struct AxisDepth<'a> {
    density: &'a Density,
    dir: Vec3,
    /// The point at `tau0`, and the depth there.
    p0: Vec3,
    tau0: f32,
    d0: f32,
}

impl<'a> AxisDepth<'a> {
    fn new(density: &'a Density, seg: &SegmentRecord, tau0: f32) -> Self {
        Self {
            density,
            dir: seg.dir,
            p0: seg.at(tau0),
            tau0,
            d0: density.depth_to(seg.origin, seg.dir, tau0),
        }
    }

    /// `D(tau)` for `tau >= tau0` (rounding below it is clamped).
    fn depth(&self, tau: f32) -> f32 {
        self.d0
            + self
                .density
                .depth_to(self.p0, self.dir, (tau - self.tau0).max(0.0))
    }

    /// The density at `tau`.
    fn rho(&self, tau: f32) -> f32 {
        self.density.at(self.p0 + self.dir * (tau - self.tau0))
    }

    /// For many depths along the chord (quadrature nodes): the change of variable from `tau0`,
    /// built once (a grid ray's pieces), instead of a walk through the grid per node.
    fn nodes(&self) -> AxisNodes {
        AxisNodes {
            along: self.density.along(self.p0, self.dir),
            tau0: self.tau0,
            d0: self.d0,
        }
    }
}

/// [`AxisDepth::nodes`]: `D(tau)` for `tau >= tau0` through one change of variable.
struct AxisNodes {
    along: Along,
    tau0: f32,
    d0: f32,
}

impl AxisNodes {
    fn depth(&self, tau: f32) -> f32 {
        self.d0 + self.along.depth((tau - self.tau0).max(0.0))
    }
}

/// Below this axial extent of a chord (relative to the chord) its mean density is the density
/// at its middle: the chord runs at nearly constant depth.
const FLAT: f32 = 1e-4;

/// What the closed forms need of a chord: the depth at its nearer axial end `D(tau_a)` and
/// `rho_bar c`, the chord's length times the mean density over its axial range (the chord's
/// optical length as the axis sees it).
fn axial<'a>(
    density: &'a Density,
    seg: &SegmentRecord,
    chord: &CylinderChord,
) -> (AxisDepth<'a>, f32) {
    let (ta, tb) = (chord.tau_min(), chord.tau1.max(chord.tau2));
    let axis = AxisDepth::new(density, seg, ta);
    let c = chord.len();
    let rho_bar = if tb - ta > FLAT * c {
        (axis.depth(tb) - axis.d0) / (tb - ta)
    } else {
        axis.rho(0.5 * (ta + tb))
    };
    (axis, rho_bar * c)
}

/// Eq. 2 in a density field, per bin (see the module's comment); `fwd` is a colour forward
/// flight's mixture and change of variable (its flux changes along the chord), None for a grey
/// one. Multiply by `f(-u.v) Phi_l W_l`.
pub fn cylinder_eq2_density(
    med: &Medium,
    seg: &SegmentRecord,
    chord: &CylinderChord,
    fwd: Option<(&Mixture, &Along)>,
    r: f32,
) -> Spectrum {
    let k = 1.0 / (PI * r * r);
    let (axis, optical) = axial(&med.density, seg, chord);
    let Some((mix, along)) = fwd.filter(|(m, _)| m.sigma_t_span() > 0.0) else {
        let mut out = Spectrum::ZERO;
        for l in 0..med.n {
            let st = med.sigma_t.0[l];
            let v = (-st * axis.d0).exp() * optical * phi1(st * optical * chord.mu());
            out.0[l] = med.sigma_s.0[l] * k * v;
        }
        return out;
    };
    let d_fwd = (along.depth(chord.lam1), along.depth(chord.lam2));
    let span =
        med.sigma_t.max_value() * optical * chord.mu() + mix.sigma_t_span() * (d_fwd.1 - d_fwd.0);
    let nodes = axis.nodes();
    let integral = chord_integral(chord.len(), panels_for(span), |x| {
        let tau = chord.tau1 + chord.uv * x;
        let mut w = med.sigma_t.transmittance(nodes.depth(tau), med.n) * axis.rho(tau);
        w *= mix.survival_weight(along.depth(chord.lam1 + x));
        w
    });
    med.sigma_s * integral * k
}

/// The truncated cylinder in a density field, per bin (see the module's comment): `cam` the
/// camera segment's mixture, `fwd` as in [`cylinder_eq2_density`].
pub fn cylinder_truncated_density(
    med: &Medium,
    seg: &SegmentRecord,
    cam: &Mixture,
    fwd: Option<(&Mixture, &Along)>,
    chord: &CylinderChord,
    r: f32,
) -> Spectrum {
    let k = 1.0 / (PI * r * r);
    let (axis, optical) = axial(&med.density, seg, chord);
    let fwd = fwd.filter(|(m, _)| m.sigma_t_span() > 0.0);
    if cam.sigma_t_span() == 0.0 && fwd.is_none() {
        // Grey: every survival ratio is 1, what is left is the chord's optical length.
        return med.sigma_s * (k * optical);
    }
    let fwd_span = fwd.map_or(0.0, |(m, a)| {
        m.sigma_t_span() * (a.depth(chord.lam2) - a.depth(chord.lam1))
    });
    let span = cam.sigma_t_span() * optical * chord.mu() + fwd_span;
    let nodes = axis.nodes();
    let integral = chord_integral(chord.len(), panels_for(span), |x| {
        let tau = chord.tau1 + chord.uv * x;
        let w = cam.survival_weight(nodes.depth(tau)) * axis.rho(tau);
        match fwd {
            Some((m, a)) => w * m.survival_weight(a.depth(chord.lam1 + x)),
            None => w,
        }
    });
    med.sigma_s * integral * k
}

/// Eq. 3 (the long cylinder, exact form) in a density field, per bin: `along` is the forward
/// segment's change of variable from its origin. Multiply by `f(-u.v) Phi_l W_l` with the
/// forward flux at the segment's origin.
pub fn long_eq3_density(
    med: &Medium,
    seg: &SegmentRecord,
    chord: &CylinderChord,
    along: &Along,
    r: f32,
) -> Spectrum {
    let k = 1.0 / (PI * r * r);
    let (axis, optical) = axial(&med.density, seg, chord);
    let d_fwd = (along.depth(chord.lam1), along.depth(chord.lam2));
    let span = med.sigma_t.max_value() * (optical * chord.mu() + (d_fwd.1 - d_fwd.0));
    let nodes = axis.nodes();
    let integral = chord_integral(chord.len(), panels_for(span), |x| {
        let tau = chord.tau1 + chord.uv * x;
        let d = nodes.depth(tau) + along.depth(chord.lam1 + x);
        med.sigma_t.transmittance(d, med.n) * axis.rho(tau)
    });
    med.sigma_s * integral * k
}

#[cfg(test)]
mod tests {
    // The closed forms and quadratures above against a brute-force midpoint rule of their
    // definitions along the chord (density at the axis point, depth by `Density::depth_to`),
    // in height fog, for chords away from, towards and level with the camera; and the camera
    // side's pieces in distance.

    use super::super::{CameraAxis, segment_cylinder};
    use super::*;
    use crate::medium::ChannelPick;
    use crate::medium::density::Height;

    const R: f32 = 0.05;

    fn fog(st: f32) -> Medium {
        let n = 2;
        Medium::new(
            &Spectrum::splat(0.8 * st, n),
            &Spectrum::splat(0.2 * st, n),
            0.0,
            n,
        )
        .unwrap()
        .with_density(Density::Height(Height::new(
            0.0,
            0.7,
            Vec3::new(0.0, 0.6, 0.8),
        )))
    }

    fn seg() -> SegmentRecord {
        SegmentRecord {
            origin: Vec3::new(0.1, -0.3, 0.2),
            pixel: 0,
            dir: Vec3::new(0.2, 0.3, 1.0).normalize(),
            throughput: 0,
            medium: 0,
            classes: 0,
        }
    }

    /// `∫_chord rho(tau) e^{-st (D(tau) + D_fwd(lam))} dlam` by 20 000 midpoints, with
    /// `fwd`: whether the forward ray's depth counts (eq. 3).
    fn brute(
        med: &Medium,
        s: &SegmentRecord,
        o: Vec3,
        v: Vec3,
        ch: &CylinderChord,
        fwd: bool,
    ) -> f64 {
        let st = med.sigma_t.0[0] as f64;
        let m = 20_000;
        let h = ch.len() as f64 / m as f64;
        (0..m)
            .map(|i| {
                let lam = ch.lam1 as f64 + (i as f64 + 0.5) * h;
                let tau = ch.tau1 as f64 + ch.uv as f64 * (lam - ch.lam1 as f64);
                let d = med.density.depth_to(s.origin, s.dir, tau as f32) as f64;
                let df = if fwd {
                    med.density.depth_to(o, v, lam as f32) as f64
                } else {
                    0.0
                };
                let rho = med.density.at(s.at(tau as f32)) as f64;
                rho * (-st * (d + df)).exp() * h
            })
            .sum()
    }

    #[test]
    fn closed_forms_and_quadrature_match_their_definitions() {
        let s = seg();
        let axis = CameraAxis {
            origin: s.origin,
            dir: s.dir,
            start: 0.0,
            len: 3.0,
        };
        let k = 1.0 / (PI * R * R) as f64;
        let ortho = s.dir.any_orthonormal_vector();
        for st in [0.5f32, 4.0] {
            let med = fog(st);
            let ss = med.sigma_s.0[0] as f64;
            // (forward direction, a point the ray passes): away, towards, level with the axis.
            for (v, p) in [
                ((s.dir + ortho).normalize(), s.at(1.2)),
                ((ortho - s.dir * 0.8).normalize(), s.at(2.0)),
                ((ortho + s.dir * 1e-6).normalize(), s.at(0.7)),
            ] {
                let o = p - v * 0.5;
                let ch = segment_cylinder(&axis, R, o, v, 10.0).expect("the ray crosses");
                let along = med.density.along(o, v);
                let eq2 = cylinder_eq2_density(&med, &s, &ch, None, R)[0] as f64;
                let want = ss * k * brute(&med, &s, o, v, &ch, false);
                assert!((eq2 / want - 1.0).abs() < 2e-3, "eq2 {eq2} vs {want}");
                let grey = Mixture::new(ChannelPick::Uniform, &Spectrum::splat(1.0, 2), &med, 0.1);
                let tr = cylinder_truncated_density(&med, &s, &grey, None, &ch, R)[0] as f64;
                // Grey: `e^{-st D} / Tmix(D)` is 1, so the truncated weight is eq. 2's at st = 0.
                let want0 = ss * k * brute(&fog(0.0), &s, o, v, &ch, false);
                assert!((tr / want0 - 1.0).abs() < 2e-3, "truncated {tr} vs {want0}");
                let long = long_eq3_density(&med, &s, &ch, &along, R)[0] as f64;
                let want3 = ss * k * brute(&med, &s, o, v, &ch, true);
                assert!((long / want3 - 1.0).abs() < 2e-3, "long {long} vs {want3}");
            }
        }
    }
}
