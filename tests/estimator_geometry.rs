//! Gather-volume geometry against brute force: chords of forward segments through spheres and
//! finite cylinders (by fine point sampling along the segment), and the bounding boxes.

use brume::integrator::estimator::{CameraAxis, Estimator, segment_cylinder, segment_sphere};
use brume::integrator::record::{CLASS_ALL, SegmentRecord, VolumeRecord};
use brume::integrator::{IntegratorDesc, VolumeKind};
use brume::medium::Medium;
use brume::spectrum::Spectrum;
use glam::Vec3;
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64Mcg;

fn rand_unit(rng: &mut Pcg64Mcg) -> Vec3 {
    let z = 2.0 * rng.random::<f32>() - 1.0;
    let phi = std::f32::consts::TAU * rng.random::<f32>();
    let s = (1.0 - z * z).sqrt();
    Vec3::new(s * phi.cos(), s * phi.sin(), z)
}

fn rand_point(rng: &mut Pcg64Mcg, r: f32) -> Vec3 {
    Vec3::new(rng.random(), rng.random(), rng.random()) * (2.0 * r) - Vec3::splat(r)
}

/// Length of `{lam in [0, len]: inside(o + v lam)}` by midpoint sampling, and the sample step.
fn brute_chord(o: Vec3, v: Vec3, len: f32, inside: impl Fn(Vec3) -> bool) -> (f32, f32) {
    let steps = 20_000;
    let h = len / steps as f32;
    let k = (0..steps)
        .filter(|&i| inside(o + v * ((i as f32 + 0.5) * h)))
        .count();
    (k as f32 * h, h)
}

#[test]
fn sphere_chords_match_brute_force() {
    let mut rng = Pcg64Mcg::seed_from_u64(700);
    let mut hits = 0;
    let mut partial = 0;
    for _ in 0..2000 {
        let c = rand_point(&mut rng, 1.0);
        let r = 0.05 + 0.5 * rng.random::<f32>();
        let o = rand_point(&mut rng, 1.5);
        // Aim near the sphere so that most segments overlap it.
        let v = (c + rand_point(&mut rng, 1.5 * r) - o).normalize();
        let len = 3.0 * rng.random::<f32>();
        let (bf, h) = brute_chord(o, v, len, |p| (p - c).length() < r);
        match segment_sphere(o, v, len, c, r) {
            None => assert!(bf <= 2.0 * h, "missed a chord of {bf}"),
            Some(ch) => {
                hits += 1;
                assert!(
                    (ch.len() - bf).abs() <= 2.0 * h + 1e-5,
                    "{} vs {bf}",
                    ch.len()
                );
                let outside = |p: Vec3| (p - c).length() >= r;
                assert_eq!(ch.full, outside(o) && outside(o + v * len));
                partial += (!ch.full) as usize;
                assert!((c - (o + v * ch.lam_in)).length() <= r * 1.0001 || ch.lam_in == 0.0);
            }
        }
    }
    assert!(hits > 300 && partial > 80, "{hits} hits, {partial} partial");
}

