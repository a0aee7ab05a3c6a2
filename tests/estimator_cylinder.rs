//! Cylinder weights: eq. 2 against direct quadrature, its limits mu -> 0 and st -> 0, and the
//! Gauss-Legendre accuracy of the truncated-cylinder and colour-forward variants.

#[path = "estimator_stats.rs"]
mod stats;

use brume::integrator::estimator::{
    CylinderChord, cylinder_eq2, cylinder_eq2_fwd, cylinder_truncated, eq2_factor,
};
use brume::medium::{ChannelPick, Medium, Mixture};
use brume::spectrum::Spectrum;
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64Mcg;
use stats::simpson;
use std::f64::consts::PI;

const N: usize = 4;
const ST: [f32; N] = [0.05, 0.7, 3.0, 20.0];
const ALB: [f32; N] = [0.9, 0.5, 0.8, 0.4];

fn medium() -> Medium {
    Medium::from_extinction_albedo(&ST, &ALB, 0.0).unwrap()
}

fn chord(lam1: f32, c: f32, tau1: f32, uv: f32) -> CylinderChord {
    CylinderChord {
        lam1,
        lam2: lam1 + c,
        tau1,
        tau2: tau1 + uv * c,
        uv,
    }
}

/// ∫_0^c e^{-st (tau1 + uv x)} dx in f64.
fn eq2_ref(st: f64, ch: &CylinderChord) -> f64 {
    let c = ch.len() as f64;
    simpson(0.0, c, 20_000, |x| {
        (-st * (ch.tau1 as f64 + ch.uv as f64 * x)).exp()
    })
}

#[test]
fn eq2_matches_quadrature() {
    let mut rng = Pcg64Mcg::seed_from_u64(800);
    for _ in 0..300 {
        let c = 0.001 + 2.0 * rng.random::<f32>();
        let uv = 2.0 * rng.random::<f32>() - 1.0;
        let tau1 = (3.0 * rng.random::<f32>()).max(-uv * c);
        let ch = chord(0.0, c, tau1, uv);
        for st in ST {
            let got = eq2_factor(st, &ch) as f64;
            let want = eq2_ref(st as f64, &ch);
            assert!(
                (got - want).abs() <= 2e-5 * want + 1e-30,
                "st={st} {ch:?}: {got} vs {want}"
            );
            // And the paper's closed form where it is well conditioned.
            let (t1, t2) = (ch.tau1.min(ch.tau2) as f64, ch.tau1.max(ch.tau2) as f64);
            if (uv.abs() * c * st) > 0.1 {
                let st = st as f64;
                let paper = ((-st * t1).exp() - (-st * t2).exp()) / (st * uv.abs() as f64);
                assert!((got - paper).abs() <= 1e-4 * paper + 1e-30);
            }
        }
    }
}

#[test]
fn eq2_is_finite_and_right_in_the_limits() {
    for uv in [0.0f32, 1e-12, -1e-9, 1e-6, 1e-3] {
        for st in [0.0f32, 1e-12, 1e-6, 0.5, 30.0] {
            let ch = chord(0.1, 0.7, 0.4, uv);
            let f = eq2_factor(st, &ch);
            assert!(f.is_finite(), "uv={uv} st={st}");
            // mu -> 0: the chord at constant depth tau1; st -> 0: the chord length.
            let limit = (-(st as f64) * 0.4).exp() * 0.7;
            let want = eq2_ref(st as f64, &ch);
            assert!(
                (f as f64 - want).abs() <= 1e-5 * want,
                "uv={uv} st={st}: {f} vs {want}"
            );
            if uv.abs() < 1e-6 || st < 1e-6 {
                assert!((f as f64 - limit).abs() <= 1e-5 * limit.max(1e-30) + 1e-30);
            }
        }
    }
    let m = medium();
    let w = cylinder_eq2(&m, &chord(0.0, 0.5, 0.2, 0.0), 0.1);
    assert!(w.is_finite());
    for l in 0..N {
        let want = (ST[l] * ALB[l]) as f64 * (-(ST[l] as f64) * 0.2).exp() * 0.5 / (PI * 0.01);
        assert!((w[l] as f64 - want).abs() < 1e-5 * want);
    }
}

