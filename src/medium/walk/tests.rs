//! The camera-side multi-sphere walk on one chromatic medium segment (method notes 2-3), in 1D:
//! each sphere's reading is replaced by its expectation `F_l(s)` (a forward-ray field that
//! decays along the camera ray), so the walk's estimate of
//! `L_l = ∫_0^T e^{-st_l s} ss_l F_l(s) ds + e^{-st_l T} Ls_l` has a closed form.
//!
//! z-bounds: |z| < 4 for every bin of every correct configuration; the paper's typo rate must be
//! off by |z| > 10 in at least one bin.

use super::{MultiSphereWalk, WalkEnd, sample_extinction};
use crate::medium::{ChannelPick, Medium, Mixture};
use crate::spectrum::Spectrum;
use crate::test_stats::Acc;
use rand::SeedableRng;
use rand_pcg::Pcg64Mcg;

const N: usize = 4;
/// Very different extinctions (1/m) and albedos per bin.
const ST: [f32; N] = [0.2, 1.0, 4.0, 15.0];
const ALB: [f32; N] = [0.9, 0.5, 0.8, 0.3];
/// Sphere reading expectation F_l(s) = E_l e^{-K_l s}, surface radiance behind the segment Ls_l.
const E: [f64; N] = [1.0, 2.0, 0.5, 1.5];
const K: [f64; N] = [0.3, 2.0, 0.1, 1.0];
const LS: [f64; N] = [0.7, 0.2, 1.0, 0.4];
const T: f32 = 1.0;
/// A strongly non-uniform "throughput" for the throughput-proportional pick.
const W_PICK: [f32; N] = [1.0, 0.05, 2.0, 0.3];

fn medium() -> Medium {
    Medium::from_extinction_albedo(&ST, &ALB, 0.5).unwrap()
}

fn mixture(m: &Medium, pick: ChannelPick) -> Mixture {
    Mixture::new(pick, &Spectrum::from_slice(&W_PICK), m, 0.1)
}

fn exact(l: usize) -> f64 {
    let (st, ss) = (ST[l] as f64, (ST[l] * ALB[l]) as f64);
    let t = T as f64;
    ss * E[l] * (1.0 - (-(st + K[l]) * t).exp()) / (st + K[l]) + (-st * t).exp() * LS[l]
}

fn reading(l: usize, s: f32) -> f64 {
    E[l] * (-K[l] * s as f64).exp()
}

/// Runs `rays` camera segments; returns the per-bin estimate and the mean sphere count.
fn run(walk: &MultiSphereWalk, pick: ChannelPick, rays: usize, seed: u64) -> (Acc, f64) {
    let m = medium();
    let mix = mixture(&m, pick);
    let mut rng = Pcg64Mcg::seed_from_u64(seed);
    let mut acc = Acc::new(N);
    let mut spheres = 0u64;
    for _ in 0..rays {
        let mut est = [0.0f64; N];
        let end = walk.walk(&m, (&mix, None), T, &mut rng, |s, w| {
            spheres += 1;
            for l in 0..N {
                est[l] += w[l] as f64 * reading(l, s);
            }
        });
        if let WalkEnd::Transmitted { weight } = end {
            for l in 0..N {
                est[l] += weight[l] as f64 * LS[l];
            }
        }
        acc.add(&est);
    }
    (acc, spheres as f64 / rays as f64)
}

#[test]
fn channel_averaged_walk_is_unbiased_in_every_bin() {
    let mut seed = 100;
    for pick in [ChannelPick::Throughput, ChannelPick::Uniform] {
        for q in [1.0f32, 0.3, 0.05] {
            seed += 1;
            let (acc, _) = run(&MultiSphereWalk::new(q).unwrap(), pick, 200_000, seed);
            for l in 0..N {
                let z = acc.z(l, exact(l));
                assert!(
                    z.abs() < 4.0,
                    "{pick:?} q={q} bin {l}: {} vs {} (z={z})",
                    acc.mean(l),
                    exact(l)
                );
            }
        }
    }
}

