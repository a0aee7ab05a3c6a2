//! The spectral channel mixture: probabilities, picking, the mixed distance density, and the
//! scaled evaluation used for deep points.

#[path = "estimator_stats.rs"]
mod stats;

use brume::medium::{ChannelPick, Medium, Mixture};
use brume::spectrum::Spectrum;
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64Mcg;

fn medium() -> Medium {
    let st = [0.05f32, 0.8, 4.0, 30.0];
    let a = [0.9f32, 0.5, 0.99, 0.2];
    Medium::from_extinction_albedo(&st, &a, 0.3).unwrap()
}

#[test]
fn probabilities_are_positive_and_sum_to_one() {
    let m = medium();
    let cases = [
        (ChannelPick::Throughput, [1.0f32, 0.0, 3.0, 0.0]),
        (ChannelPick::Throughput, [0.0; 4]),
        (
            ChannelPick::Throughput,
            [f32::NAN, -1.0, f32::INFINITY, 2.0],
        ),
        (ChannelPick::Uniform, [5.0, 1.0, 0.0, 0.0]),
    ];
    for (pick, w) in cases {
        for floor in [0.0f32, 0.1, 1.0, f32::NAN] {
            let mix = Mixture::new(pick, &Spectrum::from_slice(&w), &m, floor);
            let p = mix.probabilities();
            let s: f32 = p.as_slice(4).iter().sum();
            assert!((s - 1.0).abs() < 1e-6, "{pick:?} {w:?} {floor}: sum {s}");
            assert!(p.as_slice(4).iter().all(|&x| x > 0.0), "{p:?}");
            assert!(p.0[4..].iter().all(|&x| x == 0.0));
        }
    }
    let mix = Mixture::new(
        ChannelPick::Throughput,
        &Spectrum::from_slice(&[1.0, 0.0, 3.0, 0.0]),
        &m,
        0.2,
    );
    let p = mix.probabilities();
    assert!((p[0] - (0.8 * 0.25 + 0.05)).abs() < 1e-6 && (p[1] - 0.05).abs() < 1e-6);
}

#[test]
fn pick_frequencies_and_distance_density_match() {
    let m = medium();
    let mix = Mixture::new(
        ChannelPick::Throughput,
        &Spectrum::from_slice(&[1.0, 0.1, 2.0, 0.5]),
        &m,
        0.1,
    );
    let mut rng = Pcg64Mcg::seed_from_u64(21);
    let n = 400_000;
    let mut picks = [0u64; 4];
    let xs = [0.01f32, 0.1, 1.0, 10.0];
    let mut below = [0u64; 4];
    for _ in 0..n {
        picks[mix.pick(rng.random())] += 1;
        let s = mix.sample_distance(rng.random(), rng.random());
        for (k, &x) in xs.iter().enumerate() {
            below[k] += (s < x) as u64;
        }
    }
    for (l, &count) in picks.iter().enumerate() {
        let p = mix.probabilities()[l] as f64;
        let z = (count as f64 / n as f64 - p) / (p * (1.0 - p) / n as f64).sqrt();
        assert!(z.abs() < 4.0, "bin {l}: z={z}");
    }
    for (k, &x) in xs.iter().enumerate() {
        let p = 1.0 - mix.tmix(x) as f64;
        let z = (below[k] as f64 / n as f64 - p) / (p * (1.0 - p) / n as f64).sqrt();
        assert!(z.abs() < 4.0, "P(s<{x}): z={z}");
    }
}

#[test]
fn pdf_mix_is_the_derivative_of_one_minus_tmix() {
    let m = medium();
    let mix = Mixture::new(ChannelPick::Uniform, &Spectrum::ZERO, &m, 0.1);
    for s in [0.0f32, 0.03, 0.5, 2.0] {
        let h = 1e-3f32;
        let d = (mix.tmix(s) - mix.tmix(s + h)) / h;
        let pdf = mix.pdf_mix(s + 0.5 * h);
        assert!(
            (d - pdf).abs() < 1e-3 * pdf.max(1e-3),
            "s={s}: {d} vs {pdf}"
        );
    }
}

#[test]
fn scaled_evaluation_stays_finite_where_exponentials_underflow() {
    let m = medium();
    let mix = Mixture::new(ChannelPick::Uniform, &Spectrum::ZERO, &m, 0.1);
    // At s = 1000 every bin but the first has underflowed: the ratios must still be exact.
    let s = 1000.0f32;
    let w = mix.survival_weight(s);
    assert!(w.is_finite());
    assert!(
        (w[0] - 4.0).abs() < 1e-4,
        "only bin 0 survives, with P = 1/4: {}",
        w[0]
    );
    assert_eq!(w[3], 0.0);
    let e = mix.eval(s);
    assert!(e.pdf > 0.0 && e.tmix > 0.0);
    // Infinite distance: bins without extinction are the only survivors.
    let ss = Spectrum::from_slice(&[0.0, 1.0]);
    let vac = Medium::new(&ss, &Spectrum::ZERO, 0.0, 2).unwrap();
    let mix = Mixture::new(ChannelPick::Uniform, &Spectrum::ZERO, &vac, 0.1);
    let w = mix.survival_weight(f32::INFINITY);
    assert_eq!((w[0], w[1]), (2.0, 0.0));
}
