//! Photometric output: EXRs in cd/m² that say so, luminance read back (`probe`), metered
//! exposure, and the false-colour map with its legend.

use brume::colour::photometry::{self, luminance_scale};
use brume::colour::{Observer, ViewTransform, XyzWeights};
use brume::film::SpectralImage;
use brume::film::output::false_colour::{
    self, BACKGROUND, BAR_BOTTOM, BAR_TOP, BAR_W, BAR_X, INK, MIN_HEIGHT, PANEL,
};
use brume::film::output::{
    Exposure, OutputOptions, Units, metered_stops, probe, protected_stops, write,
};
use brume::spectrum::SpectralGrid;

/// A horizontal ramp: pixel x has a constant spectrum of radiance `base * 10^(x / 8)`; noise
/// 1 % of the value in every bin.
fn ramp(width: usize, height: usize, base: f32) -> SpectralImage {
    let g = SpectralGrid::new(16, 380.0, 780.0);
    let mut img = SpectralImage::new(width, height, g.clone());
    let mut noise = vec![0.0; img.data.len()];
    for y in 0..height {
        for x in 0..width {
            let v = base * 10f32.powf(x as f32 / 8.0);
            for b in 0..g.n {
                let i = (y * width + x) * g.n + b;
                img.data[i] = v;
                noise[i] = 0.01 * v;
            }
        }
    }
    img.noise = Some(noise);
    img
}

/// The luminance (cd/m²) of a constant spectral radiance `v` over the grid.
fn cd(img: &SpectralImage, v: f32) -> f64 {
    let w = photometry::luminous_weights(&img.grid).expect("V");
    photometry::photometric(&w, &vec![v; img.grid.n])
}

#[test]
fn photometric_exr_holds_cd_per_m2_and_says_so() {
    let dir = tempfile::tempdir().expect("tempdir");
    let img = ramp(24, 2, 1e-5);
    let k = luminance_scale(Observer::Cie1931).expect("scale");
    assert!((k / (683.0 * 106.857) - 1.0).abs() < 1e-4, "{k}");
    for units in [Units::Photometric, Units::Radiometric] {
        let path = dir.path().join(format!("{}.exr", units.name()));
        let opts = OutputOptions {
            units,
            noise_layer: true,
            ..Default::default()
        };
        write(&path, &img, &opts).expect("write");
        let p = probe::read(&path).expect("probe");
        assert_eq!(p.units, Some(units));
        let to_cd = match units {
            Units::Photometric => 1.0,
            Units::Radiometric => p.white_luminance.expect("whiteLuminance"),
        };
        let xyz = XyzWeights::new(Observer::Cie1931, &img.grid).expect("cmfs");
        for x in [0usize, 7, 23] {
            let v = 1e-5 * 10f32.powf(x as f32 / 8.0);
            let m = p.region([x, 0, x + 1, 1]).expect("inside");
            // Y in cd/m² is K_m * sum of L * y-bar: the film's Y times 683 * 106.857.
            let want = cd(&img, v);
            assert!(
                (m.mean * to_cd / want - 1.0).abs() < 1e-5,
                "{units:?} x={x}"
            );
            assert!((xyz.xyz(img.pixel(x, 0))[1] * k / want - 1.0).abs() < 1e-5);
            // noise.Y: 1 % in every bin, bins taken as independent.
            let w2: f64 = xyz.w.iter().map(|w| w[1] * w[1]).sum();
            let se = 0.01 * v as f64 * w2.sqrt() * k / to_cd;
            let got = m.std_error.expect("noise layer");
            assert!((got / se - 1.0).abs() < 1e-4, "{got} vs {se}");
        }
        // A region: the mean of its pixels, errors added as independent.
        let r = p.region([0, 0, 2, 2]).expect("inside");
        let a = p.region([0, 0, 1, 1]).expect("inside");
        let b = p.region([1, 0, 2, 1]).expect("inside");
        assert!((r.mean - 0.5 * (a.mean + b.mean)).abs() < 1e-9 * r.mean);
        assert_eq!(r.pixels, 4);
        assert!(p.region([20, 0, 25, 1]).is_none(), "outside the image");
    }
}

#[test]
fn auto_exposure_maps_the_log_average_to_middle_grey() {
    let conv = brume::colour::FilmToRgb::new(
        brume::colour::ColourSpace::Srgb,
        Observer::Cie1931,
        &SpectralGrid::new(16, 380.0, 780.0),
        Default::default(),
    )
    .expect("conv");
    let dim = ramp(16, 4, 1e-6);
    let bright = ramp(16, 4, 1e-3);
    let (a, b) = (metered_stops(&dim, &conv), metered_stops(&bright, &conv));
    // Scale invariance: 1000 times brighter, log2(1000) stops less.
    assert!((a - b - 1000f32.log2()).abs() < 1e-3, "{a} {b}");
    // The log-average of the ramp lands on 0.18.
    let ys: Vec<f64> = dim
        .data
        .chunks_exact(16)
        .map(|px| conv.xyz.xyz(px)[1])
        .collect();
    let log_avg = (ys.iter().map(|y| y.ln()).sum::<f64>() / ys.len() as f64).exp();
    assert!((log_avg * 2f64.powf(a as f64) - 0.18).abs() < 1e-4);
    assert_eq!(
        metered_stops(&ramp(4, 1, 0.0), &conv),
        0.0,
        "black stays at 0 stops"
    );
    assert_eq!("auto".parse::<Exposure>(), Ok(Exposure::Auto));
    assert_eq!("-1.5".parse::<Exposure>(), Ok(Exposure::Stops(-1.5)));
    assert!("bright".parse::<Exposure>().is_err());
}

