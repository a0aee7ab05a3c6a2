//! Spectral arithmetic per bin count: the fixed 64-lane `Spectrum` against a runtime-n loop
//! over slices and a const-generic `[f32; N]`. The kernel is a transport-like chain
//! `t = t * albedo + emission` repeated 64 times (one "path" of 64 events).
//!
//! cargo bench --bench spectral -- --warm-up-time 1 --measurement-time 3

use std::hint::black_box;

use brume::spectrum::{MAX_BINS, Spectrum};
use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};

const EVENTS: usize = 64;

fn inputs(n: usize) -> (Vec<f32>, Vec<f32>) {
    let a = (0..n).map(|i| 0.5 + 0.4 * (i as f32 / n as f32)).collect();
    let e = (0..n).map(|i| 0.01 * i as f32).collect();
    (a, e)
}

fn fixed(c: &mut Criterion) {
    let mut g = c.benchmark_group("fixed64");
    for n in [8, 16, 32, 64] {
        let (a, e) = inputs(n);
        let (a, e) = (Spectrum::from_slice(&a), Spectrum::from_slice(&e));
        g.bench_with_input(BenchmarkId::from_parameter(n), &n, |b, &n| {
            b.iter(|| {
                let mut t = Spectrum::splat(1.0, n);
                let (a, e) = (black_box(a), black_box(e));
                for _ in 0..EVENTS {
                    t = t * a + e;
                }
                t
            })
        });
    }
    g.finish();
}

fn runtime_n(c: &mut Criterion) {
    let mut g = c.benchmark_group("runtime_n");
    for n in [8, 16, 32, 64] {
        let (a, e) = inputs(n);
        g.bench_with_input(BenchmarkId::from_parameter(n), &n, |b, &n| {
            let mut t = vec![0.0f32; n];
            b.iter(|| {
                t.fill(1.0);
                let (a, e) = (black_box(&a[..]), black_box(&e[..]));
                for _ in 0..EVENTS {
                    for ((t, a), e) in t.iter_mut().zip(a).zip(e) {
                        *t = *t * a + e;
                    }
                }
                black_box(&t);
            })
        });
    }
    g.finish();
}

fn const_n<const N: usize>(
    g: &mut criterion::BenchmarkGroup<'_, criterion::measurement::WallTime>,
) {
    let (a, e) = inputs(N);
    let a: [f32; N] = a.try_into().unwrap_or([0.0; N]);
    let e: [f32; N] = e.try_into().unwrap_or([0.0; N]);
    g.bench_function(BenchmarkId::from_parameter(N), |b| {
        b.iter(|| {
            let mut t = [1.0f32; N];
            let (a, e) = (black_box(a), black_box(e));
            for _ in 0..EVENTS {
                for i in 0..N {
                    t[i] = t[i] * a[i] + e[i];
                }
            }
            t
        })
    });
}

fn const_generic(c: &mut Criterion) {
    let mut g = c.benchmark_group("const_generic");
    const_n::<8>(&mut g);
    const_n::<16>(&mut g);
    const_n::<32>(&mut g);
    const_n::<MAX_BINS>(&mut g);
    g.finish();
}

criterion_group!(benches, fixed, runtime_n, const_generic);
criterion_main!(benches);
