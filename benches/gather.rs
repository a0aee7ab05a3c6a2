//! The gather structure: build throughput (spheres/s), forward-segment queries (queries/s) and
//! memory per sphere, on synthetic integration spheres in a 1 m cube.
//! Run briefly: `cargo bench --bench gather -- --warm-up-time 1 --measurement-time 3`.
//! The 1e7 case is built once outside criterion (timed with `Instant`, printed) because one build
//! takes seconds and ~3 GB; set `BRUME_BENCH_1E7=0` to skip it.
//!
//! The sphere radius shrinks as N^(-1/2) (0.01 m at 1e5) so a 1 m segment meets ~31 spheres at
//! every size: the query cost then measures traversal, not the number of hits. Spheres lie on
//! camera segments along -Z (the gather stores a segment once and a distance per sphere).

use std::time::Instant;

use brume::integrator::gather::Gather;
use brume::integrator::record::{CLASS_ALL, SegmentRecord, VolumeRecord};
use brume::integrator::{Estimator, IntegratorDesc, Radii};
use brume::medium::Medium;
use brume::spectrum::Spectrum;
use criterion::{BenchmarkId, Criterion, Throughput, black_box, criterion_group, criterion_main};
use glam::Vec3;
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64Mcg;

/// Spectral bins per throughput, as in scenes/fog-cube.toml.
const BINS: usize = 32;
const QUERIES: usize = 1024;
/// Spheres per camera segment in the timed cases (q = 0.1 in a 1 m fog of extinction 1 /m
/// leaves about 6).
const PER_SEGMENT: usize = 6;

fn radius(n: usize) -> f32 {
    0.01 * (1e5 / n as f32).sqrt()
}

/// The records of a gather, for `Gather::new`.
struct Records {
    segments: Vec<SegmentRecord>,
    volumes: Vec<VolumeRecord>,
    throughputs: Vec<f32>,
}

/// `n` spheres uniform in the cube, `per_segment` of them on each camera segment (parallel to
/// -Z, as from fog-cube's orthographic camera). `distinct`: every segment has a throughput of
/// its own (the table's worst case); otherwise all share W = 1 (paths entering fog directly).
fn records(n: usize, per_segment: usize, distinct: bool, seed: u64) -> Records {
    let mut rng = Pcg64Mcg::seed_from_u64(seed);
    let segs = n.div_ceil(per_segment);
    let segments = (0..segs)
        .map(|i| SegmentRecord {
            origin: Vec3::new(rng.random::<f32>() - 0.5, rng.random::<f32>() - 0.5, 0.5),
            pixel: (i % (128 * 128)) as u32,
            dir: Vec3::NEG_Z,
            throughput: if distinct { i as u32 } else { 0 },
            medium: 0,
            classes: CLASS_ALL,
        })
        .collect();
    let volumes = (0..n)
        .map(|i| VolumeRecord {
            segment: (i / per_segment) as u32,
            s: rng.random(),
            scale: 1.0,
        })
        .collect();
    let entries = if distinct { segs } else { 1 };
    let throughputs = (0..entries * BINS).map(|i| 1.0 + (i % 7) as f32).collect();
    Records {
        segments,
        volumes,
        throughputs,
    }
}

fn media() -> Vec<Medium> {
    let s = Spectrum::splat(0.8, BINS);
    let a = Spectrum::splat(0.2, BINS);
    vec![Medium::new(&s, &a, 0.5, BINS).expect("valid medium")]
}

fn build(n: usize, r: Records) -> Gather {
    // q does not matter here: the records are given; spheres bound them.
    let spheres =
        Estimator::from_desc(&IntegratorDesc::default(), &[1.0], &media()).expect("spheres");
    Gather::new(
        &spheres,
        Radii::one(radius(n)),
        Vec::new(),
        (r.segments, Default::default()),
        r.volumes,
        r.throughputs,
        BINS,
    )
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
    let r2 = g.radii.direct * g.radii.direct;
    let (mut candidates, mut hits) = (0u64, 0u64);
    for &(o, d) in segs {
        g.volumes_along(o, d, 1.0, |seg, rec| {
            candidates += 1;
            let c = seg.at(rec.s);
            let t = (c - o).dot(d).clamp(0.0, 1.0);
            hits += ((o + d * t).distance_squared(c) < r2) as u64;
        });
    }
    (candidates, hits)
}

fn report(n: usize, g: &Gather, build_s: Option<f64>) {
    let (c, h) = query_all(g, &segments());
    eprintln!(
        "gather n={n:e}: {:.1} bytes/sphere ({PER_SEGMENT} per segment, shared W), {:.1} candidates and {:.1} hits per query{}",
        g.bytes() as f64 / n as f64,
        c as f64 / QUERIES as f64,
        h as f64 / QUERIES as f64,
        build_s.map_or(String::new(), |s| format!(
            ", build {s:.2} s = {:.3e} spheres/s",
            n as f64 / s
        )),
    );
}

/// Bytes per sphere of the layouts a pass can produce: one sphere per segment (q = 1) or
/// several, throughputs shared or all distinct.
fn report_layouts(n: usize) {
    for per_segment in [1, PER_SEGMENT, 30] {
        for distinct in [false, true] {
            let g = build(n, records(n, per_segment, distinct, 5));
            eprintln!(
                "gather n={n:e}: {per_segment:>2} spheres per segment, {} throughputs: {:.1} bytes/sphere (BVH {:.1})",
                if distinct { "distinct" } else { "shared  " },
                g.bytes() as f64 / n as f64,
                g.bvh_nodes().1 as f64 * 80.0 / n as f64,
            );
        }
    }
}

fn bench(c: &mut Criterion) {
    let segs = segments();
    let mut built = Vec::new();
    {
        let mut group = c.benchmark_group("gather_build");
        group.sample_size(10);
        for n in [100_000usize, 1_000_000] {
            group.throughput(Throughput::Elements(n as u64));
            group.bench_function(BenchmarkId::from_parameter(n), |b| {
                b.iter_batched(
                    || records(n, PER_SEGMENT, false, n as u64),
                    |r| build(n, r),
                    criterion::BatchSize::LargeInput,
                )
            });
            let g = build(n, records(n, PER_SEGMENT, false, n as u64));
            report(n, &g, None);
            report_layouts(n);
            built.push((n, g));
        }
    }
    // Only under `cargo bench` (criterion's test mode, `cargo test --benches`, skips it).
    let benching = std::env::args().any(|a| a == "--bench");
    if benching && std::env::var("BRUME_BENCH_1E7").as_deref() != Ok("0") {
        let n = 10_000_000usize;
        let r = records(n, PER_SEGMENT, false, n as u64);
        let t = Instant::now();
        let g = build(n, r);
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
