//! Continuing the camera path after a real extinction (method note 4), per bin, against an
//! independent brute-force simulation: a chromatic 1D rod `[0, L]` with forward/backward
//! scattering, lit from its right end by light travelling left; the camera at `x = 0` looks
//! right. Multiple scattering (both directions) is essential here.
//!
//! The camera path re-picks its mixture from its current throughput on every segment
//! (throughput-proportional pick), so any error in the roulette/throughput update shows up in
//! the bins the walk rarely steps with. Reference: analog per-bin particle tracing of light.
//! z-bound: |z| < 4 per bin, with the standard errors of both simulations combined.

#[path = "estimator_stats.rs"]
mod stats;

use brume::medium::{ChannelPick, Medium, Mixture, MultiSphereWalk, WalkEnd, sample_extinction};
use brume::spectrum::Spectrum;
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64Mcg;
use stats::Acc;

const N: usize = 4;
const ST: [f32; N] = [0.3, 1.5, 3.0, 6.0];
const ALB: [f32; N] = [0.95, 0.7, 0.9, 0.5];
/// Probability that a scattering keeps the direction.
const PF: f32 = 0.7;
const L: f32 = 1.5;
/// Radiance entering at the right end, travelling left.
const I: [f64; N] = [1.0, 0.8, 1.2, 2.0];

fn medium() -> Medium {
    Medium::from_extinction_albedo(&ST, &ALB, 0.0).unwrap()
}

/// Light side, written independently of the library: analog transport in bin `l` of a particle
/// entering at x = L moving left; 1 if it leaves at x = 0 moving left.
fn brute_force(l: usize, particles: usize, rng: &mut Pcg64Mcg) -> (f64, f64) {
    let (st, alb) = (ST[l] as f64, ALB[l] as f64);
    let mut hits = 0u64;
    for _ in 0..particles {
        let (mut x, mut dir) = (L as f64, -1.0f64);
        loop {
            let t = -(1.0 - rng.random::<f64>()).ln() / st;
            let nx = x + dir * t;
            if nx <= 0.0 {
                hits += (dir < 0.0) as u64;
                break;
            }
            if nx >= L as f64 {
                break;
            }
            x = nx;
            if rng.random::<f64>() >= alb {
                break;
            }
            if rng.random::<f32>() >= PF {
                dir = -dir;
            }
        }
    }
    let p = hits as f64 / particles as f64;
    (p, (p * (1.0 - p) / particles as f64).sqrt())
}

/// Camera side with the library: segment walks with a fresh mixture each segment.
fn camera(walk: Option<MultiSphereWalk>, paths: usize, seed: u64) -> Acc {
    let m = medium();
    let mut rng = Pcg64Mcg::seed_from_u64(seed);
    let mut acc = Acc::new(N);
    for _ in 0..paths {
        let (mut x, mut dir) = (0.0f32, 1.0f32);
        let mut w = Spectrum::splat(1.0, N);
        let mut est = [0.0f64; N];
        loop {
            let seg = if dir > 0.0 { L - x } else { x };
            let mix = Mixture::new(ChannelPick::Throughput, &w, &m, 0.1);
            let end = match &walk {
                Some(walk) => walk.walk(&m, (&mix, None), seg, &mut rng, |_, _| {}),
                None => sample_extinction(&m, (&mix, None), seg, &mut rng),
            };
            match end {
                WalkEnd::Transmitted { weight } => {
                    if dir > 0.0 {
                        for l in 0..N {
                            est[l] = (w[l] * weight[l]) as f64 * I[l];
                        }
                    }
                    break;
                }
                WalkEnd::Absorbed { .. } => break,
                WalkEnd::Scattered { s, weight } => {
                    x += dir * s;
                    w *= weight;
                    if rng.random::<f32>() >= PF {
                        dir = -dir;
                    }
                }
            }
        }
        acc.add(&est);
    }
    acc
}

#[test]
fn continued_camera_paths_match_brute_force_per_bin() {
    let mut rng = Pcg64Mcg::seed_from_u64(500);
    let reference: Vec<(f64, f64)> = (0..N).map(|l| brute_force(l, 400_000, &mut rng)).collect();
    for (k, walk) in [None, Some(MultiSphereWalk::new(0.3).unwrap())]
        .into_iter()
        .enumerate()
    {
        let acc = camera(walk, 300_000, 510 + k as u64);
        for l in 0..N {
            let (p, se) = reference[l];
            let (r, rse) = (p * I[l], se * I[l]);
            let z = (acc.mean(l) - r) / (acc.se(l).powi(2) + rse.powi(2)).sqrt();
            assert!(
                z.abs() < 4.0,
                "walk {k} bin {l}: camera {} vs brute force {r} (z={z})",
                acc.mean(l)
            );
        }
    }
}