/// Truncated cylinder and colour forward flights use composite Gauss–Legendre: check against a
/// fine Simpson reference over chords whose optical variation reaches tens of mean free paths.
#[test]
fn gauss_legendre_variants_are_accurate() {
    let m = medium();
    let cam = Mixture::new(
        ChannelPick::Throughput,
        &Spectrum::from_slice(&[1.0, 0.2, 0.05, 3.0]),
        &m,
        0.1,
    );
    let fwd = Mixture::new(
        ChannelPick::Throughput,
        &Spectrum::from_slice(&[0.1, 2.0, 1.0, 0.3]),
        &m,
        0.1,
    );
    let r = 0.05f32;
    let k = 1.0 / (PI * (r * r) as f64);
    let mut rng = Pcg64Mcg::seed_from_u64(801);
    let mut worst = 0.0f64;
    for case in 0..200 {
        let c = [0.01f32, 0.3, 3.0][case % 3] * (0.5 + rng.random::<f32>());
        let uv = if case % 7 == 0 {
            0.0
        } else {
            2.0 * rng.random::<f32>() - 1.0
        };
        let tau1 = (2.0 * rng.random::<f32>()).max(-uv * c);
        let ch = chord(2.0 * rng.random::<f32>(), c, tau1, uv);
        let trunc = cylinder_truncated(&m, &cam, None, &ch, r);
        let trunc_fwd = cylinder_truncated(&m, &cam, Some(&fwd), &ch, r);
        let eq2f = cylinder_eq2_fwd(&m, &fwd, &ch, r);
        let tau = |x: f64| ch.tau1 as f64 + ch.uv as f64 * x;
        let surv = |mix: &Mixture, s: f64, l: usize| {
            let num = (-(ST[l] as f64) * s).exp();
            let den: f64 = (0..N)
                .map(|j| mix.probabilities()[j] as f64 * (-(ST[j] as f64) * s).exp())
                .sum();
            num / den
        };
        for l in 0..N {
            let ss = (ST[l] * ALB[l]) as f64;
            let lam = |x: f64| ch.lam1 as f64 + x;
            let refs = [
                simpson(0.0, c as f64, 4000, |x| surv(&cam, tau(x), l)),
                simpson(0.0, c as f64, 4000, |x| {
                    surv(&cam, tau(x), l) * surv(&fwd, lam(x), l)
                }),
                simpson(0.0, c as f64, 4000, |x| {
                    (-(ST[l] as f64) * tau(x)).exp() * surv(&fwd, lam(x), l)
                }),
            ];
            for (got, want) in [trunc[l], trunc_fwd[l], eq2f[l]].into_iter().zip(refs) {
                let want = ss * k * want;
                let rel = (got as f64 - want).abs() / want.max(1e-300);
                worst = worst.max(if want > 1e-25 { rel } else { 0.0 });
                assert!(
                    rel < 1e-4 || want < 1e-25,
                    "case {case} bin {l}: {got} vs {want} {ch:?}"
                );
            }
        }
    }
    eprintln!("worst relative error {worst:e}");
}

#[test]
fn grey_truncated_cylinder_is_the_chord_length() {
    let ss = Spectrum::splat(0.3, 3);
    let g = Medium::new(&ss, &Spectrum::splat(0.2, 3), 0.0, 3).unwrap();
    let cam = Mixture::new(
        ChannelPick::Throughput,
        &Spectrum::from_slice(&[1.0, 5.0, 0.1]),
        &g,
        0.1,
    );
    let ch = chord(0.3, 1.7, 0.5, 0.4);
    let w = cylinder_truncated(&g, &cam, None, &ch, 0.2);
    for l in 0..3 {
        let want = 0.3 * 1.7 / (std::f32::consts::PI * 0.04);
        assert!((w[l] - want).abs() < 1e-5 * want);
    }
}
