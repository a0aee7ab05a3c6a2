//! The blend's weight against the mean square error it minimises, on films whose passes have a
//! known mean, blur and noise; the blended image, its noise and merges.

use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64Mcg;

use super::*;
use crate::film::{Film, PassBuffer};
use crate::spectrum::SpectralGrid;

const W: usize = 32;
const H: usize = 32;
const BINS: usize = 4;
const VALUES: usize = W * H * BINS;

/// The mean difference of value `i`.
type Delta = dyn Fn(usize) -> f64;
/// The total's and the difference's standard deviations per pass, and their correlation.
type Noise = (f64, f64, f64);

/// A standard normal deviate (Box-Muller).
fn normal(rng: &mut Pcg64Mcg) -> f64 {
    let (u, v): (f64, f64) = (rng.random::<f64>().max(1e-300), rng.random());
    (-2.0 * u.ln()).sqrt() * (std::f64::consts::TAU * v).cos()
}

/// One pass whose every value has total `T = 10 + x` and difference `D = delta(i) + y`, with
/// `Var x = st^2`, `Var y = sd^2` and correlation `rho`. The medium layer holds 3/4 of each,
/// the surface 1/4.
fn pass(
    rng: &mut Pcg64Mcg,
    delta: &dyn Fn(usize) -> f64,
    (st, sd, rho): (f64, f64, f64),
) -> PassBuffer {
    let mut b = PassBuffer::new(W * H, BINS).with_blend(true);
    b.blend.truncate(LAYERS * VALUES);
    for i in 0..VALUES {
        let (a, c) = (normal(rng), normal(rng));
        let x = st * a;
        let y = sd * (rho * a + (1.0 - rho * rho).sqrt() * c);
        let (t, d) = (10.0 + x, delta(i) + y);
        b.data[i] = (0.75 * t) as f32;
        b.data[VALUES + i] = (0.25 * t) as f32;
        b.blend[i] = (0.75 * d) as f32;
        b.blend[VALUES + i] = (0.25 * d) as f32;
    }
    b
}

fn film(passes: u64, seed: u64, delta: &dyn Fn(usize) -> f64, noise: (f64, f64, f64)) -> Film {
    let mut rng = Pcg64Mcg::seed_from_u64(seed);
    let mut f = Film::new(W, H, SpectralGrid::new(BINS, 400.0, 700.0));
    for _ in 0..passes {
        f.add_pass(&pass(&mut rng, delta, noise));
    }
    f
}

/// The weight that minimises the expected error for the true parameters (module comment of
/// `film::blend`): `((4/3) A - C) / (A + B)` with the true blur, noise and covariance.
fn best(passes: u64, delta: &dyn Fn(usize) -> f64, (st, sd, rho): (f64, f64, f64)) -> f64 {
    let n = passes as f64;
    let a: f64 = (0..VALUES).map(|i| delta(i) * delta(i)).sum();
    let b = VALUES as f64 * sd * sd / n;
    let c = VALUES as f64 * rho * st * sd / n;
    ((4.0 / 3.0 * a - c) / (a + b)).clamp(0.0, 1.0)
}

/// Over 4096 values and 64 passes, the estimated blur, noise and covariance sums are within a
/// few percent of the truth, and so the weight; four regimes: no blur with the difference
/// anticorrelated with the total (a small positive weight, the variance-minimising mix), no
/// blur with it correlated (0), a blur of the noise's size (between), and a resolved blur (1).
#[test]
fn the_weight_minimises_the_error_for_known_blur_and_noise() {
    let passes = 64;
    let zero = |_: usize| 0.0;
    let some = |i: usize| if i.is_multiple_of(2) { 0.1 } else { -0.1 };
    let large = |i: usize| 0.5 * ((i % 7) as f64 - 3.0);
    let cases: [(&Delta, Noise, (f64, f64)); 4] = [
        (&zero, (1.0, 1.0, -0.3), (0.2, 0.4)),
        (&zero, (1.0, 1.0, 0.3), (0.0, 0.0)),
        (&some, (1.0, 1.0, -0.1), (0.3, 0.7)),
        (&large, (1.0, 1.0, 0.2), (1.0, 1.0)),
    ];
    for (k, (delta, noise, (lo, hi))) in cases.into_iter().enumerate() {
        let f = film(passes, 100 + k as u64, delta, noise);
        let b = f.blend().expect("a blended film");
        let want = best(passes, delta, noise);
        assert!(
            (lo..=hi).contains(&want),
            "case {k}: the regime is not the one meant ({want})"
        );
        // The weight's own error: A, B, C from 64 passes of 4096 values are within 5 % (B's
        // relative standard error is sqrt(2/63/4096), under 0.3 %; A's and C's similar).
        assert!(
            (b.w - want).abs() < 0.03 + 0.05 * want,
            "case {k}: weight {} against the best {want} ({b:?})",
            b.w
        );
        let true_noise = VALUES as f64 * noise.1 * noise.1 / passes as f64;
        assert!(
            (b.noise / true_noise - 1.0).abs() < 0.05,
            "case {k}: noise {} against {true_noise}",
            b.noise
        );
    }
}

