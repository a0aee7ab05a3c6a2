//! The CWBVH must return exactly what a loop over every primitive returns.

use brume::geometry::{Geometry, Ray, ShapeDesc, ShapeKind, Transform};
use glam::{Vec2, Vec3};

mod common;
use common::check_against_brute_force;

/// A lat-long sphere with a bumpy radius: `rings * segments * 2` triangles.
fn bumpy_sphere(rings: u32, segments: u32) -> ShapeKind {
    let mut positions = Vec::new();
    for i in 0..=rings {
        let theta = std::f32::consts::PI * i as f32 / rings as f32;
        for j in 0..segments {
            let phi = std::f32::consts::TAU * j as f32 / segments as f32;
            let r = 1.0 + 0.15 * (5.0 * theta).sin() * (7.0 * phi).cos();
            positions.push(
                r * Vec3::new(
                    theta.sin() * phi.cos(),
                    theta.sin() * phi.sin(),
                    theta.cos(),
                ),
            );
        }
    }
    let mut indices = Vec::new();
    for i in 0..rings {
        for j in 0..segments {
            let a = i * segments + j;
            let b = i * segments + (j + 1) % segments;
            let (c, d) = (a + segments, b + segments);
            indices.push([a, c, b]);
            indices.push([b, c, d]);
        }
    }
    ShapeKind::Mesh {
        positions,
        normals: None,
        uvs: None,
        indices,
    }
}

#[test]
fn mesh_bvh_matches_brute_force() {
    let geo = Geometry::new(vec![ShapeDesc::new(
        bumpy_sphere(40, 60),
        Transform::IDENTITY,
    )])
    .unwrap();
    assert!(geo.num_primitives() > 4000);
    check_against_brute_force(&geo, 100_000, 1);
}

#[test]
fn mixed_shapes_bvh_matches_brute_force() {
    let t = |x: f32, y: f32, z: f32| {
        Transform::new(Vec3::new(x, y, z), Vec3::new(20.0, 35.0, -10.0), Vec3::ONE)
    };
    let shapes = vec![
        ShapeDesc::new(
            bumpy_sphere(30, 40),
            Transform::new(Vec3::ZERO, Vec3::ZERO, Vec3::splat(0.8)),
        ),
        ShapeDesc::new(ShapeKind::Sphere { radius: 0.5 }, t(2.0, 0.0, 0.0)),
        ShapeDesc::new(
            ShapeKind::Sphere { radius: 0.4 },
            Transform::new(
                Vec3::new(-2.0, 0.5, 0.0),
                Vec3::ZERO,
                Vec3::new(1.0, 2.0, 0.5),
            ),
        ),
        ShapeDesc::new(ShapeKind::Disc { radius: 0.7 }, t(0.0, 2.0, 0.0)),
        ShapeDesc::new(
            ShapeKind::Box {
                size: Vec3::new(0.5, 1.0, 0.3),
            },
            t(0.0, -2.0, 0.5),
        ),
        ShapeDesc::new(
            ShapeKind::Quad {
                size: Vec2::new(6.0, 6.0),
            },
            t(0.0, 0.0, -2.0),
        ),
    ];
    let geo = Geometry::new(shapes).unwrap();
    check_against_brute_force(&geo, 100_000, 2);
}

#[test]
fn analytic_hits_have_outward_normals_and_exact_points() {
    let geo = Geometry::new(vec![ShapeDesc::new(
        ShapeKind::Sphere { radius: 2.0 },
        Transform::translate(Vec3::new(1.0, 0.0, 0.0)),
    )])
    .unwrap();
    let h = geo
        .intersect(
            &Ray::new(Vec3::new(1.0, 0.0, 10.0), Vec3::NEG_Z),
            f32::INFINITY,
        )
        .unwrap();
    assert!((h.t - 8.0).abs() < 1e-5 && (h.ng - Vec3::Z).length() < 1e-6);
    // From inside: the exit point, normal still outward.
    let h = geo
        .intersect(&Ray::new(Vec3::new(1.0, 0.0, 0.0), Vec3::X), f32::INFINITY)
        .unwrap();
    assert!((h.t - 2.0).abs() < 1e-5 && (h.ng - Vec3::X).length() < 1e-6);
    assert!((geo.area(0) - 16.0 * std::f32::consts::PI).abs() < 1e-3);
}