#[test]
fn cylinder_chords_match_brute_force() {
    let mut rng = Pcg64Mcg::seed_from_u64(701);
    let mut hits = 0;
    for k in 0..3000 {
        let axis = CameraAxis {
            origin: rand_point(&mut rng, 0.5),
            dir: rand_unit(&mut rng),
            start: 0.0,
            len: 0.2 + 1.5 * rng.random::<f32>(),
        };
        let r = 0.05 + 0.3 * rng.random::<f32>();
        let o = rand_point(&mut rng, 1.5);
        // Every 10th ray parallel or perpendicular to the axis: the degenerate branches.
        let v = match k % 10 {
            0 => axis.dir,
            1 => -axis.dir,
            2 => axis.dir.any_orthonormal_vector(),
            _ => {
                let target = axis.origin + axis.dir * (axis.len * rng.random::<f32>());
                (target + rand_point(&mut rng, 1.5 * r) - o).normalize()
            }
        };
        let o = if k % 10 < 3 {
            axis.origin + (o - axis.origin) * 0.2 - v
        } else {
            o
        };
        let len = 3.0 * rng.random::<f32>();
        let inside = |p: Vec3| {
            let d = p - axis.origin;
            let a = d.dot(axis.dir);
            (d - axis.dir * a).length() < r && (0.0..=axis.len).contains(&a)
        };
        let (bf, h) = brute_chord(o, v, len, inside);
        match segment_cylinder(&axis, r, o, v, len) {
            None => assert!(bf <= 2.0 * h, "case {k}: missed a chord of {bf}"),
            Some(ch) => {
                hits += 1;
                assert!(
                    (ch.len() - bf).abs() <= 2.0 * h + 1e-4,
                    "case {k}: {} vs {bf}",
                    ch.len()
                );
                for (lam, tau) in [(ch.lam1, ch.tau1), (ch.lam2, ch.tau2)] {
                    let a = (o + v * lam - axis.origin).dot(axis.dir);
                    assert!((a - tau).abs() < 1e-4, "case {k}: tau {tau} vs {a}");
                }
                assert!((ch.uv - v.dot(axis.dir)).abs() < 1e-6);
            }
        }
    }
    assert!(hits > 600, "{hits} hits");
}

/// Every estimator's gather bounds contain its volume: points on a sphere of radius r around
/// the volume's distance (spheres), or on the surface of the cylinder over the segment's first
/// `s` metres (cylinders), including its rims.
#[test]
fn estimator_bounds_contain_their_volumes() {
    let medium = Medium::new(&Spectrum::splat(1.0, 1), &Spectrum::ZERO, 0.0, 1).unwrap();
    let mut desc = IntegratorDesc::default();
    let mut rng = Pcg64Mcg::seed_from_u64(702);
    for kind in [
        VolumeKind::Spheres,
        VolumeKind::Cylinder,
        VolumeKind::CylinderTruncated,
        VolumeKind::CylinderLong,
    ] {
        desc.volume = kind;
        let e = Estimator::from_desc(&desc, &[1.0], std::slice::from_ref(&medium)).unwrap();
        for _ in 0..200 {
            let a = rand_point(&mut rng, 1.0);
            let u = rand_unit(&mut rng);
            let (len, r) = (rng.random::<f32>() * 2.0, rng.random::<f32>() * 0.3);
            let seg = SegmentRecord {
                origin: a,
                pixel: 0,
                dir: u,
                throughput: 0,
                medium: 0,
                classes: CLASS_ALL,
            };
            // Spheres keep their weight in `scale`; a cylinder piece its start (here 0: whole).
            let v = VolumeRecord {
                segment: 0,
                s: len,
                scale: match kind {
                    VolumeKind::Spheres => 1.0,
                    VolumeKind::Cylinder
                    | VolumeKind::CylinderTruncated
                    | VolumeKind::CylinderLong => 0.0,
                },
            };
            let b = e.bounds(&seg, &v, r);
            let (e1, e2) = u.any_orthonormal_pair();
            for _ in 0..200 {
                let p = match kind {
                    VolumeKind::Spheres => a + u * len + rand_unit(&mut rng) * r,
                    VolumeKind::Cylinder
                    | VolumeKind::CylinderTruncated
                    | VolumeKind::CylinderLong => {
                        let phi = std::f32::consts::TAU * rng.random::<f32>();
                        let t = len * rng.random::<f32>().clamp(0.0, 1.0);
                        a + u * t + (e1 * phi.cos() + e2 * phi.sin()) * r
                    }
                };
                for i in 0..3 {
                    assert!(
                        p[i] >= b.min[i] - 1e-5 && p[i] <= b.max[i] + 1e-5,
                        "{kind:?}: {p} outside its bounds"
                    );
                }
            }
        }
    }
}
