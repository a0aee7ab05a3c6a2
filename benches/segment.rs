//! Query math per forward segment: sphere test + weight, cylinder test + eq. 2 weights, and the
//! truncated cylinder's Gauss–Legendre weights (colour, 16 bins). Geometry only; no BVH.
//! Run briefly: `cargo bench --bench segment -- --warm-up-time 1 --measurement-time 3`.

use brume::integrator::estimator::{
    CameraAxis, cylinder_eq2, cylinder_truncated, segment_cylinder, segment_sphere,
    track_length_density,
};
use brume::medium::{ChannelPick, Medium, Mixture};
use brume::spectrum::Spectrum;
use criterion::{Criterion, Throughput, black_box, criterion_group, criterion_main};
use glam::Vec3;
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64Mcg;

const Q: usize = 1024;
const BINS: usize = 16;

struct Case {
    o: Vec3,
    v: Vec3,
    len: f32,
    c: Vec3,
    axis: CameraAxis,
}

fn cases() -> Vec<Case> {
    let mut rng = Pcg64Mcg::seed_from_u64(1);
    let mut p = || Vec3::new(rng.random(), rng.random(), rng.random()) * 2.0 - Vec3::ONE;
    (0..Q)
        .map(|_| {
            let o = p();
            let c = p() * 0.3;
            // Half the segments aimed at the volumes, so both hit and miss paths are timed.
            let v = (c + p() * 0.2 - o).normalize();
            let axis = CameraAxis {
                origin: p() * 0.3,
                dir: p().normalize(),
                start: 0.0,
                len: 1.0,
            };
            Case {
                o,
                v,
                len: 2.0,
                c,
                axis,
            }
        })
        .collect()
}

fn bench(c: &mut Criterion) {
    let cases = cases();
    let st: Vec<f32> = (0..BINS).map(|l| 0.2 + 0.5 * l as f32).collect();
    let ss = Spectrum::from_slice(&st) * 0.7;
    let sa = Spectrum::from_slice(&st) * 0.3;
    let m = Medium::new(&ss, &sa, 0.5, BINS).unwrap();
    let mix = Mixture::new(ChannelPick::Uniform, &Spectrum::ZERO, &m, 0.1);
    let r = 0.1f32;
    let mut g = c.benchmark_group("segment");
    g.throughput(Throughput::Elements(Q as u64));
    g.bench_function("sphere", |b| {
        b.iter(|| {
            let mut acc = 0.0f32;
            for k in &cases {
                if let Some(ch) = segment_sphere(k.o, k.v, k.len, k.c, r) {
                    acc += track_length_density(&ch, r);
                }
            }
            black_box(acc)
        })
    });
    g.bench_function("cylinder_chord", |b| {
        b.iter(|| {
            let mut acc = 0.0f32;
            for k in &cases {
                if let Some(ch) = segment_cylinder(&k.axis, r, k.o, k.v, k.len) {
                    acc += ch.len();
                }
            }
            black_box(acc)
        })
    });
    g.bench_function("cylinder_eq2_16bins", |b| {
        b.iter(|| {
            let mut acc = Spectrum::ZERO;
            for k in &cases {
                if let Some(ch) = segment_cylinder(&k.axis, r, k.o, k.v, k.len) {
                    acc += cylinder_eq2(&m, &ch, r);
                }
            }
            black_box(acc)
        })
    });
    g.bench_function("cylinder_truncated_16bins", |b| {
        b.iter(|| {
            let mut acc = Spectrum::ZERO;
            for k in &cases {
                if let Some(ch) = segment_cylinder(&k.axis, r, k.o, k.v, k.len) {
                    acc += cylinder_truncated(&m, &mix, None, &ch, r);
                }
            }
            black_box(acc)
        })
    });
    g.finish();
    // Hit rates, for reading the numbers.
    let hs = cases
        .iter()
        .filter(|k| segment_sphere(k.o, k.v, k.len, k.c, r).is_some())
        .count();
    let hc = cases
        .iter()
        .filter(|k| segment_cylinder(&k.axis, r, k.o, k.v, k.len).is_some())
        .count();
    eprintln!("hit rates: sphere {hs}/{Q}, cylinder {hc}/{Q}");
}

criterion_group!(benches, bench);
criterion_main!(benches);
