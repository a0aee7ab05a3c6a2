//! Delta and ratio tracking against the exact optical depth of the same grid (`GridRay`, itself
//! checked against quadrature in `density::grid::tests`): the majorant bounds the field, the
//! DDA covers the ray's part in the box, free flights follow `1 - e^{-sigma D(s)}`
//! (chi-square) and ratio tracking's mean is `e^{-st_l D}` per bin.

use std::sync::Arc;

use glam::{Mat4, Quat, Vec3};
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64;
use statrs::distribution::{ChiSquared, ContinuousCDF};

use super::*;
use crate::medium::density::GridField;
use crate::medium::density::grid::GridData;

/// A 13 x 10 x 9 grid in a rotated box: a dense blob in one corner, zeros elsewhere except a
/// faint haze in one slab (so blocks of 4 see empty, faint and dense blocks).
fn field() -> Arc<GridField> {
    let mut rng = Pcg64::seed_from_u64(5);
    let res = [13, 10, 9];
    let mut values = vec![0.0f32; 13 * 10 * 9];
    for z in 0..9 {
        for y in 0..10 {
            for x in 0..13 {
                let v = if x < 6 && y < 5 && z < 5 {
                    3.0 * rng.random::<f32>()
                } else if z == 7 {
                    0.05 * rng.random::<f32>()
                } else {
                    0.0
                };
                values[(z * 10 + y) * 13 + x] = v;
            }
        }
    }
    let unit = Mat4::from_scale_rotation_translation(
        Vec3::new(2.6, 2.0, 1.8),
        Quat::from_euler(glam::EulerRot::ZYX, 0.2, -0.3, 0.1),
        Vec3::new(-1.3, -1.0, -0.9),
    );
    let data = GridData {
        res,
        values,
        bounds: None,
    };
    Arc::new(GridField::new(data, 1.0, Some(unit), "test".into()).expect("valid grid"))
}

fn rays(seed: u64, count: usize) -> Vec<(Vec3, Vec3)> {
    let mut rng = Pcg64::seed_from_u64(seed);
    let mut v = |a: f32| Vec3::new(rng.random(), rng.random(), rng.random()) * 2.0 * a - a;
    (0..count).map(|_| (v(2.5), v(1.0).normalize())).collect()
}

fn majorants() -> Vec<Majorant> {
    let g = field();
    vec![
        Majorant::new(g.clone(), Some(4)),
        Majorant::new(g.clone(), Some(1)),
        Majorant::new(g, None),
    ]
}

#[test]
fn the_majorant_bounds_the_field_and_the_dda_covers_the_box() {
    for maj in majorants() {
        for (o, d) in rays(1, 200) {
            let tr = Tracker::new(&maj, o, d);
            let mut last: Option<f64> = None;
            maj.segments(tr.ray, 0.0, f64::INFINITY, |t0, t1, m| {
                if let Some(l) = last {
                    assert!((t0 - l).abs() < 1e-9, "gap between blocks: {l} -> {t0}");
                }
                last = Some(t1);
                for i in 0..=20 {
                    let t = t0 + (t1 - t0) * i as f64 / 20.0;
                    let rho = tr.rho(t as f32);
                    assert!(rho <= m * (1.0 + 1e-6) + 1e-7, "rho {rho} > majorant {m}");
                }
                true
            });
            // The blocks end where the exact depth stops growing (the box's exit).
            let ray = maj.grid().along(o, d);
            if let Some(end) = last {
                let (a, b) = (ray.depth(end as f32), ray.depth(end as f32 + 10.0));
                assert!(
                    (a - b).abs() <= 1e-5 * b.max(1.0),
                    "depth beyond the blocks"
                );
            } else {
                assert_eq!(
                    ray.depth(100.0),
                    0.0,
                    "a ray missing every block crosses fog"
                );
            }
        }
    }
    let coarse = &majorants()[0];
    assert!(coarse.blocks() == 4 * 3 * 3);
}

