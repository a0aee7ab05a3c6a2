//! Strong forward scattering (Henyey-Greenstein g = 0.9, issue 19) in the fog cube, against an
//! independent reference: a backward path tracer written here.
//!
//! The light turns 135 degrees towards the camera, where the phase function is 0.0028 against
//! 15.1 in its forward peak: most of the medium's radiance is light scattered several times, and
//! a gathered estimate of it is dominated by rare forward rays that travel within a few degrees
//! of the camera rays (the peak) through the viewed column. Per pass this is a heavy right tail
//! (docs/study.md, "Strong forward scattering"); here every pass traces 10^5 forward rays
//! against 1024 to 16384 camera paths over 0.9 x 0.9 m, where a pass's estimate has a skewness
//! of -0.2 to 1.7 (measured).

use std::f64::consts::PI;

use super::{BINS, Z, exit_distance, fog_text, hg, light_dir};
use crate::common::*;

/// A unit vector perpendicular to `d` (unit), and a third completing the frame.
fn frame(d: [f64; 3]) -> ([f64; 3], [f64; 3]) {
    let a = if d[0].abs() < 0.9 {
        [1.0, 0.0, 0.0]
    } else {
        [0.0, 1.0, 0.0]
    };
    let c = cross(d, a);
    let l = dot(c, c).sqrt();
    let t1 = [c[0] / l, c[1] / l, c[2] / l];
    (t1, cross(d, t1))
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// A direction from the Henyey-Greenstein phase `g` around `axis` (inverse CDF of the cosine).
fn hg_sample(g: f64, axis: [f64; 3], u: f64, v: f64) -> [f64; 3] {
    let s = (1.0 - g * g) / (1.0 - g + 2.0 * g * u);
    let cos = ((1.0 + g * g - s * s) / (2.0 * g)).clamp(-1.0, 1.0);
    let sin = (1.0 - cos * cos).sqrt();
    let (t1, t2) = frame(axis);
    let (c, s) = ((2.0 * PI * v).cos(), (2.0 * PI * v).sin());
    let d: [f64; 3] = std::array::from_fn(|i| cos * axis[i] + sin * (c * t1[i] + s * t2[i]));
    let l = dot(d, d).sqrt();
    d.map(|x| x / l)
}

/// The medium radiance of the fog cube (grey or one bin: scattering `ss`, absorption `sa`, HG
/// `g`) under the parallel light of `fog_text`, averaged over the view square |x|, |y| < `half`
/// of the orthographic camera: (mean, standard error) over 16 batches of `paths`.
///
/// A backward path tracer independent of brume's code: paths start on the front face, go
/// along -Z, take free paths with the analog density, carry the albedo as weight, and at every
/// collision add the parallel light's single scattering (phase times the light's attenuation to
/// the cube's face). New directions come from the one-sample mixture (1/2 each) of the phase
/// around the path and the phase around the light's reverse direction, weighted by phase /
/// mixture density: with g = 0.9 plain phase sampling leaves the light's peak to chance and
/// its estimate has the heavy tail this test is about (a reference 100x slower for the same
/// error); the mixture bounds the product of the two peaks.
pub fn backward_reference(
    ss: f64,
    sa: f64,
    g: f64,
    half: f64,
    paths: u64,
    seed: u64,
) -> (f64, f64) {
    use rand::{Rng, SeedableRng};
    let d = light_dir();
    let back = d.map(|x| -x);
    let e = 4.0 / 400.0;
    let st = ss + sa;
    let mut rng = rand_pcg::Pcg64Mcg::seed_from_u64(seed);
    let batches: Vec<Vec<f64>> = (0..16)
        .map(|_| {
            let mut acc = 0.0;
            for _ in 0..paths {
                let mut p = [
                    half * (2.0 * rng.random::<f64>() - 1.0),
                    half * (2.0 * rng.random::<f64>() - 1.0),
                    0.5,
                ];
                let mut dir = [0.0, 0.0, -1.0];
                let mut w = 1.0;
                // Weights fall by the albedo (0.8 here) per collision: 0.8^256 is nothing.
                for _ in 0..256 {
                    let s = -(1.0 - rng.random::<f64>()).ln() / st;
                    if s >= exit_distance(p, dir) {
                        break;
                    }
                    p = std::array::from_fn(|i| p[i] + dir[i] * s);
                    w *= ss / st;
                    acc += w * hg(g, dot(back, dir)) * e * (-st * exit_distance(p, back)).exp();
                    let axis = if rng.random::<f64>() < 0.5 { dir } else { back };
                    let next = hg_sample(g, axis, rng.random(), rng.random());
                    let f = hg(g, dot(dir, next));
                    w *= f / (0.5 * f + 0.5 * hg(g, dot(back, next)));
                    dir = next;
                }
            }
            vec![acc / paths as f64]
        })
        .collect();
    let (m, se) = mean_and_se(&batches, 1);
    (m[0], se[0])
}

/// Passes per estimator: each pass is one sample (its own seed).
const PASSES: u64 = 20;

/// The medium layer's image mean of `PASSES` one-pass renders of `s` (seeds from `seed`), one
/// sample per pass (the fog is grey: every bin holds the same estimate; the mean of the bins).
fn pass_means(s: &Setup, seed: u64) -> Vec<f64> {
    let (w, h) = s.camera.resolution();
    (0..PASSES)
        .map(|i| {
            let img = render(s, seed + i, 1);
            let layer = &img.layers.iter().find(|(n, _)| n == "medium").unwrap().1;
            let m = region_mean(&img, layer, 0, w as usize, 0, h as usize);
            m.iter().sum::<f64>() / BINS as f64
        })
        .collect()
}

/// Every estimator, in the paper's pure method and with next-event estimation, against the
/// backward reference (16 x 16 pixels over 0.9 x 0.9 m of the cube's face, 10^5 forward rays
/// per pass): per estimator |z| <= 4 (1 % floor for the kernels' blur, as in the other tests),
/// and the mean of the ten (independent seeds) within 4 of its standard error.
///
/// The standard error of an estimator is the larger of its own (20 passes) and the ten's
/// pooled relative one: a per-pass estimate here is skewed, and a run of few passes that misses
/// the tail has both a low mean and a low spread, so that its own standard error alone
/// overstates z (16 passes of q = 1 spheres at 16 camera samples gave z = -4.0 at -4.8 %, with
/// less than half the spread 48 passes showed). Camera samples per pixel are each estimator's
/// most efficient of 4, 16, 64 (measured). An estimator is tested to 1.7-2.3 %, the mean of the
/// ten to 0.6 %; docs/study.md has 200-1280 passes of each, within 1.6 % of the reference.
#[test]
fn strong_forward_scattering_matches_a_backward_reference() {
    let (reference, ref_se) = backward_reference(0.8, 0.2, 0.9, 0.45, 125_000, 3);
    eprintln!(
        "g = 0.9 backward reference {reference:.5e} (se {:.2}%)",
        100.0 * ref_se / reference
    );
    // (volume, its settings, camera samples per pixel).
    let volumes: [(&str, &str, &str); 5] = [
        ("spheres q=1", "integrator.q=1", "64"),
        ("spheres q=0.3", "integrator.q=0.3", "16"),
        ("cylinder", "integrator.volume=\"cylinder\"", "4"),
        (
            "cylinder-truncated",
            "integrator.volume=\"cylinder-truncated\"",
            "4",
        ),
        ("cylinder-long", "integrator.volume=\"cylinder-long\"", "4"),
    ];
    let mut runs = Vec::new();
    for (k, (name, set, spp)) in volumes.iter().enumerate() {
        for (j, direct) in ["photons", "nee"].iter().enumerate() {
            let d = format!("integrator.direct=\"{direct}\"");
            let c = format!("integrator.camera_samples={spp}");
            let s = scene(
                &fog_text(""),
                &[
                    "media.fog.sigma_s=0.8",
                    "media.fog.g=0.9",
                    "camera.width=16",
                    "camera.height=16",
                    "camera.view_width=0.9",
                    "camera.view_height=0.9",
                    "integrator.max_depth=256",
                    set,
                    &c,
                    &d,
                ],
            );
            let x = pass_means(&s, 7000 + 100 * (2 * k + j) as u64);
            runs.push((format!("g = 0.9, {name} {direct}"), x));
        }
    }
    // Relative mean and variance per pass of each estimator, and pooled over the ten.
    let stats: Vec<(f64, f64)> = runs
        .iter()
        .map(|(_, x)| {
            let samples: Vec<Vec<f64>> = x.iter().map(|v| vec![*v]).collect();
            let (m, se) = mean_and_se(&samples, 1);
            (m[0], (se[0] / m[0]).powi(2) * PASSES as f64)
        })
        .collect();
    let pooled = stats.iter().map(|s| s.1).sum::<f64>() / stats.len() as f64;
    eprintln!(
        "pooled relative spread per pass {:.1} %",
        100.0 * pooled.sqrt()
    );
    let mut ratios = Vec::new();
    for ((name, _), (mean, rel_var)) in runs.iter().zip(&stats) {
        let rel_se = (rel_var.max(pooled) / PASSES as f64).sqrt();
        let combined = (mean * rel_se).hypot(ref_se);
        assert_bins(name, &[*mean], &[combined], &[reference], Z, 0.01);
        ratios.push((mean / reference, rel_se));
    }
    let n = ratios.len() as f64;
    let mean = ratios.iter().map(|r| r.0).sum::<f64>() / n;
    let se = (ratios.iter().map(|r| r.1 * r.1).sum::<f64>() / (n * n))
        .sqrt()
        .hypot(ref_se / reference);
    let z = (mean - 1.0) / se;
    eprintln!("mean of the ten / reference {mean:.4} (se {se:.4}, z {z:.2})");
    assert!(z.abs() <= Z, "the estimators' mean is off: z = {z:.2}");
}