#[test]
fn mean_sphere_count_matches_the_formula() {
    let m = medium();
    let mut seed = 200;
    for pick in [ChannelPick::Throughput, ChannelPick::Uniform] {
        let p = *mixture(&m, pick).probabilities();
        for q in [1.0f32, 0.3, 0.05] {
            seed += 1;
            let walk = MultiSphereWalk::new(q).unwrap();
            let mix = mixture(&m, pick);
            let mut rng = Pcg64Mcg::seed_from_u64(seed);
            let mut acc = Acc::new(1);
            for _ in 0..200_000 {
                let mut k = 0.0;
                walk.walk(&m, (&mix, None), T, &mut rng, |_, _| k += 1.0);
                acc.add(&[k]);
            }
            let expected: f64 = (0..N)
                .map(|l| p[l] as f64 * (1.0 - (-(ST[l] * T) as f64).exp()))
                .sum::<f64>()
                / q as f64;
            let z = acc.z(0, expected);
            assert!(
                z.abs() < 4.0,
                "{pick:?} q={q}: {} vs {expected} (z={z})",
                acc.mean(0)
            );
        }
    }
    // Unbounded segment: 1/q spheres exactly on average.
    let walk = MultiSphereWalk::new(0.1).unwrap();
    let mix = mixture(&m, ChannelPick::Uniform);
    let mut rng = Pcg64Mcg::seed_from_u64(299);
    let mut acc = Acc::new(1);
    for _ in 0..100_000 {
        let mut k = 0.0;
        let end = walk.walk(&m, (&mix, None), f32::INFINITY, &mut rng, |_, _| k += 1.0);
        assert!(!matches!(end, WalkEnd::Transmitted { .. }));
        acc.add(&[k]);
    }
    assert!(acc.z(0, 10.0).abs() < 4.0, "{}", acc.mean(0));
}

/// The paper's colour section steps with rate q*st: this must be visibly biased, so that nobody
/// "simplifies" the code back to it.
#[test]
fn paper_typo_rate_is_biased() {
    let pick = ChannelPick::Uniform;
    let q = 0.3;
    let (good, _) = run(&MultiSphereWalk::new(q).unwrap(), pick, 200_000, 301);
    let (bad, _) = run(
        &MultiSphereWalk::paper_typo_biased(q).unwrap(),
        pick,
        200_000,
        302,
    );
    let zmax_good = (0..N)
        .map(|l| good.z(l, exact(l)).abs())
        .fold(0.0, f64::max);
    let zmax_bad = (0..N).map(|l| bad.z(l, exact(l)).abs()).fold(0.0, f64::max);
    eprintln!("max |z|: correct rate {zmax_good:.1}, typo rate {zmax_bad:.1}");
    assert!(zmax_good < 4.0, "correct rate: max |z| = {zmax_good}");
    assert!(
        zmax_bad > 10.0,
        "typo rate should be biased: max |z| = {zmax_bad}"
    );
}

/// Cylinder-truncated on the same segment: the camera only samples where it stops (density
/// pdf_mix); the estimate integrates `Tr_l(z) ss_l F_l(z)` with `Tr_l = e^{-st_l z}/Tmix(z)` over
/// `[0, min(t_e, T)]`, plus the transmitted surface term.
#[test]
fn truncated_cylinder_weights_are_unbiased_in_every_bin() {
    let m = medium();
    let mut seed = 400;
    for pick in [ChannelPick::Throughput, ChannelPick::Uniform] {
        seed += 1;
        let mix = mixture(&m, pick);
        let mut rng = Pcg64Mcg::seed_from_u64(seed);
        let mut acc = Acc::new(N);
        for _ in 0..100_000 {
            let end = sample_extinction(&m, (&mix, None), T, &mut rng);
            let (len, surface) = match end {
                WalkEnd::Transmitted { weight } => (T, Some(weight)),
                WalkEnd::Scattered { s, .. } | WalkEnd::Absorbed { s } => (s, None),
            };
            let mut est = [0.0f64; N];
            // Gauss-Legendre (8 panels x 4 points) in f64 along [0, len].
            let nodes = [
                -0.861136311594053,
                -0.339981043584856,
                0.339981043584856,
                0.861136311594053,
            ];
            let wts = [
                0.347854845137454,
                0.652145154862546,
                0.652145154862546,
                0.347854845137454,
            ];
            let panels = 8;
            let h = len as f64 / panels as f64;
            for k in 0..panels {
                for i in 0..4 {
                    let z = (k as f64 + 0.5 + 0.5 * nodes[i]) * h;
                    let tr = mix.survival_weight(z as f32);
                    for l in 0..N {
                        let ss = (ST[l] * ALB[l]) as f64;
                        est[l] += 0.5 * h * wts[i] * tr[l] as f64 * ss * reading(l, z as f32);
                    }
                }
            }
            if let Some(w) = surface {
                for l in 0..N {
                    est[l] += w[l] as f64 * LS[l];
                }
            }
            acc.add(&est);
        }
        for l in 0..N {
            let z = acc.z(l, exact(l));
            assert!(
                z.abs() < 4.0,
                "{pick:?} bin {l}: {} vs {} (z={z})",
                acc.mean(l),
                exact(l)
            );
        }
    }
}

