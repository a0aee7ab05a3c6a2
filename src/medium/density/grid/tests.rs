//! The grid field: its sample convention (Mitsuba 3's), the exact depth along rays against
//! quadrature, the inverse, and refusals.

use glam::{DVec3, Mat4, Quat, Vec3};
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64;

use super::*;

/// Its unit box to world.
fn placement() -> Mat4 {
    Mat4::from_scale_rotation_translation(
        Vec3::new(2.0, 1.5, 1.0),
        Quat::from_euler(glam::EulerRot::ZYX, 0.3, -0.5, 0.2),
        Vec3::new(-1.0, -0.7, -0.4),
    )
}

/// A 5 x 4 x 3 grid of random samples in [0, 2) with some zeros, in a rotated, stretched box.
fn field(seed: u64) -> GridField {
    let mut rng = Pcg64::seed_from_u64(seed);
    let values = (0..60)
        .map(|_| {
            if rng.random::<f32>() < 0.2 {
                0.0
            } else {
                2.0 * rng.random::<f32>()
            }
        })
        .collect();
    let data = GridData {
        res: [5, 4, 3],
        values,
        bounds: None,
    };
    GridField::new(data, 1.0, Some(placement()), "test".into()).unwrap()
}

fn rays(seed: u64) -> Vec<(Vec3, Vec3)> {
    let mut rng = Pcg64::seed_from_u64(seed);
    let mut v = |a: f32| Vec3::new(rng.random(), rng.random(), rng.random()) * 2.0 * a - a;
    let mut out: Vec<(Vec3, Vec3)> = (0..40).map(|_| (v(3.0), v(1.0).normalize())).collect();
    // Rays along the box's axes and through sample planes.
    out.push((Vec3::new(-3.0, 0.0, 0.0), Vec3::X));
    out.push((Vec3::new(0.1, -3.0, 0.2), Vec3::Y));
    out
}

/// Composite Simpson of `at` along the ray over the part of `[0, s]` inside the box (found in
/// the unit box's coordinates, so the jump to 0 at the box's faces is not integrated across).
fn quadrature(f: &GridField, o: Vec3, d: Vec3, s: f32) -> f64 {
    let inv = placement().inverse();
    let (a, b) = (inv.transform_point3(o), inv.transform_vector3(d));
    let (mut t0, mut t1) = (0.0f32, s);
    for k in 0..3 {
        if b[k] == 0.0 {
            if !(0.0..=1.0).contains(&a[k]) {
                return 0.0;
            }
            continue;
        }
        let (x, y) = (-a[k] / b[k], (1.0 - a[k]) / b[k]);
        (t0, t1) = (t0.max(x.min(y)), t1.min(x.max(y)));
    }
    if t0 >= t1 {
        return 0.0;
    }
    let n = 20000;
    let h = (t1 - t0) as f64 / n as f64;
    // Points just inside the ends: at the faces themselves f32 rounding may fall outside.
    let at = |t: f64| f.at(o + d * (t.clamp(t0 as f64 + 1e-6, t1 as f64 - 1e-6)) as f32) as f64;
    let sum: f64 = (0..=n)
        .map(|i| {
            let w = if i == 0 || i == n {
                1.0
            } else if i % 2 == 1 {
                4.0
            } else {
                2.0
            };
            w * at(t0 as f64 + i as f64 * h)
        })
        .sum();
    sum * h / 3.0
}

/// Asserts that the ray's depth to `s` and the one-off depth match the quadrature within 2e-5
/// (relative to 1 + depth); the ray's depth.
fn matches_quadrature(f: &GridField, ray: &GridRay, (o, d): (Vec3, Vec3), s: f32) -> f64 {
    let want = quadrature(f, o, d, s);
    let got = ray.depth(s) as f64;
    assert!(
        (got - want).abs() <= 2e-5 * (1.0 + want),
        "{o} {d} {s}: {got} vs {want}"
    );
    let by_points = f.depth(o, d, s) as f64;
    assert!(
        (by_points - want).abs() <= 2e-5 * (1.0 + want),
        "{o} {d} {s}: one-off {by_points} vs {want}"
    );
    got
}

#[test]
fn samples_sit_at_cell_centres_and_clamp_in_the_outer_half_cells() {
    let data = GridData {
        res: [2, 1, 1],
        values: vec![1.0, 3.0],
        bounds: Some((Vec3::ZERO, Vec3::new(2.0, 1.0, 1.0))),
    };
    let g = GridField::new(data, 1.0, None, "t".into()).unwrap();
    let at = |x: f32| g.at(Vec3::new(x, 0.5, 0.5));
    // Centres at x = 0.5 and 1.5; clamped beyond them; zero outside the box.
    assert_eq!((at(0.5), at(1.5), at(1.0)), (1.0, 3.0, 2.0));
    assert_eq!((at(0.1), at(1.9)), (1.0, 3.0));
    assert_eq!((at(-0.01), at(2.01)), (0.0, 0.0));
    assert_eq!(g.at(Vec3::new(1.0, 1.01, 0.5)), 0.0);
}

