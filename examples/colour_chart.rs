//! Writes a colour test image through brume's film output: the 24 ColorChecker patches lit by
//! D65 (a perfect white would have Y = 1), an HDR grey ramp from 0 to 8, and a row of narrow-band
//! spectra whose colours lie outside the sRGB gamut.
//!
//! usage: colour_chart OUT.exr|OUT.png... [--bins N] [--space srgb|acescg|xyz] [--half]
//!        [--spectral] [--noise] [--view clip|filmic] [--exposure STOPS]

use std::path::PathBuf;

use brume::colour::{ColourSpace, Observer, ViewTransform, XyzWeights};
use brume::film::SpectralImage;
use brume::film::output::{OutputOptions, write};
use brume::spectrum::{Extrapolation, SpectralGrid, Spectrum, resolve};

const PATCH: usize = 16;

fn fail(msg: String) -> ! {
    eprintln!("colour_chart: {msg}");
    std::process::exit(2)
}

fn main() {
    let mut outs = Vec::new();
    let mut opts = OutputOptions::default();
    let mut bins = SpectralGrid::default().n;
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        let mut val = || {
            args.next()
                .unwrap_or_else(|| fail(format!("{a} needs a value")))
        };
        match a.as_str() {
            "--bins" => {
                bins = val()
                    .parse()
                    .unwrap_or_else(|e| fail(format!("--bins: {e}")))
            }
            "--space" => {
                opts.colour_space = match val().as_str() {
                    "srgb" => ColourSpace::Srgb,
                    "acescg" => ColourSpace::Acescg,
                    "xyz" => ColourSpace::Xyz,
                    s => fail(format!("unknown space {s}")),
                }
            }
            "--view" => {
                opts.view = match val().as_str() {
                    "clip" => ViewTransform::Clip,
                    "filmic" => ViewTransform::Filmic,
                    s => fail(format!("unknown view {s}")),
                }
            }
            "--exposure" => {
                opts.exposure = val()
                    .parse()
                    .unwrap_or_else(|e| fail(format!("--exposure: {e}")))
            }
            "--half" => opts.half = true,
            "--spectral" => opts.spectral_layers = true,
            "--noise" => opts.noise_layer = true,
            _ if a.starts_with("--") => fail(format!("unknown option {a}")),
            _ => outs.push(PathBuf::from(a)),
        }
    }
    if outs.is_empty() || !(1..=64).contains(&bins) {
        fail("usage: colour_chart OUT.exr|OUT.png... [--bins N] [--space S] [--half] [--spectral] [--noise]".into());
    }
    let img = chart(SpectralGrid::new(bins, 380.0, 780.0));
    for out in &outs {
        if let Err(e) = write(out, &img, &opts) {
            fail(e.to_string());
        }
        println!("wrote {}", out.display());
    }
}

fn chart(grid: SpectralGrid) -> SpectralImage {
    let n = grid.n;
    let get = |name: &str| {
        resolve(name, None, false)
            .unwrap_or_else(|e| fail(e.to_string()))
            .bin_averages(&grid, Extrapolation::Clamp)
    };
    let d65 = get("D65");
    let w = XyzWeights::new(Observer::Cie1931, &grid).unwrap_or_else(|e| fail(e.to_string()));
    // Radiance of a perfect white diffuser under this light: Y = 1.
    let light = d65 * (1.0 / w.xyz_of(&d65)[1] as f32);
    let (width, height) = (6 * PATCH, 5 * PATCH);
    let mut img = SpectralImage::new(width, height, grid.clone());
    let mut put = |x: usize, y: usize, s: &Spectrum| {
        let i = (y * width + x) * n;
        img.data[i..i + n].copy_from_slice(s.as_slice(n));
    };
    for p in 0..24 {
        let patch = light * get(&format!("colorchecker:{}", p + 1));
        let (px, py) = (p % 6, p / 6);
        for y in py * PATCH..(py + 1) * PATCH {
            for x in px * PATCH..(px + 1) * PATCH {
                put(x, y, &patch);
            }
        }
    }
    // Row 5, top half: HDR ramp, grey (D65-shaped) radiance with Y from 0 to 8.
    for x in 0..width {
        let s = light * (8.0 * x as f32 / (width - 1) as f32);
        for y in 4 * PATCH..4 * PATCH + PATCH / 2 {
            put(x, y, &s);
        }
    }
    // Row 5, bottom half: one bin lit at a time, out of the sRGB gamut (negative components).
    for x in 0..width {
        let bin = x * n / width;
        let s = Spectrum::single(bin, 0.5 * n as f32);
        for y in 4 * PATCH + PATCH / 2..height {
            put(x, y, &s);
        }
    }
    // A synthetic standard error (5% of the value) so the noise layer has content.
    img.noise = Some(img.data.iter().map(|v| 0.05 * v).collect());
    img
}
