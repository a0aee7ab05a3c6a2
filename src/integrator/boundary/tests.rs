//! The cut ball's geometry against brute force, and the clipped estimator's mean against the
//! cut ball's volume under isotropic uniform random lines. Fixed seeds.

use super::*;
use crate::integrator::estimator::segment_sphere;
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64Mcg;

fn unit(rng: &mut Pcg64Mcg) -> Vec3 {
    let z: f32 = rng.random_range(-1.0..1.0);
    let phi: f32 = rng.random_range(0.0..std::f32::consts::TAU);
    let s = (1.0 - z * z).max(0.0).sqrt();
    Vec3::new(s * phi.cos(), s * phi.sin(), z)
}

/// A segment from the origin along `dir` (unit), with a start plane of normal `n0` (into the
/// medium) through the origin and an end plane of normal `n1` at `end` along it.
fn planes(dir: Vec3, n0: Option<Vec3>, end: Option<(f32, Vec3)>) -> Planes {
    let mut p = Planes::NONE;
    if let Some(n0) = n0 {
        p.start_cos = n0.dot(dir);
        p.start_n = Oct::encode(n0);
    }
    if let Some((t, n1)) = end {
        p.end = t;
        p.end_n = Oct::encode(n1);
    }
    p
}

/// A camera segment along a random direction and the sphere at `s` on it, with planes at the
/// given distances of its centre (`d0` behind, `d1` ahead, in radii) tilted at random.
fn cut_ball(rng: &mut Pcg64Mcg, d0: f32, d1: f32) -> (Vec3, Planes, Vec3, Vec3, Vec3) {
    let dir = unit(rng);
    let tilt = |rng: &mut Pcg64Mcg, towards: Vec3| loop {
        let n = unit(rng);
        if n.dot(towards) > 0.3 {
            return n;
        }
    };
    let n0 = tilt(rng, dir);
    let n1 = tilt(rng, -dir);
    // The start plane passes through the origin, d0 from the centre; the end plane's point
    // is `end` along the ray, d1 from the centre.
    let c = Vec3::new(0.3, -0.2, 0.5);
    let s = d0 / n0.dot(dir);
    let origin = c - dir * s;
    let end = s + d1 / (-n1.dot(dir));
    let p = planes(dir, Some(n0), Some((end, n1)));
    assert!((origin + dir * s - c).length() < 1e-5);
    (origin, p, dir, n0, n1)
}

#[test]
fn cap_fractions_are_the_balls_volume_beyond_a_plane() {
    let mut rng = Pcg64Mcg::seed_from_u64(7);
    let n = 400_000;
    let pts: Vec<Vec3> = (0..n)
        .map(|_| {
            loop {
                let p = Vec3::new(
                    rng.random_range(-1.0..1.0),
                    rng.random_range(-1.0..1.0),
                    rng.random_range(-1.0..1.0),
                );
                if p.length_squared() <= 1.0 {
                    return p;
                }
            }
        })
        .collect();
    for delta in [0.0f32, 0.1, 0.35, 0.6, 0.9, 1.0] {
        let beyond = pts.iter().filter(|p| p.y < -delta).count() as f64 / n as f64;
        let want = cap_fraction(delta) as f64;
        let se = (want * (1.0 - want) / n as f64).sqrt().max(1e-9);
        eprintln!(
            "delta {delta}: brute {beyond:.5} formula {want:.5} z {:.2}",
            (beyond - want) / se
        );
        assert!((beyond - want).abs() <= 4.0 * se + 1e-6, "delta {delta}");
    }
    assert_eq!(cap_fraction(0.0), 0.5);
    assert_eq!(cap_fraction(1.0), 0.0);
}