#[test]
fn invalid_q_is_an_error() {
    for q in [0.0f32, -0.1, 1.5, f32::NAN] {
        assert!(MultiSphereWalk::new(q).is_err(), "q={q}");
    }
}

// ----------------------------------------------------------------- stratified spheres

/// `run`'s estimate with stratified spheres (`stratified.rs`) on a segment of length `len`:
/// per bin, the spheres' readings plus the independently sampled outcome's surface term.
fn run_stratified(q: f32, pick: ChannelPick, len: f32, rays: usize, seed: u64) -> Acc {
    let m = medium();
    let mix = mixture(&m, pick);
    let walk = MultiSphereWalk::new(q).unwrap();
    let mut rng = Pcg64Mcg::seed_from_u64(seed);
    let mut acc = Acc::new(N);
    for _ in 0..rays {
        let mut est = [0.0f64; N];
        let end = walk
            .stratified(&m, &mix, len, &mut rng, |s, w| {
                for l in 0..N {
                    est[l] += w[l] as f64 * reading(l, s);
                }
            })
            .expect("every bin has extinction");
        if let WalkEnd::Transmitted { weight } = end {
            for l in 0..N {
                est[l] += weight[l] as f64 * LS[l];
            }
        }
        acc.add(&est);
    }
    acc
}

/// The closed form of `exact` for a segment of any length (`+inf`: no surface term).
fn exact_len(l: usize, len: f32) -> f64 {
    let (st, ss) = (ST[l] as f64, (ST[l] * ALB[l]) as f64);
    let t = len as f64;
    let surface = if len.is_finite() {
        (-st * t).exp() * LS[l]
    } else {
        0.0
    };
    ss * E[l] * (1.0 - (-(st + K[l]) * t).exp()) / (st + K[l]) + surface
}

/// Unbiased per bin (|z| < 4) for both channel picks, q from one sphere to many, on a finite
/// and an endless segment.
#[test]
fn stratified_spheres_are_unbiased_in_every_bin() {
    let mut seed = 500;
    for pick in [ChannelPick::Throughput, ChannelPick::Uniform] {
        for (q, len) in [(1.0f32, T), (0.3, T), (0.05, T), (0.3, f32::INFINITY)] {
            seed += 1;
            let acc = run_stratified(q, pick, len, 100_000, seed);
            for l in 0..N {
                let want = exact_len(l, len);
                let z = acc.z(l, want);
                assert!(
                    z.abs() < 4.0,
                    "{pick:?} q={q} len={len} bin {l}: {} vs {want} (z={z})",
                    acc.mean(l)
                );
            }
        }
    }
}

/// Each segment gets the walk's mean count `(1 - Tmix(T)) / q` rounded to a neighbouring
/// integer (never below 1), so the count's mean is `max(1, m)` exactly (|z| < 4), and no
/// segment gets any other count.
#[test]
fn stratified_sphere_count_is_the_walks_mean_rounded() {
    let m = medium();
    let mix = mixture(&m, ChannelPick::Uniform);
    let tm = mix.tmix(T) as f64;
    let mut rng = Pcg64Mcg::seed_from_u64(600);
    for q in [1.0f32, 0.3, 0.07] {
        let walk = MultiSphereWalk::new(q).unwrap();
        let mean = (1.0 - tm) / q as f64;
        let (lo, hi) = (mean.floor().max(1.0), mean.ceil().max(1.0));
        let mut acc = Acc::new(1);
        for _ in 0..50_000 {
            let mut k = 0.0;
            walk.stratified(&m, &mix, T, &mut rng, |_, _| k += 1.0);
            assert!(k == lo || k == hi, "q={q}: {k} spheres, not {lo} or {hi}");
            acc.add(&[k]);
        }
        let want = mean.max(1.0);
        // A count that never varies (m below 1) has no standard error: compare exactly.
        if acc.se(0) == 0.0 {
            assert_eq!(acc.mean(0), want, "q={q}");
        } else {
            let z = acc.z(0, want);
            assert!(z.abs() < 4.0, "q={q}: {} vs {want} (z={z})", acc.mean(0));
        }
    }
}

