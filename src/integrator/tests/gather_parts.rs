//! The volumes' BVH in spatial parts (`gather::volume_parts`): a segment query must meet every
//! volume whose bounds it crosses exactly once, whichever part holds it, checked against a
//! brute-force test of every volume's box on a real fog-cube pass of several parts.

use glam::Vec3;
use rand::{Rng, SeedableRng};

use super::{shipped_scene, untiled_pass};
use crate::integrator::gather::Gather;

/// Whether the segment `[o, o + d len]` meets the box `[lo, hi]` (slab test).
fn meets(o: Vec3, d: Vec3, len: f32, lo: Vec3, hi: Vec3) -> bool {
    let (mut t0, mut t1) = (0.0f32, len);
    for a in 0..3 {
        let inv = 1.0 / d[a];
        let (u, v) = ((lo[a] - o[a]) * inv, (hi[a] - o[a]) * inv);
        t0 = t0.max(u.min(v));
        t1 = t1.min(u.max(v));
    }
    t0 <= t1
}

#[test]
fn a_segment_meets_every_volume_it_crosses_once_whatever_its_part() {
    let (scene, integrator) = shipped_scene("fog-cube.toml", &["integrator.q=0.05"]);
    let mut out = untiled_pass(&scene, &integrator, 2);
    let radii = integrator.radii(0);
    let g = Gather::from_output(&integrator.estimator, radii, &mut out);
    let n = g.volumes.len();
    assert!(n > 4 << 16, "{n} volumes: fewer than 5 parts' worth");
    let radius = radii.bound();
    let boxes: Vec<(Vec3, Vec3)> = g
        .volumes
        .iter()
        .map(|v| {
            let b = integrator
                .estimator
                .bounds(&g.segments[v.segment as usize], v, radius);
            (Vec3::from(b.min), Vec3::from(b.max))
        })
        .collect();
    let (lo, hi) = boxes
        .iter()
        .fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(lo, hi), b| {
            (lo.min(b.0), hi.max(b.1))
        });
    let mut rng = rand::rngs::StdRng::seed_from_u64(9);
    let (mut expected_total, mut queries_in_several_parts) = (0usize, 0);
    for _ in 0..300 {
        let o = lo + (hi - lo) * Vec3::new(rng.random(), rng.random(), rng.random());
        let d = Vec3::new(
            rng.random::<f32>() - 0.5,
            rng.random::<f32>() - 0.5,
            rng.random::<f32>() - 0.5,
        )
        .normalize();
        let len = rng.random::<f32>() * (hi - lo).length();
        let mut seen = vec![0u8; n];
        let base = g.volumes.as_ptr() as usize;
        g.volumes_along(o, d, len, |_, v| {
            let i = (v as *const _ as usize - base) / std::mem::size_of_val(v);
            seen[i] += 1;
        });
        assert!(seen.iter().all(|&c| c <= 1), "a volume met twice");
        // Every volume whose box the segment crosses (shrunk by a hair, for rounding) is met.
        let shrink = Vec3::splat(1e-4);
        for (i, (a, b)) in boxes.iter().enumerate() {
            if meets(o, d, len, *a + shrink, *b - shrink) {
                assert_eq!(seen[i], 1, "volume {i} crossed but not met");
                expected_total += 1;
            }
        }
        let (first, last) = (
            seen.iter().position(|&c| c > 0),
            seen.iter().rposition(|&c| c > 0),
        );
        if let (Some(f), Some(l)) = (first, last)
            && l - f > n / 4
        {
            queries_in_several_parts += 1;
        }
    }
    assert!(expected_total > 10_000, "only {expected_total} crossings");
    assert!(queries_in_several_parts > 30, "{queries_in_several_parts}");
}