/// Chi-square of delta-tracking flight distances (each mapped by `warp`) binned by their exact
/// optical depth `sigma D(s)`: the cumulative `1 - e^{-u}` makes the bins' expected counts
/// equal; escapes are one more bin.
fn flight_chi2(maj: &Majorant, warp: impl Fn(f32) -> f32, seed: u64) -> f64 {
    let mut rng = Pcg64::seed_from_u64(seed);
    let (o, d) = (
        Vec3::new(-2.0, -1.6, -1.2),
        Vec3::new(1.0, 0.8, 0.55).normalize(),
    );
    let (sigma, bins, n) = (1.7f32, 20, 200_000);
    let tr = Tracker::new(maj, o, d);
    let ray = maj.grid().along(o, d);
    let total = sigma as f64 * ray.depth(f32::INFINITY) as f64;
    assert!(total > 2.0, "the test ray crosses too little fog: {total}");
    let p_escape = (-total).exp();
    let mut counts = vec![0u64; bins + 1];
    for _ in 0..n {
        match tr.free_flight(0.0, f32::INFINITY, sigma, &mut rng) {
            None => counts[bins] += 1,
            Some(s) => {
                let u = sigma as f64 * ray.depth(warp(s)) as f64;
                let c = (1.0 - (-u).exp()) / (1.0 - p_escape);
                counts[((c * bins as f64) as usize).min(bins - 1)] += 1;
            }
        }
    }
    let mut chi2 = 0.0;
    for (i, &c) in counts.iter().enumerate() {
        let p = if i == bins {
            p_escape
        } else {
            (1.0 - p_escape) / bins as f64
        };
        let e = p * n as f64;
        chi2 += (c as f64 - e).powi(2) / e;
    }
    chi2
}

/// The 1e-4 upper quantile of chi-square with 20 degrees of freedom (21 bins, total fixed).
fn bound() -> f64 {
    ChiSquared::new(20.0).expect("dof").inverse_cdf(1.0 - 1e-4)
}

/// Delta-tracking flights follow the exact depth, with the global majorant and two block
/// sizes.
#[test]
fn delta_tracking_flights_follow_the_exact_depth() {
    for (i, maj) in majorants().iter().enumerate() {
        let chi2 = flight_chi2(maj, |s| s, 11 + i as u64);
        assert!(
            chi2 < bound(),
            "chi2 {chi2} over {} ({} blocks)",
            bound(),
            maj.blocks()
        );
    }
}

/// The same chi-square catches flights 3 % too short: the test has power.
#[test]
fn flights_slightly_too_short_are_caught() {
    let maj = Majorant::new(field(), Some(4));
    let chi2 = flight_chi2(&maj, |s| s * 0.97, 11);
    assert!(
        chi2 > 10.0 * bound(),
        "a 3 % bias went unnoticed: chi2 {chi2}"
    );
}

/// Ratio tracking's per-bin mean against `e^{-st_l D}` over 3 bins (one of them 4x the
/// others, so the update factors differ per bin), |z| <= 4 on the sample standard error, over
/// several rays and partial intervals.
#[test]
fn ratio_tracking_is_unbiased_per_bin() {
    let mut rng = Pcg64::seed_from_u64(17);
    let st = Spectrum::from_slice(&[0.4, 1.6, 0.9]);
    for maj in majorants() {
        for (i, (o, d)) in rays(2, 12).into_iter().enumerate() {
            let tr = Tracker::new(&maj, o, d);
            let ray = maj.grid().along(o, d);
            let (from, to) = if i % 2 == 0 {
                (0.0, f32::INFINITY)
            } else {
                (0.5, 2.5)
            };
            let depth = (ray.depth(to) - ray.depth(from)) as f64;
            let n = 20_000;
            let (mut sum, mut sum2) = ([0.0f64; 3], [0.0f64; 3]);
            for _ in 0..n {
                let t = tr.transmittance((from, to), &st, 3, &mut rng);
                for l in 0..3 {
                    sum[l] += t.0[l] as f64;
                    sum2[l] += (t.0[l] as f64).powi(2);
                }
            }
            for l in 0..3 {
                let mean = sum[l] / n as f64;
                let var = (sum2[l] / n as f64 - mean * mean).max(0.0);
                let se = (var / n as f64).sqrt().max(1e-9);
                let exact = (-(st.0[l] as f64) * depth).exp();
                let z = (mean - exact) / se;
                assert!(z.abs() <= 4.0, "bin {l}: {mean} vs {exact}, z = {z}");
            }
        }
    }
}