/// Issue 31: `exposure = "auto"` clipped a white wall in a dark scene. A wall over 10 % of the
/// image, 1000 times the rest: the log-average alone puts it 6.5 stops past middle grey, far
/// past white; the protected exposure stops where the 99th percentile reaches the view's white.
#[test]
fn auto_exposure_protects_the_highlights() {
    let g = SpectralGrid::new(16, 380.0, 780.0);
    let conv = brume::colour::FilmToRgb::new(
        brume::colour::ColourSpace::Srgb,
        Observer::Cie1931,
        &g,
        Default::default(),
    )
    .expect("conv");
    let mut img = SpectralImage::new(10, 10, g.clone());
    for (p, px) in img.data.chunks_exact_mut(g.n).enumerate() {
        px.fill(if p < 10 { 1.0 } else { 1e-3 });
    }
    let wall = conv.xyz.xyz(img.pixel(0, 0))[1];
    let metered = metered_stops(&img, &conv);
    assert!(wall * 2f64.powf(metered as f64) > 50.0, "{metered}");
    for view in [ViewTransform::Clip, ViewTransform::Filmic] {
        let white = view.white();
        let stops = protected_stops(&img, &conv, white);
        assert!(
            (wall * 2f64.powf(stops as f64) / white as f64 - 1.0).abs() < 1e-4,
            "{view:?}: {stops}"
        );
        assert_eq!(Exposure::Auto.stops(&img, &conv, white), stops);
    }
    // A uniform image is not held back: its log-average lands on middle grey.
    let flat = ramp(4, 4, 1e-3);
    let one = ramp(1, 4, 1e-3);
    assert_eq!(
        protected_stops(&one, &conv, 1.0),
        metered_stops(&one, &conv)
    );
    assert!(protected_stops(&flat, &conv, 1.0) <= metered_stops(&flat, &conv));
}

/// Reads a PNG as RGB rows.
fn read_png(path: &std::path::Path) -> (usize, usize, Vec<u8>) {
    let img = image::open(path).expect("png").to_rgb8();
    (img.width() as usize, img.height() as usize, img.into_raw())
}

/// Position of a colour on the map (nearest of 4096 samples).
fn position(c: [u8; 3]) -> f64 {
    (0..4096)
        .map(|k| k as f64 / 4095.0)
        .min_by_key(|t| {
            let m = false_colour::colour(*t);
            (0..3)
                .map(|i| (m[i] as i32 - c[i] as i32).pow(2))
                .sum::<i32>()
        })
        .expect("samples")
}

#[test]
fn false_colour_maps_a_ramp_monotonically_with_a_legend() {
    let dir = tempfile::tempdir().expect("tempdir");
    let img = ramp(40, 30, 1e-6);
    let path = dir.path().join("map.png");
    let range = [
        cd(&img, 1e-6) as f32,
        cd(&img, 1e-6 * 10f32.powf(39.0 / 8.0)) as f32,
    ];
    false_colour::write(&path, &img, Some(range)).expect("write");
    let (w, h, px) = read_png(&path);
    assert_eq!((w, h), (40 + PANEL, MIN_HEIGHT));
    let at = |x: usize, y: usize| {
        let i = (y * w + x) * 3;
        [px[i], px[i + 1], px[i + 2]]
    };
    // Along the ramp: positions rise, from the map's low end to its high end, linearly in
    // log luminance (each pixel a factor 10^(1/8) brighter).
    let pos: Vec<f64> = (0..40).map(|x| position(at(x, 10))).collect();
    for x in 1..40 {
        assert!(
            pos[x] > pos[x - 1],
            "x = {x}: {} then {}",
            pos[x - 1],
            pos[x]
        );
        assert!(
            (pos[x] - x as f64 / 39.0).abs() < 0.01,
            "x = {x}: {}",
            pos[x]
        );
    }
    // The legend bar: the map from top (high) to bottom (low).
    let x = 40 + BAR_X + BAR_W / 2;
    let (top, bottom) = (BAR_TOP, h - BAR_BOTTOM - 1);
    assert!(position(at(x, top)) > 0.99 && position(at(x, bottom)) < 0.01);
    let bar: Vec<f64> = (top..=bottom)
        .step_by(10)
        .map(|y| position(at(x, y)))
        .collect();
    assert!(bar.windows(2).all(|p| p[1] < p[0]), "{bar:?}");
    // Labels: ink right of the bar at each decade tick, and the unit above it.
    let ink = |x0: usize, x1: usize, y0: usize, y1: usize| {
        (y0..y1)
            .flat_map(|y| (x0..x1).map(move |x| (x, y)))
            .filter(|&(x, y)| at(x, y) == INK)
            .count()
    };
    let ticks = false_colour::ticks([range[0] as f64, range[1] as f64]);
    assert!(ticks.len() >= 4, "{ticks:?}");
    let label_x = 40 + BAR_X + BAR_W;
    assert!(
        ink(label_x, w, top, bottom + 1) > 40 * ticks.len(),
        "labels drawn"
    );
    assert!(ink(40 + BAR_X, w, 0, BAR_TOP) > 20, "unit drawn");
    assert_eq!(at(w - 1, h - 1), BACKGROUND);
}
