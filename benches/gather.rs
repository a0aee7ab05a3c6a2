//! The gather structure: build throughput (spheres/s), forward-segment queries (queries/s) and
//! memory per sphere, on synthetic integration spheres in a 1 m cube.
//! Run briefly: `cargo bench --bench gather -- --warm-up-time 1 --measurement-time 3`.
//! The 1e7 case is built once outside criterion (timed with `Instant`, printed) because one build
//! takes seconds and ~3 GB; set `BRUME_BENCH_1E7=0` to skip it.
//!
//! The sphere radius shrinks as N^(-1/2) (0.01 m at 1e5) so a 1 m segment meets ~31 spheres at
//! every size: the query cost then measures traversal, not the number of hits.

use std::time::Instant;

use brume::integrator::gather::Gather;
use brume::integrator::record::{CLASS_ALL, VolumeRecord, VolumeShape};
use criterion::{BenchmarkId, Criterion, Throughput, black_box, criterion_group, criterion_main};
use glam::Vec3;
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64Mcg;

/// Spectral bins per record, as in scenes/fog-cube.toml.
const BINS: usize = 32;
const QUERIES: usize = 1024;

fn radius(n: usize) -> f32 {
    0.01 * (1e5 / n as f32).sqrt()
}

fn records(n: usize, seed: u64) -> (Vec<VolumeRecord>, Vec<f32>) {
    let mut rng = Pcg64Mcg::seed_from_u64(seed);
    let volumes = (0..n)
        .map(|i| VolumeRecord {
            start: Vec3::new(rng.random(), rng.random(), rng.random()) - Vec3::splat(0.5),
            pixel: (i % (128 * 128)) as u32,
            dir: Vec3::NEG_Z,
            len: 0.0,
            medium: 0,
            shape: VolumeShape::Sphere,
            classes: CLASS_ALL,
            weight: (i * BINS) as u32,
        })
        .collect();
    let weights = (0..n * BINS).map(|i| 1.0 + (i % 7) as f32).collect();
    (volumes, weights)
}

/// Segments of 1 m from random points of the cube in random directions.
fn segments() -> Vec<(Vec3, Vec3)> {
    let mut rng = Pcg64Mcg::seed_from_u64(7);
    (0..QUERIES)
        .map(|_| {
            let o = Vec3::new(rng.random(), rng.random(), rng.random()) - Vec3::splat(0.5);
            let d = loop {
                let v = Vec3::new(rng.random(), rng.random(), rng.random()) * 2.0 - Vec3::ONE;
                if v.length_squared() > 1e-3 && v.length_squared() <= 1.0 {
                    break v.normalize();
                }
            };
            (o, d)
        })
        .collect()
}

/// Hits of all segments, with the exact sphere test a light pass would do on each candidate.
fn query_all(g: &Gather, segs: &[(Vec3, Vec3)]) -> (u64, u64) {
    let r2 = g.radius * g.radius;
    let (mut candidates, mut hits) = (0u64, 0u64);
    for &(o, d) in segs {
        g.volumes_along(o, d, 1.0, |rec| {
            candidates += 1;
            let t = (rec.start - o).dot(d).clamp(0.0, 1.0);
            hits += ((o + d * t).distance_squared(rec.start) < r2) as u64;
        });
    }
    (candidates, hits)
}

fn report(n: usize, g: &Gather, build_s: Option<f64>) {
    let (c, h) = query_all(g, &segments());
    eprintln!(
        "gather n={n:e}: {:.1} bytes/sphere ({} bins of weights), {:.1} candidates and {:.1} hits per query{}",
        g.bytes() as f64 / n as f64,
        BINS,
        c as f64 / QUERIES as f64,
        h as f64 / QUERIES as f64,
        build_s.map_or(String::new(), |s| format!(
            ", build {s:.2} s = {:.3e} spheres/s",
            n as f64 / s
        )),
    );
}

fn bench(c: &mut Criterion) {
    let segs = segments();
    let mut built = Vec::new();
    {
        let mut group = c.benchmark_group("gather_build");
        group.sample_size(10);
        for n in [100_000usize, 1_000_000] {
            let (v, w) = records(n, n as u64);
            group.throughput(Throughput::Elements(n as u64));
            group.bench_function(BenchmarkId::from_parameter(n), |b| {
                b.iter_batched(
                    || (v.clone(), w.clone()),
                    |(v, w)| Gather::new(radius(n), Vec::new(), v, w),
                    criterion::BatchSize::LargeInput,
                )
            });
            let g = Gather::new(radius(n), Vec::new(), v, w);
            report(n, &g, None);
            built.push((n, g));
        }
    }
    // Only under `cargo bench` (criterion's test mode, `cargo test --benches`, skips it).
    let benching = std::env::args().any(|a| a == "--bench");
    if benching && std::env::var("BRUME_BENCH_1E7").as_deref() != Ok("0") {
        let n = 10_000_000usize;
        let (v, w) = records(n, n as u64);
        let t = Instant::now();
        let g = Gather::new(radius(n), Vec::new(), v, w);
        let s = t.elapsed().as_secs_f64();
        report(n, &g, Some(s));
        built.push((n, g));
    }
    let mut group = c.benchmark_group("gather_query");
    group.throughput(Throughput::Elements(QUERIES as u64));
    for (n, g) in &built {
        group.bench_function(BenchmarkId::from_parameter(n), |b| {
            b.iter(|| black_box(query_all(g, &segs)))
        });
    }
}

criterion_group!(benches, bench);
criterion_main!(benches);