#[test]
fn depth_is_the_integral_of_the_density_and_distance_inverts_it() {
    for seed in 0..3 {
        let f = field(seed);
        for (o, d) in rays(seed + 10) {
            let ray = f.along(o, d);
            for s in [0.3f32, 1.7, 4.0, 7.5] {
                let got = matches_quadrature(&f, &ray, (o, d), s);
                assert!((f.depth(o, d, s) as f64 - got).abs() <= 1e-5 * (1.0 + got));
                let back = ray.distance(ray.depth(s));
                // Where the density is 0 up to s, any distance in the gap has that depth.
                let same = (ray.depth(back) - ray.depth(s)).abs() <= 1e-5 * (1.0 + got as f32);
                assert!(same && back <= s + 1e-4, "{o} {d} {s}: back {back}");
                let rho = ray.rho(s) as f64;
                assert!((rho - f.at(o + d * s) as f64).abs() < 1e-4, "rho at {s}");
            }
            let total = ray.depth(f32::INFINITY);
            assert_eq!(ray.distance(total * 1.001 + 1e-3), f32::INFINITY);
        }
    }
}

#[test]
fn a_grid_of_equal_samples_is_the_uniform_medium_inside_its_box() {
    let data = GridData {
        res: [7, 3, 4],
        values: vec![0.75; 84],
        bounds: Some((Vec3::new(-1.0, -1.0, -1.0), Vec3::new(1.0, 1.0, 1.0))),
    };
    let g = GridField::new(data, 2.0, None, "t".into()).unwrap();
    let d = Vec3::new(0.3, -0.2, 0.9).normalize();
    let ray = g.along(Vec3::ZERO, d);
    // From the centre the ray leaves the box where its z reaches 1.
    let exit = 1.0 / d.z;
    for s in [0.1f32, 0.5, 1.0] {
        assert!((ray.depth(s) - 1.5 * s).abs() < 1e-6);
        assert!((ray.distance(1.5 * s) - s).abs() < 1e-6);
    }
    assert!((ray.depth(10.0) - 1.5 * exit).abs() < 1e-5);
}

#[test]
fn bad_samples_and_empty_grids_are_refused() {
    let mk = |values: Vec<f32>| GridData {
        res: [2, 2, 1],
        values,
        bounds: Some((Vec3::ZERO, Vec3::ONE)),
    };
    let e = GridField::new(mk(vec![0.0, 1.0, -1.0, 0.0]), 1.0, None, "t".into()).unwrap_err();
    assert_eq!(
        e,
        GridValueError::Bad {
            i: 0,
            j: 1,
            k: 0,
            value: -1.0
        }
    );
    let e = GridField::new(mk(vec![0.0, f32::NAN, 1.0, 0.0]), 1.0, None, "t".into()).unwrap_err();
    assert!(matches!(e, GridValueError::Bad { i: 1, j: 0, .. }));
    let e = GridField::new(mk(vec![0.0; 4]), 1.0, None, "t".into()).unwrap_err();
    assert_eq!(e, GridValueError::Empty);
    let none = GridData {
        bounds: None,
        ..mk(vec![1.0; 4])
    };
    assert_eq!(
        GridField::new(none, 1.0, None, "t".into()).unwrap_err(),
        GridValueError::Placement
    );
}

/// A 37 x 21 x 29 grid (several occupancy blocks per axis) that is empty but for a random blob
/// and two lone samples, one on the corner shared by eight blocks: rays cross whole empty
/// blocks and blocks whose only smoke is a sample on their boundary.
fn sparse_field(seed: u64) -> (GridField, Vec<Vec3>) {
    let res = [37usize, 21, 29];
    let mut rng = Pcg64::seed_from_u64(seed);
    let mut values = vec![0.0f32; res[0] * res[1] * res[2]];
    let idx = |x: usize, y: usize, z: usize| (z * res[1] + y) * res[0] + x;
    for z in 3..11 {
        for y in 10..19 {
            for x in 20..31 {
                values[idx(x, y, z)] = 2.0 * rng.random::<f32>();
            }
        }
    }
    let lone = [[16usize, 8, 8], [5, 13, 22]];
    for [x, y, z] in lone {
        values[idx(x, y, z)] = 3.0;
    }
    let data = GridData {
        res,
        values,
        bounds: None,
    };
    let f = GridField::new(data, 1.0, Some(placement()), "sparse".into()).unwrap();
    let to_world = |[x, y, z]: [usize; 3]| {
        let unit = Vec3::new(
            (x as f32 + 0.5) / res[0] as f32,
            (y as f32 + 0.5) / res[1] as f32,
            (z as f32 + 0.5) / res[2] as f32,
        );
        placement().transform_point3(unit)
    };
    (f, lone.iter().map(|&q| to_world(q)).collect())
}