/// The image is the larger radius's mean plus w times the mean difference, per layer, and its
/// noise is the standard error of `T + w D`; without difference layers (a pass without them
/// joined) it is the plain mean.
#[test]
fn the_blended_image_is_the_large_radius_plus_w_times_the_difference() {
    let delta = |i: usize| 0.3 * ((i % 5) as f64 - 2.0);
    let noise = (1.0, 0.5, -0.2);
    let passes = 16;
    let f = film(passes, 7, &delta, noise);
    let w = f.blend().expect("blended").w;
    assert!(w > 0.5, "a resolved blur: {w}");
    let img = f.image();
    let b = f.blend.as_ref().expect("sums");
    let p = passes as f64;
    let worst = (0..VALUES)
        .map(|i| {
            let t = f.sum[i].wrapping_add(f.sum[VALUES + i]) as f64 / accum_sum_scale() / p;
            let d = b.sum[i].wrapping_add(b.sum[VALUES + i]) as f64 / accum_sum_scale() / p;
            let m = (f.sum[i] as f64 + w * b.sum[i] as f64) / accum_sum_scale() / p;
            let layer = img.layers[0].1[i] as f64;
            ((img.data[i] as f64 - (t + w * d)).abs()).max((layer - m).abs())
        })
        .fold(0.0, f64::max);
    assert!(worst < 1e-5, "{worst}");
    // The noise layer: sqrt((V_T + 2 w C + w^2 V_D) / n), here known up to sampling error.
    let (st, sd, rho) = noise;
    let var = st * st + 2.0 * w * rho * st * sd + w * w * sd * sd;
    let se = (var / p).sqrt();
    let noise_img = img.noise.as_ref().expect("noise");
    let mean: f64 = noise_img.iter().map(|v| *v as f64).sum::<f64>() / VALUES as f64;
    assert!((mean / se - 1.0).abs() < 0.05, "noise {mean} against {se}");
    // A pass without difference layers leaves the film without them.
    let mut g = f.clone();
    g.add_pass(&PassBuffer::new(W * H, BINS));
    assert!(g.blend.is_none() && g.blend().is_none());
}

fn accum_sum_scale() -> f64 {
    crate::film::fixed::SUM_SCALE
}

/// Pass ranges merged in any grouping give the film of one run, blend sums included, and so
/// the same image bits; a part without difference layers leaves the merge without them.
#[test]
fn merges_keep_the_blend_bit_exact() {
    let delta = |i: usize| 0.01 * (i % 3) as f64;
    let noise = (1.0, 0.7, -0.3);
    let mut rng = Pcg64Mcg::seed_from_u64(3);
    let passes: Vec<PassBuffer> = (0..6).map(|_| pass(&mut rng, &delta, noise)).collect();
    let grid = SpectralGrid::new(BINS, 400.0, 700.0);
    let mut straight = Film::new(W, H, grid.clone());
    passes.iter().for_each(|p| straight.add_pass(p));
    let slice = |a: usize, b: usize| {
        let mut f = Film::starting_at(W, H, grid.clone(), a as u64);
        passes[a..b].iter().for_each(|p| f.add_pass(p));
        f
    };
    let mut merged = slice(4, 6);
    merged.merge(&slice(1, 4)).expect("adjacent");
    merged.merge(&slice(0, 1)).expect("adjacent");
    assert_eq!(merged, straight);
    assert_eq!(merged.image().data, straight.image().data);
    assert!(straight.blend.is_some());
    let mut plain = Film::starting_at(W, H, grid, 6);
    plain.add_pass(&PassBuffer::new(W * H, BINS));
    merged.merge(&plain).expect("adjacent");
    assert!(merged.blend.is_none());
}
