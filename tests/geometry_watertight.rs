//! Rays aimed exactly at the shared edges and vertices of a closed mesh must not slip through:
//! every ray from outside crosses the surface an even number of times, and the medium recorded
//! after the last crossing is the exterior again.

use brume::geometry::{Geometry, Ray, ShapeDesc, ShapeKind, Transform, spawn};
use glam::Vec3;
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64Mcg;

fn closed_mesh() -> (Vec<Vec3>, Vec<[u32; 3]>) {
    // Lat-long sphere with explicit single pole vertices so that the surface is closed.
    let (rings, segs) = (24u32, 32u32);
    let mut p = vec![Vec3::Z];
    for i in 1..rings {
        let th = std::f32::consts::PI * i as f32 / rings as f32;
        for j in 0..segs {
            let ph = std::f32::consts::TAU * j as f32 / segs as f32;
            let r = 1.0 + 0.1 * (3.0 * th).sin() * (4.0 * ph).cos();
            p.push(r * Vec3::new(th.sin() * ph.cos(), th.sin() * ph.sin(), th.cos()));
        }
    }
    p.push(Vec3::NEG_Z);
    let south = p.len() as u32 - 1;
    let v = |i: u32, j: u32| 1 + (i - 1) * segs + j % segs;
    let mut idx = Vec::new();
    for j in 0..segs {
        idx.push([0, v(1, j), v(1, j + 1)]);
        idx.push([south, v(rings - 1, j + 1), v(rings - 1, j)]);
    }
    for i in 1..rings - 1 {
        for j in 0..segs {
            idx.push([v(i, j), v(i + 1, j), v(i + 1, j + 1)]);
            idx.push([v(i, j), v(i + 1, j + 1), v(i, j + 1)]);
        }
    }
    (p, idx)
}

#[test]
fn rays_through_edges_and_vertices_do_not_leak() {
    let (positions, indices) = closed_mesh();
    let tr = Transform::new(
        Vec3::new(0.3, -0.1, 0.2),
        Vec3::new(10.0, 20.0, 30.0),
        Vec3::splat(1.7),
    );
    let shape = ShapeDesc {
        interior: Some(1),
        exterior: None,
        ..ShapeDesc::new(
            ShapeKind::Mesh {
                positions: positions.clone(),
                normals: None,
                uvs: None,
                indices: indices.clone(),
            },
            tr,
        )
    };
    let geo = Geometry::new(vec![shape]).unwrap();
    let mut rng = Pcg64Mcg::seed_from_u64(1000);
    let mut leaks = 0;
    let n = 100_000;
    for k in 0..n {
        let tri = indices[rng.random_range(0..indices.len())];
        let (a, b) = (positions[tri[0] as usize], positions[tri[1] as usize]);
        // Half the targets are vertices, half points on edges.
        let target = tr.point(if k % 2 == 0 {
            a
        } else {
            a + (b - a) * rng.random::<f32>()
        });
        let z = 1.0 - 2.0 * rng.random::<f32>();
        let phi = std::f32::consts::TAU * rng.random::<f32>();
        let s = (1.0 - z * z).sqrt();
        let d = Vec3::new(s * phi.cos(), s * phi.sin(), z);
        let mut ray = Ray::new(target - d * 5.0, d);
        let mut medium = None;
        let mut crossings = 0;
        while let Some(h) = geo.intersect(&ray, f32::INFINITY) {
            let next = geo.medium_after(&h, ray.d);
            if next != medium {
                crossings += 1;
            }
            medium = next;
            ray = spawn(h.p, h.ng, ray.d);
            assert!(crossings < 100);
        }
        if crossings % 2 != 0 || medium.is_some() {
            leaks += 1;
        }
    }
    assert_eq!(
        leaks, 0,
        "{leaks} of {n} rays slipped through an edge or vertex"
    );
}