#[test]
fn box_normals_point_out_even_when_mirrored() {
    for scale in [Vec3::ONE, Vec3::new(-1.0, 1.0, 1.0)] {
        let geo = Geometry::new(vec![ShapeDesc::new(
            ShapeKind::Box {
                size: Vec3::splat(2.0),
            },
            Transform::new(Vec3::ZERO, Vec3::ZERO, scale),
        )])
        .unwrap();
        for d in [
            Vec3::X,
            Vec3::NEG_X,
            Vec3::Y,
            Vec3::NEG_Y,
            Vec3::Z,
            Vec3::NEG_Z,
        ] {
            let h = geo
                .intersect(&Ray::new(d * 5.0 + Vec3::splat(0.1), -d), f32::INFINITY)
                .unwrap();
            assert!((h.ng - d).length() < 1e-6, "{d} {:?}", h.ng);
            assert!((h.t - (4.0 + 0.1 * d.element_sum())).abs() < 1e-5);
        }
        assert!((geo.area(0) - 24.0).abs() < 1e-4);
    }
}

#[test]
fn invalid_shapes_are_errors() {
    let bad = ShapeDesc::new(ShapeKind::Sphere { radius: -1.0 }, Transform::IDENTITY);
    assert!(Geometry::new(vec![bad]).is_err());
    let bad = ShapeDesc::new(
        ShapeKind::Mesh {
            positions: vec![Vec3::ZERO],
            normals: None,
            uvs: None,
            indices: vec![[0, 1, 2]],
        },
        Transform::IDENTITY,
    );
    assert!(Geometry::new(vec![bad]).is_err());
    let singular = ShapeDesc::new(
        ShapeKind::Quad { size: Vec2::ONE },
        Transform::new(Vec3::ZERO, Vec3::ZERO, Vec3::new(1.0, 0.0, 1.0)),
    );
    assert!(Geometry::new(vec![singular]).is_err());
    assert!(
        Geometry::new(vec![])
            .unwrap()
            .intersect(&Ray::new(Vec3::ZERO, Vec3::X), 1.0)
            .is_none()
    );
}

#[test]
fn runtime_types_are_shareable_across_threads_and_area_sampling_flags() {
    fn shareable<T: Send + Sync>() {}
    shareable::<Geometry>();
    shareable::<brume::material::Material>();
    shareable::<brume::light::Light>();
    shareable::<brume::light::LightSet>();
    shareable::<brume::camera::Camera>();
    let geo = Geometry::new(vec![
        ShapeDesc::new(
            ShapeKind::Sphere { radius: 1.0 },
            Transform::new(Vec3::ZERO, Vec3::new(10.0, 0.0, 0.0), Vec3::splat(2.0)),
        ),
        ShapeDesc::new(
            ShapeKind::Sphere { radius: 1.0 },
            Transform::new(Vec3::ZERO, Vec3::ZERO, Vec3::new(1.0, 2.0, 1.0)),
        ),
        ShapeDesc::new(
            ShapeKind::Disc { radius: 1.0 },
            Transform::new(Vec3::ZERO, Vec3::ZERO, Vec3::new(1.0, 2.0, 1.0)),
        ),
    ])
    .unwrap();
    assert!(geo.area_sampling_exact(0));
    assert!(!geo.area_sampling_exact(1));
    assert!(geo.area_sampling_exact(2));
    assert!((geo.area(2) - 2.0 * std::f32::consts::PI).abs() < 1e-4);
}