/// One sphere drawn at random from each segment's K is distributed as the truncated mixture
/// `p_T(s) = Σ P_l st_l e^{-st_l s} / (1 - e^{-st_l T})` (the density the weights divide by):
/// chi-square over 20 bins of equal probability, |(X² - 19) / sqrt(2 x 19)| < 5.
#[test]
fn stratified_sphere_positions_follow_the_truncated_mixture() {
    use rand::Rng;
    let m = medium();
    for (pick, seed) in [(ChannelPick::Throughput, 700), (ChannelPick::Uniform, 701)] {
        let mix = mixture(&m, pick);
        let p = *mix.probabilities();
        let cdf = |s: f64| -> f64 {
            (0..N)
                .map(|l| {
                    let st = ST[l] as f64;
                    p[l] as f64 * (1.0 - (-st * s).exp()) / (1.0 - (-st * T as f64).exp())
                })
                .sum()
        };
        let bins = 20usize;
        // Edges of equal probability by bisection on the cdf.
        let edges: Vec<f64> = (1..bins)
            .map(|i| {
                let target = i as f64 / bins as f64;
                let (mut a, mut b) = (0.0, T as f64);
                for _ in 0..60 {
                    let c = 0.5 * (a + b);
                    if cdf(c) < target { a = c } else { b = c }
                }
                0.5 * (a + b)
            })
            .collect();
        let walk = MultiSphereWalk::new(0.2).unwrap();
        let mut rng = Pcg64Mcg::seed_from_u64(seed);
        let mut pick_rng = Pcg64Mcg::seed_from_u64(seed + 50);
        let draws = 200_000;
        let mut counts = vec![0u64; bins];
        for _ in 0..draws {
            let mut at = Vec::new();
            walk.stratified(&m, &mix, T, &mut rng, |s, _| at.push(s as f64));
            let s = at[pick_rng.random_range(0..at.len())];
            counts[edges.partition_point(|e| *e <= s)] += 1;
        }
        let expect = draws as f64 / bins as f64;
        let x2: f64 = counts
            .iter()
            .map(|&c| (c as f64 - expect).powi(2) / expect)
            .sum();
        let df = (bins - 1) as f64;
        let z = (x2 - df) / (2.0 * df).sqrt();
        assert!(
            z.abs() < 5.0,
            "{pick:?}: X² = {x2:.1} over {df} df (z={z:.2})"
        );
    }
}

/// The point of stratifying: on a smooth reading, the spheres' part of the estimate (the
/// outcome's surface term left out: it is the same coin for both) has far less variance than
/// the walk's at the same q (the same mean sphere count). Bound: below half the walk's in
/// every bin (the measured ratios are printed).
#[test]
fn stratified_spheres_have_less_variance_than_the_walk() {
    let m = medium();
    let mix = mixture(&m, ChannelPick::Throughput);
    let walk = MultiSphereWalk::new(0.3).unwrap();
    let mut rng = Pcg64Mcg::seed_from_u64(801);
    let (mut strat, mut walked) = (Acc::new(N), Acc::new(N));
    for _ in 0..50_000 {
        let mut est = [0.0f64; N];
        let sum = |est: &mut [f64; N], s: f32, w: &Spectrum| {
            for l in 0..N {
                est[l] += w[l] as f64 * reading(l, s);
            }
        };
        walk.stratified(&m, &mix, T, &mut rng, |s, w| sum(&mut est, s, w));
        strat.add(&est);
        let mut est = [0.0f64; N];
        walk.walk(&m, (&mix, None), T, &mut rng, |s, w| sum(&mut est, s, w));
        walked.add(&est);
    }
    for l in 0..N {
        let ratio = (strat.se(l) / walked.se(l)).powi(2);
        eprintln!("bin {l}: variance ratio stratified / walk {ratio:.3}");
        assert!(ratio < 0.5, "bin {l}: ratio {ratio}");
    }
}

/// A bin without extinction has no quantiles over an endless segment: the caller keeps the
/// walk (None), and no random number is drawn.
#[test]
fn stratified_spheres_decline_a_bin_without_extinction() {
    let m = Medium::from_extinction_albedo(&[0.0, 1.0], &[0.5, 0.5], 0.0).unwrap();
    let mix = Mixture::new(
        ChannelPick::Uniform,
        &Spectrum::from_slice(&[1.0, 1.0]),
        &m,
        0.1,
    );
    let walk = MultiSphereWalk::new(0.5).unwrap();
    let mut rng = Pcg64Mcg::seed_from_u64(900);
    let before = rng.clone();
    let mut spheres = 0;
    let end = walk.stratified(&m, &mix, 1.0, &mut rng, |_, _| spheres += 1);
    assert!(end.is_none() && spheres == 0);
    assert_eq!(rng, before, "no random number drawn");
}
