//! Closest-hit throughput of the scene BVH on a generated ~100k-triangle mesh, single thread.
//! Run: cargo bench --bench bvh -- --warm-up-time 1 --measurement-time 3

use brume::geometry::{Geometry, Ray, ShapeDesc, ShapeKind, Transform};
use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use glam::Vec3;
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64Mcg;

/// Bumpy lat-long sphere with `2 * rings * segments` triangles.
fn mesh(rings: u32, segments: u32) -> ShapeKind {
    let mut positions = Vec::new();
    for i in 0..=rings {
        let th = std::f32::consts::PI * i as f32 / rings as f32;
        for j in 0..segments {
            let ph = std::f32::consts::TAU * j as f32 / segments as f32;
            let r = 1.0 + 0.1 * (9.0 * th).sin() * (11.0 * ph).cos();
            positions.push(r * Vec3::new(th.sin() * ph.cos(), th.sin() * ph.sin(), th.cos()));
        }
    }
    let mut indices = Vec::new();
    for i in 0..rings {
        for j in 0..segments {
            let a = i * segments + j;
            let b = i * segments + (j + 1) % segments;
            indices.push([a, a + segments, b]);
            indices.push([b, a + segments, b + segments]);
        }
    }
    ShapeKind::Mesh {
        positions,
        normals: None,
        uvs: None,
        indices,
    }
}

fn bench(c: &mut Criterion) {
    let geo = Geometry::new(vec![ShapeDesc::new(mesh(224, 224), Transform::IDENTITY)]).unwrap();
    let mut rng = Pcg64Mcg::seed_from_u64(7);
    // Rays from a shell around the mesh towards random points near it: most hit.
    let rays: Vec<Ray> = (0..10_000)
        .map(|_| {
            let o = (Vec3::new(rng.random(), rng.random(), rng.random()) * 2.0 - 1.0)
                .normalize_or(Vec3::Z)
                * 3.0;
            let t = (Vec3::new(rng.random(), rng.random(), rng.random()) * 2.0 - 1.0) * 0.8;
            Ray::new(o, (t - o).normalize())
        })
        .collect();
    let mut g = c.benchmark_group("bvh");
    g.throughput(Throughput::Elements(rays.len() as u64));
    g.bench_function(format!("closest_hit_{}_tris", geo.num_primitives()), |b| {
        b.iter(|| {
            rays.iter()
                .filter(|r| geo.intersect(r, f32::INFINITY).is_some())
                .count()
        })
    });
    g.bench_function("any_hit", |b| {
        b.iter(|| {
            rays.iter()
                .filter(|r| geo.occluded(r, f32::INFINITY))
                .count()
        })
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
