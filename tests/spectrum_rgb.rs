//! RGB -> spectrum (Jakob and Hanika 2019): round trips through the film's own colorimetry.
//! Run with `-- --nocapture` to print the round-trip figures quoted in docs/colour.md.

use brume::colour::rgb::{CoefficientTable, FitContext};
use brume::colour::{ColourSpace, FilmToRgb, Observer, XyzWeights, srgb_decode, srgb_encode};
use brume::colour::{RgbKind, rgb_to_spectrum};
use brume::spectrum::{Extrapolation, SpectralGrid, resolve};

/// sRGB-encoded grid 0, 1/16, ..., 1 per channel, returned linear.
fn grid_colours() -> Vec<[f32; 3]> {
    let steps = 17;
    let mut v = Vec::new();
    for r in 0..steps {
        for g in 0..steps {
            for b in 0..steps {
                let e = [r, g, b].map(|c| srgb_decode(c as f32 / (steps - 1) as f32));
                v.push(e);
            }
        }
    }
    v
}

struct Stats {
    max_lin: f32,
    mean_lin: f32,
    max_code: f32,
}

fn stats(pairs: impl Iterator<Item = ([f32; 3], [f32; 3])>) -> Stats {
    let (mut max_lin, mut sum, mut n, mut max_code) = (0.0f32, 0.0f32, 0, 0.0f32);
    for (want, got) in pairs {
        for c in 0..3 {
            let d = (want[c] - got[c]).abs();
            max_lin = max_lin.max(d);
            sum += d;
            n += 1;
            let code = |v: f32| srgb_encode(v.clamp(0.0, 1.0)) * 255.0;
            max_code = max_code.max((code(want[c]) - code(got[c])).abs());
        }
    }
    Stats {
        max_lin,
        mean_lin: sum / n as f32,
        max_code,
    }
}

#[test]
fn reflectance_round_trip_through_the_fit() {
    let t0 = std::time::Instant::now();
    let table = CoefficientTable::srgb().expect("table");
    println!("coefficient table fitted in {:.2?}", t0.elapsed());
    let ctx = FitContext::srgb().unwrap();
    let s = stats(grid_colours().into_iter().map(|rgb| {
        let sp = table.lookup(rgb.map(|v| v as f64));
        (rgb, ctx.rgb_of(&sp).map(|v| v as f32))
    }));
    println!(
        "continuous round trip (17^3 sRGB grid): max |d| {:.2e}, mean {:.2e}, max {:.2} code values",
        s.max_lin, s.mean_lin, s.max_code
    );
    assert!(s.max_lin < 0.015 && s.mean_lin < 2e-3);
}

#[test]
fn reflectance_round_trip_through_the_film_bins() {
    // What the renderer sees: reflectance bins times D65 bins, through the film's bin weights.
    for n in [16, 32, 64] {
        let g = SpectralGrid::new(n, 380.0, 780.0);
        let d65 = resolve("D65", None, false)
            .unwrap()
            .bin_averages(&g, Extrapolation::Clamp);
        let y = XyzWeights::new(Observer::Cie1931, &g).unwrap().xyz_of(&d65)[1] as f32;
        let light = d65 * (1.0 / y);
        let film =
            FilmToRgb::new(ColourSpace::Srgb, Observer::Cie1931, &g, Default::default()).unwrap();
        let s = stats(grid_colours().into_iter().map(|rgb| {
            let refl = rgb_to_spectrum(rgb, RgbKind::Reflectance, &g).unwrap();
            assert!(refl.as_slice(n).iter().all(|v| (0.0..=1.0).contains(v)));
            (rgb, film.rgb((refl * light).as_slice(n)))
        }));
        println!(
            "film round trip, {n} bins: max |d| {:.2e}, mean {:.2e}, max {:.2} code values",
            s.max_lin, s.mean_lin, s.max_code
        );
        assert!(s.max_lin < 0.03, "{n} bins: {}", s.max_lin);
    }
}

#[test]
fn emission_and_unbounded_round_trip() {
    let g = SpectralGrid::new(32, 380.0, 780.0);
    let film =
        FilmToRgb::new(ColourSpace::Srgb, Observer::Cie1931, &g, Default::default()).unwrap();
    let d65 = resolve("D65", None, false)
        .unwrap()
        .bin_averages(&g, Extrapolation::Clamp);
    let light =
        d65 * (1.0 / XyzWeights::new(Observer::Cie1931, &g).unwrap().xyz_of(&d65)[1] as f32);
    for rgb in [
        [1.0, 1.0, 1.0],
        [4.0, 2.0, 0.5],
        [0.0, 0.3, 10.0],
        [0.2, 0.2, 0.0],
    ] {
        let e = rgb_to_spectrum(rgb, RgbKind::Illuminant, &g).unwrap();
        let got = film.rgb(e.as_slice(g.n));
        for c in 0..3 {
            assert!(
                (got[c] - rgb[c]).abs() < 0.02 * rgb[0].max(rgb[1]).max(rgb[2]),
                "{rgb:?} -> {got:?}"
            );
        }
        // Unbounded: seen as a "reflectance" under D65 (Y = 1) it reproduces the colour at any
        // magnitude, and it never exceeds twice the largest component (the fit is at half).
        let u = rgb_to_spectrum(rgb, RgbKind::Unbounded, &g).unwrap();
        let m = rgb[0].max(rgb[1]).max(rgb[2]);
        assert!(u.max_value() <= 2.0 * m && u.max_value() > 0.0);
        let got = film.rgb((u * light).as_slice(g.n));
        for c in 0..3 {
            assert!((got[c] - rgb[c]).abs() < 0.02 * m, "{rgb:?} -> {got:?}");
        }
    }
    assert!(
        rgb_to_spectrum([0.0; 3], RgbKind::Unbounded, &g)
            .unwrap()
            .is_zero()
    );
}