/// The clipped chord is the part of the segment inside the ball and on the medium's side of
/// both planes, against a fine midpoint rule along it.
#[test]
fn clipped_chords_are_the_part_inside_the_cut_ball() {
    let mut rng = Pcg64Mcg::seed_from_u64(11);
    let r = 0.5;
    let mut clipped = 0;
    for _ in 0..2000 {
        let (d0, d1) = (
            rng.random_range(0.0..1.2) * r,
            rng.random_range(0.0..1.2) * r,
        );
        let (origin, p, dir, n0, n1) = cut_ball(&mut rng, d0, d1);
        let s = d0 / n0.dot(dir);
        let c = origin + dir * s;
        let o = c + unit(&mut rng) * rng.random_range(0.0..1.5);
        let d = unit(&mut rng);
        let len = rng.random_range(0.2..2.0);
        let end_p = origin + dir * p.end;
        let inside = |x: Vec3| {
            (x - c).length() <= r && n0.dot(x - origin) >= 0.0 && n1.dot(x - end_p) >= 0.0
        };
        let k = 20_000;
        let brute = (0..k)
            .filter(|&i| inside(o + d * ((i as f32 + 0.5) / k as f32 * len)))
            .count() as f32
            * len
            / k as f32;
        let got = segment_sphere(o, d, len, c, r)
            .and_then(|ch| p.clip((origin, dir, s), (o, d), (ch.lam_in, ch.lam_out), r))
            .map_or(0.0, |(a, b, _)| b - a);
        // The normals are stored in 32 bits (1e-4 rad): allow that much of a radius.
        assert!(
            (got - brute).abs() <= 2.0 * len / k as f32 + 2e-4 * r,
            "{got} vs {brute}"
        );
        if got > 0.0 && (d0 < r || d1 < r) {
            clipped += 1;
        }
    }
    assert!(clipped > 300, "{clipped} clipped chords");
}

/// Isotropic uniform random lines crossing a bounding ball of radius `rb` put a mean chord
/// length of `|A| / (pi rb^2)` into any region A inside it. So the clipped track-length
/// estimate `chord / (fraction V)`, times `pi rb^2`, has mean 1 for every cut: the fraction is
/// the cut ball's volume, for one plane at any distance, and for two planes on opposite sides.
#[test]
fn clipped_estimates_average_the_fluence_over_the_cut_ball() {
    let mut rng = Pcg64Mcg::seed_from_u64(3);
    let (r, rb) = (0.5f32, 0.6f32);
    let v = 4.0 / 3.0 * std::f64::consts::PI * (r as f64).powi(3);
    for (d0, d1) in [
        (2.0, 2.0),
        (0.0, 2.0),
        (0.3, 2.0),
        (2.0, 0.7),
        (0.2, 0.5),
        (0.05, 0.05),
    ] {
        let (origin, p, dir, n0, _) = cut_ball(&mut rng, d0 * r, d1 * r);
        let s = d0 * r / n0.dot(dir);
        let c = origin + dir * s;
        let lines = 400_000;
        let (mut sum, mut sum2) = (0.0f64, 0.0f64);
        for _ in 0..lines {
            let d = unit(&mut rng);
            // A uniform point on the disc of radius rb through c, perpendicular to d.
            let (a, b) = d.any_orthonormal_pair();
            let (rho, phi) = (
                rb * rng.random::<f32>().sqrt(),
                rng.random_range(0.0..std::f32::consts::TAU),
            );
            let o = c + a * (rho * phi.cos()) + b * (rho * phi.sin()) - d * 2.0 * rb;
            let x = segment_sphere(o, d, 4.0 * rb, c, r)
                .and_then(|ch| p.clip((origin, dir, s), (o, d), (ch.lam_in, ch.lam_out), r))
                .map_or(0.0, |(a, b, f)| (b - a) as f64 / (f as f64 * v));
            let e = x * std::f64::consts::PI * (rb as f64).powi(2);
            sum += e;
            sum2 += e * e;
        }
        let mean = sum / lines as f64;
        let se = ((sum2 / lines as f64 - mean * mean) / lines as f64).sqrt();
        eprintln!(
            "planes at {d0} and {d1} radii: mean {mean:.4} se {se:.4} z {:.2}",
            (mean - 1.0) / se
        );
        assert!(
            (mean - 1.0).abs() <= 4.0 * se,
            "planes at {d0}, {d1}: {mean} (se {se})"
        );
    }
}

/// Two caps of parallel planes: facing each other (a slab) they share nothing; on the same
/// side they share the smaller one.
#[test]
fn parallel_caps_overlap_as_they_should() {
    let n = Vec3::new(0.2, -0.9, 0.3).normalize();
    assert_eq!(overlap_fraction((0.3, n), (0.1, -n)), 0.0);
    let same = overlap_fraction((0.3, n), (0.6, n));
    assert!(
        (same - cap_fraction(0.6)).abs() < 1e-4,
        "{same} vs {}",
        cap_fraction(0.6)
    );
}
