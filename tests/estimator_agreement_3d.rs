//! The four medium estimators on the same single-scattering quantity in 3D: a camera segment
//! (axis +z, length T) in an unbounded chromatic fog, lit by a uniform parallel beam of forward
//! rays (colour free flights with the spectral mixture, gathered along their first, uncollided
//! segment). Closed form: `L_l = ss_l f E_l e^{-st_l D} (1 - e^{-st_l (1+u.v) T}) / (st_l (1+u.v))`
//! times the exact blur of each volume on this exponential field (ball average for spheres, disc
//! average for cylinders; both ~1e-3 here).
//!
//! Estimators: spheres q = 1 and q = 0.05 (multi-sphere walk, track-length sphere weight),
//! cylinder eq. 2 (deterministic camera transmittance) and truncated cylinder (camera extinction
//! sampled with the mixture). z-bound: |z| < 4 per bin and estimator.

#[path = "estimator_stats.rs"]
mod stats;

use brume::integrator::estimator::{
    CameraAxis, cylinder_eq2_fwd, cylinder_truncated, segment_cylinder, segment_sphere,
    track_length_density,
};
use brume::medium::{
    ChannelPick, ForwardFlight, Medium, Mixture, MultiSphereWalk, WalkEnd, sample_extinction,
};
use brume::spectrum::Spectrum;
use glam::Vec3;
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64Mcg;
use stats::Acc;

const N: usize = 4;
const ST: [f32; N] = [0.3, 1.0, 3.0, 8.0];
const ALB: [f32; N] = [0.9, 0.6, 0.8, 0.5];
const E: [f32; N] = [1.0, 0.5, 2.0, 1.0];
const G: f32 = 0.5;
const T: f32 = 1.0;
const R: f32 = 0.01;
/// Distance of the beam's source plane upstream of the camera origin.
const D: f32 = 0.5;
const THETA: f32 = std::f32::consts::FRAC_PI_3;

#[test]
fn spheres_cylinders_and_truncated_cylinders_agree_with_the_closed_form() {
    let ss: Vec<f32> = (0..N).map(|l| ST[l] * ALB[l]).collect();
    let sa: Vec<f32> = (0..N).map(|l| ST[l] * (1.0 - ALB[l])).collect();
    let m = Medium::new(&Spectrum::from_slice(&ss), &Spectrum::from_slice(&sa), G, N).unwrap();
    let u = Vec3::Z;
    let v = Vec3::new(THETA.sin(), 0.0, THETA.cos());
    let uv = u.dot(v);
    let f = m.phase.eval_uv(u, v);
    let axis = CameraAxis {
        origin: Vec3::ZERO,
        dir: u,
        start: 0.0,
        len: T,
    };
    // Source rectangle in the plane perpendicular to v, covering the cylinder's shadow.
    let p0 = -v * D;
    let e1 = Vec3::new(THETA.cos(), 0.0, -THETA.sin());
    let e2 = Vec3::Y;
    let (a_lo, a_hi) = (-THETA.sin() - R, R);
    let area = (a_hi - a_lo) * 2.0 * R;
    let cam_mix = Mixture::new(
        ChannelPick::Throughput,
        &Spectrum::from_slice(&[0.3, 1.0, 0.1, 2.0]),
        &m,
        0.1,
    );
    let walks = [
        MultiSphereWalk::new(1.0).unwrap(),
        MultiSphereWalk::new(0.05).unwrap(),
    ];
    let (trials, fwd_per_trial) = (3000, 1000);
    let phi = Spectrum::from_slice(&E) * (area / fwd_per_trial as f32);
    let mut rng = Pcg64Mcg::seed_from_u64(1100);
    let mut accs: Vec<Acc> = (0..4).map(|_| Acc::new(N)).collect();
    let mut spheres: [Vec<(f32, Spectrum)>; 2] = [Vec::new(), Vec::new()];
    for _ in 0..trials {
        for (k, walk) in walks.iter().enumerate() {
            spheres[k].clear();
            walk.walk(&m, (&cam_mix, None), T, &mut rng, |s, w| {
                spheres[k].push((s, *w))
            });
        }
        let trunc_len = match sample_extinction(&m, (&cam_mix, None), T, &mut rng) {
            WalkEnd::Transmitted { .. } => T,
            WalkEnd::Scattered { s, .. } | WalkEnd::Absorbed { s } => s,
        };
        let trunc_axis = CameraAxis {
            len: trunc_len,
            ..axis
        };
        let mut est = [Spectrum::ZERO; 4];
        for _ in 0..fwd_per_trial {
            let a = a_lo + (a_hi - a_lo) * rng.random::<f32>();
            let b = R * (2.0 * rng.random::<f32>() - 1.0);
            let o = p0 + e1 * a + e2 * b;
            let flight = ForwardFlight::sample(&m, &phi, 0.1, f32::INFINITY, &mut rng);
            let len = flight.end();
            for k in 0..2 {
                for (s, w) in &spheres[k] {
                    if let Some(ch) = segment_sphere(o, v, len, u * *s, R) {
                        let flux = flight.flux_at(&phi, ch.mid());
                        est[k] += *w * flux * (f * track_length_density(&ch, R));
                    }
                }
            }
            if let Some(ch) = segment_cylinder(&axis, R, o, v, len) {
                est[2] += cylinder_eq2_fwd(&m, flight.mixture(), &ch, R) * phi * f;
            }
            if let Some(ch) = segment_cylinder(&trunc_axis, R, o, v, len) {
                est[3] +=
                    cylinder_truncated(&m, &cam_mix, Some(flight.mixture()), &ch, R) * phi * f;
            }
        }
        for (acc, e) in accs.iter_mut().zip(&est) {
            acc.add_f32(e.as_slice(N));
        }
    }
    let names = [
        "spheres q=1",
        "spheres q=0.05",
        "cylinder eq.2",
        "truncated cylinder",
    ];
    for l in 0..N {
        let (st, ssl) = (ST[l] as f64, ss[l] as f64);
        let k = st * (1.0 + uv as f64);
        let point =
            ssl * f as f64 * E[l] as f64 * (-st * D as f64).exp() * (1.0 - (-k * T as f64).exp())
                / k;
        // Exact averages of e^{-st v.p} over the ball and over the disc perpendicular to u.
        let x = st * R as f64;
        let ball = 3.0 * (x * x.cosh() - x.sinh()) / x.powi(3);
        let y = st * THETA.sin() as f64 * R as f64;
        let disc = 1.0 + y * y / 8.0 + y.powi(4) / 192.0;
        for (i, acc) in accs.iter().enumerate() {
            let want = point * if i < 2 { ball } else { disc };
            let z = acc.z(l, want);
            eprintln!(
                "bin {l} {:>18}: {:.6} vs {want:.6} (rel se {:.4}, z={z:+.2})",
                names[i],
                acc.mean(l),
                acc.se(l) / want
            );
            assert!(
                z.abs() < 4.0,
                "bin {l} {}: {} vs {want} (z={z})",
                names[i],
                acc.mean(l)
            );
        }
    }
}