/// Random rays and rays from random origins through the given points.
fn rays_through(seed: u64, targets: &[Vec3]) -> Vec<(Vec3, Vec3)> {
    let mut out = rays(seed);
    let mut rng = Pcg64::seed_from_u64(seed + 1000);
    for &p in targets {
        for _ in 0..6 {
            let o = Vec3::new(rng.random(), rng.random(), rng.random()) * 6.0 - 3.0;
            out.push((o, (p - o).normalize()));
        }
    }
    out
}

#[test]
fn crossings_are_the_sorted_plane_crossings() {
    let (f, _) = sparse_field(1);
    let n = f.extent();
    let mut rng = Pcg64::seed_from_u64(5);
    for _ in 0..300 {
        let a = DVec3::new(rng.random(), rng.random(), rng.random()) * 80.0 - 20.0;
        let mut b = DVec3::new(rng.random(), rng.random(), rng.random()) * 2.0 - 1.0;
        // Some rays parallel to a plane.
        if rng.random::<f32>() < 0.2 {
            b[rng.random_range(0..3)] = 0.0;
        }
        let Some((t0, t1)) = f.box_interval(a, b) else {
            assert!(f.crossings(a, b).is_none());
            continue;
        };
        // Every plane's crossing, collected and sorted.
        let mut want = vec![t0, t1];
        for k in 0..3 {
            if b[k] == 0.0 {
                continue;
            }
            for p in 0..n[k] as usize {
                let t = (p as f64 - a[k]) / b[k];
                if t > t0 && t < t1 {
                    want.push(t);
                }
            }
        }
        want.sort_by(f64::total_cmp);
        want.dedup();
        let mut cross = f.crossings(a, b).unwrap();
        let mut got = vec![cross.first()];
        got.extend(cross.by_ref());
        assert_eq!(got, want);
    }
}

#[test]
fn empty_blocks_are_crossed_in_one_step_and_lose_no_smoke() {
    for seed in 0..3 {
        let (f, lone) = sparse_field(seed);
        for (o, d) in rays_through(seed + 20, &lone) {
            let ray = f.along(o, d);
            for s in [0.3f32, 1.7, 4.0, 7.5] {
                matches_quadrature(&f, &ray, (o, d), s);
            }
        }
        // The lone samples are seen: a ray straight through each has depth.
        for &p in &lone {
            let o = p - Vec3::X * 5.0;
            assert!(f.along(o, Vec3::X).depth(10.0) > 0.0, "{p}");
        }
    }
}

#[test]
fn a_ray_cut_short_is_the_whole_rays_beginning() {
    let (f, lone) = sparse_field(7);
    let mut rng = Pcg64::seed_from_u64(8);
    for (o, d) in rays_through(30, &lone) {
        let whole = f.along(o, d);
        let total = whole.depth(f32::INFINITY);
        for _ in 0..5 {
            let s_max = 8.0 * rng.random::<f32>();
            let u_max = total * 1.2 * rng.random::<f32>();
            let cut = f.along_until(o, d, (s_max, u_max));
            let reach = s_max.min(whole.distance(u_max));
            for j in 0..=20 {
                let s = reach.min(10.0) * j as f32 / 20.0;
                assert_eq!(cut.depth(s).to_bits(), whole.depth(s).to_bits(), "{s}");
            }
            let reach_u = u_max.min(whole.depth(s_max));
            for j in 0..=20 {
                let u = reach_u * j as f32 / 20.0;
                assert_eq!(
                    cut.distance(u).to_bits(),
                    whole.distance(u).to_bits(),
                    "{u}"
                );
            }
            // Beyond its reach the cut ray's depth never exceeds the whole ray's, and a cut by
            // depth passes u_max (a flight's escape test reads the same answer from both).
            let far = cut.depth(f32::INFINITY);
            assert!(far <= total);
            if whole.depth(s_max) > u_max {
                assert!(far > u_max, "{far} {u_max}");
            }
        }
    }
}
