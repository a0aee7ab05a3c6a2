//! Boxes are analytic primitives: they must hit, face and texture exactly as the twelve
//! triangles they replaced, and scenes of a few primitives (intersected without their BVH) must
//! answer as the loop over every primitive does.

use brume::geometry::{Geometry, Ray, ShapeDesc, ShapeKind, Transform};
use glam::{Vec2, Vec3, vec2};
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64Mcg;

mod common;
use common::{check_against_brute_force, random_dir};

/// The box of `size` as the mesh the tessellator used to make: per face (outward axis, u, v with
/// u x v outward), uv (0, 0) at `c - u - v` and (1, 1) at `c + u + v`.
fn box_mesh(size: Vec3) -> ShapeKind {
    let h = size * 0.5;
    let faces = [
        (Vec3::X, Vec3::Y, Vec3::Z),
        (-Vec3::X, Vec3::Z, Vec3::Y),
        (Vec3::Y, Vec3::Z, Vec3::X),
        (-Vec3::Y, Vec3::X, Vec3::Z),
        (Vec3::Z, Vec3::X, Vec3::Y),
        (-Vec3::Z, Vec3::Y, Vec3::X),
    ];
    let (mut positions, mut uvs, mut indices) = (Vec::new(), Vec::new(), Vec::new());
    for (n, u, v) in faces {
        let (c, du, dv) = (n * h, u * h, v * h);
        let k = positions.len() as u32;
        positions.extend([c - du - dv, c + du - dv, c + du + dv, c - du + dv]);
        uvs.extend([
            vec2(0.0, 0.0),
            vec2(1.0, 0.0),
            vec2(1.0, 1.0),
            vec2(0.0, 1.0),
        ]);
        indices.extend([[k, k + 1, k + 2], [k, k + 2, k + 3]]);
    }
    ShapeKind::Mesh {
        positions,
        normals: None,
        uvs: Some(uvs),
        indices,
    }
}

/// Rays from around the box (a third from inside it) against the box and its mesh, under a
/// rotation, a mirror and an axis scale: the same hits, distances, points, normals, uvs and
/// areas, and the same medium on either side.
#[test]
fn analytic_box_matches_its_triangles() {
    let size = Vec3::new(0.5, 1.0, 0.3);
    let transforms = [
        Transform::IDENTITY,
        Transform::new(
            Vec3::new(0.3, -0.2, 1.0),
            Vec3::new(20.0, 35.0, -10.0),
            Vec3::ONE,
        ),
        Transform::new(
            Vec3::ZERO,
            Vec3::new(0.0, 30.0, 0.0),
            Vec3::new(-1.0, 2.0, 0.5),
        ),
    ];
    let mut rng = Pcg64Mcg::seed_from_u64(5);
    for (i, t) in transforms.iter().enumerate() {
        let one = |kind| {
            let desc = ShapeDesc {
                interior: Some(0),
                ..ShapeDesc::new(kind, *t)
            };
            Geometry::new(vec![desc]).unwrap()
        };
        let (analytic, mesh) = (one(ShapeKind::Box { size }), one(box_mesh(size)));
        assert!(
            (analytic.area(0) / mesh.area(0) - 1.0).abs() < 1e-5,
            "transform {i}"
        );
        let c = t.point(Vec3::ZERO);
        let mut hits = 0;
        for k in 0..20_000 {
            let o = if k % 3 == 0 {
                t.point((Vec3::new(rng.random(), rng.random(), rng.random()) - 0.5) * size * 0.98)
            } else {
                c + (Vec3::new(rng.random(), rng.random(), rng.random()) - 0.5) * 4.0
            };
            let d = if k % 2 == 0 {
                random_dir(&mut rng)
            } else {
                (c - o + (Vec3::new(rng.random(), rng.random(), rng.random()) - 0.5) * 0.4)
                    .normalize_or(Vec3::Z)
            };
            let ray = Ray::new(o, d);
            match (
                analytic.intersect(&ray, f32::INFINITY),
                mesh.intersect(&ray, f32::INFINITY),
            ) {
                (None, None) => {}
                (Some(a), Some(m)) => {
                    hits += 1;
                    assert!(
                        (a.t - m.t).abs() < 1e-5 * (1.0 + m.t),
                        "{i}/{k}: t {} vs {}",
                        a.t,
                        m.t
                    );
                    assert!((a.p - m.p).length() < 1e-5, "{i}/{k}: p {} vs {}", a.p, m.p);
                    // Away from edges the face is unambiguous.
                    if (a.uv - vec2(0.5, 0.5)).abs().max_element() < 0.49 {
                        assert!(
                            (a.ng - m.ng).length() < 1e-5,
                            "{i}/{k}: n {} vs {}",
                            a.ng,
                            m.ng
                        );
                        assert!(
                            (a.uv - m.uv).length() < 1e-4,
                            "{i}/{k}: uv {} vs {}",
                            a.uv,
                            m.uv
                        );
                        assert_eq!(
                            analytic.medium_after(&a, d),
                            mesh.medium_after(&m, d),
                            "{i}/{k}"
                        );
                    }
                }
                (a, m) => panic!("{i}/{k}: analytic {a:?} vs triangles {m:?}"),
            }
            assert_eq!(
                analytic.medium_at(o),
                mesh.medium_at(o),
                "{i}/{k}: medium at {o}"
            );
        }
        assert!(hits > 10_000, "only {hits} hits");
    }
}

/// A fog box against a wall (three primitives, intersected one by one) and a scene of many
/// primitives: closest hits and any-hit answers as the loop over every primitive gives them.
#[test]
fn small_scenes_answer_as_brute_force() {
    let fog = ShapeDesc {
        interior: Some(0),
        ..ShapeDesc::new(ShapeKind::Box { size: Vec3::ONE }, Transform::IDENTITY)
    };
    let wall = ShapeDesc {
        material: Some(0),
        ..ShapeDesc::new(
            ShapeKind::Quad { size: Vec2::ONE },
            Transform::translate(Vec3::new(0.0, 0.0, -0.5)),
        )
    };
    let geo = Geometry::new(vec![fog, wall]).unwrap();
    assert_eq!(geo.num_primitives(), 3);
    check_against_brute_force(&geo, 50_000, 11);
    // The wall is coplanar with the box's back face: from inside, the wall (a surface) is met
    // first, as null_rank orders them, so that no light leaks through it.
    let h = geo
        .intersect(
            &Ray::new(Vec3::new(0.1, 0.2, 0.0), Vec3::NEG_Z),
            f32::INFINITY,
        )
        .unwrap();
    assert_eq!(h.shape, 1, "{h:?}");
}
