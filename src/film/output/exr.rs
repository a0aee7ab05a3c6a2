//! OpenEXR output: working-space RGB with its `chromaticities`, plus the optional spectral
//! layout of Fichet, Pacanowski and Wilkie (JCGT 2021) and a standard-error layer.

use std::path::Path;

use exr::meta::attribute::Chromaticities;
use exr::prelude::*;

use super::{OutputOptions, Units, to_rgb};
use crate::colour::photometry::luminance_scale;
use crate::colour::{ColourSpace, FilmToRgb};
use crate::film::SpectralImage;

/// The header attribute naming what the colour channels hold: "radiometric" or
/// "photometric" (Y in cd/m²).
pub const UNITS_ATTRIBUTE: &str = "brumeUnits";

/// The spectral layout's name for an emissive (unpolarised, Stokes S0) channel at `centre` nm:
/// the wavelength printed with six decimals and a comma as decimal separator, so that the
/// dot stays the layer separator: 550 nm -> `S0.550,000000nm`.
pub fn spectral_channel_name(centre: f64) -> String {
    format!("S0.{}nm", format!("{centre:.6}").replace('.', ","))
}

fn samples(values: Vec<f32>, half: bool) -> FlatSamples {
    if half {
        // Clamp to the largest finite half (as pbrt does) rather than turn bright pixels into inf.
        let max = f16::MAX.to_f32();
        FlatSamples::F16(
            values
                .into_iter()
                .map(|v| f16::from_f32(v.clamp(-max, max)))
                .collect(),
        )
    } else {
        FlatSamples::F32(values)
    }
}

/// One channel per RGB component of `rgb` times `k`, named `<prefix>R` etc.
fn rgb_channels(
    out: &mut Vec<AnyChannel<FlatSamples>>,
    prefix: &str,
    (rgb, k): (&[[f32; 3]], f32),
    half: bool,
) {
    for (c, name) in ["R", "G", "B"].iter().enumerate() {
        let v = rgb.iter().map(|p| p[c] * k).collect();
        out.push(AnyChannel::new(
            Text::from(format!("{prefix}{name}").as_str()),
            samples(v, half),
        ));
    }
}

/// The `n + 1` bin edges in nm, space-separated.
fn bin_edges(img: &SpectralImage) -> String {
    let g = &img.grid;
    let mut edges: Vec<String> = (0..g.n).map(|i| g.edges(i).0.to_string()).collect();
    edges.push(g.edges(g.n - 1).1.to_string());
    edges.join(" ")
}

/// One channel per bin, named `<prefix>S0.<centre>nm` (a line bin: at its line).
fn spectral_channels(
    out: &mut Vec<AnyChannel<FlatSamples>>,
    prefix: &str,
    img: &SpectralImage,
    data: &[f32],
    half: bool,
) {
    let n = img.grid.n;
    for i in 0..n {
        let v = data.iter().skip(i).step_by(n).copied().collect();
        let name = format!("{prefix}{}", spectral_channel_name(img.grid.centre(i)));
        out.push(AnyChannel::new(Text::from(name.as_str()), samples(v, half)));
    }
}

pub(super) fn write(
    path: &Path,
    img: &SpectralImage,
    opts: &OutputOptions,
) -> std::result::Result<(), String> {
    let space = opts.colour_space;
    let half = opts.half;
    // cd/m² per unit of the film's Y: the photometric scale, and the EXR's whiteLuminance.
    let per_y = luminance_scale(opts.observer).map_err(|e| e.to_string())? as f32;
    let k = match opts.units {
        Units::Radiometric => 1.0,
        Units::Photometric => per_y,
    };
    let mut ch = Vec::new();
    rgb_channels(
        &mut ch,
        "",
        (&to_rgb(img, &img.data, space, opts)?, k),
        half,
    );
    if opts.spectral_layers {
        spectral_channels(&mut ch, "", img, &img.data, half);
    }
    for (name, data) in &img.layers {
        let rgb = to_rgb(img, data, space, opts)?;
        rgb_channels(&mut ch, &format!("{name}."), (&rgb, k), half);
        if opts.spectral_layers {
            spectral_channels(&mut ch, &format!("{name}."), img, data, half);
        }
    }
    if let (true, Some(noise)) = (opts.noise_layer, &img.noise) {
        noise_channels(&mut ch, img, noise, opts, k)?;
    }
    let attributes = LayerAttributes {
        // The luminance (cd/m²) of RGB (1, 1, 1), as OpenEXR defines `whiteLuminance`.
        white_luminance: Some(per_y / k),
        ..LayerAttributes::default()
    };
    let layer = Layer::new(
        (img.width, img.height),
        attributes,
        Encoding::SMALL_LOSSLESS,
        AnyChannels::sort(ch.into()),
    );
    let mut image = Image::from_layer(layer);
    header_attributes(&mut image, img, space, opts);
    write_sorted(image, path)
}

/// The header's chromaticities and brume's text attributes (colour space, units, the caller's
/// extra attributes, the spectral layout).
fn header_attributes(
    image: &mut Image<Layer<AnyChannels<FlatSamples>>>,
    img: &SpectralImage,
    space: ColourSpace,
    opts: &OutputOptions,
) {
    let (p, w) = space.chromaticities();
    let v = |xy: [f64; 2]| Vec2(xy[0] as f32, xy[1] as f32);
    image.attributes.chromaticities = Some(Chromaticities {
        red: v(p[0]),
        green: v(p[1]),
        blue: v(p[2]),
        white: v(w),
    });
    let mut text = |k: &str, val: &str| {
        image
            .attributes
            .other
            .insert(Text::from(k), AttributeValue::Text(Text::from(val)));
    };
    text(
        "brumeColourSpace",
        match space {
            ColourSpace::Srgb => "lin_rec709",
            ColourSpace::Acescg => "acescg",
            ColourSpace::Xyz => "ciexyz",
        },
    );
    text(UNITS_ATTRIBUTE, opts.units.name());
    for (name, value) in &opts.attributes {
        text(name, value);
    }
    if opts.spectral_layers {
        text("spectralLayoutVersion", "1.0");
        // The layout's unit for emissive data; channel values are spectral radiance, i.e. per
        // nanometre (bin averages), as in pbrt-v4's spectral film.
        text("emissiveUnits", "W.m^-2.sr^-1");
        // Bins differ in width once spectral lines split them (a line's channel is named at
        // the line and holds its power over its narrow bin): the edges let a reader integrate.
        text("brumeBinEdges", &bin_edges(img));
    }
}

/// Writes `image` with its header's attributes in name order: same passes, same bytes (the
/// crate's own attribute order varies between processes).
fn write_sorted(
    image: Image<Layer<AnyChannels<FlatSamples>>>,
    path: &Path,
) -> std::result::Result<(), String> {
    let mut bytes = std::io::Cursor::new(Vec::new());
    image
        .write()
        .to_buffered(&mut bytes)
        .map_err(|e| e.to_string())?;
    let mut bytes = bytes.into_inner();
    super::exr_header::sort_attributes(&mut bytes);
    std::fs::write(path, bytes).map_err(|e| e.to_string())
}

/// The standard-error layer: `noise.R/G/B` and `noise.Y` (the luminance channel's error), both
/// computed as if the bins were independent, scaled by `k` as the image; per bin with
/// spectral layers.
fn noise_channels(
    ch: &mut Vec<AnyChannel<FlatSamples>>,
    img: &SpectralImage,
    noise: &[f32],
    opts: &OutputOptions,
    k: f32,
) -> std::result::Result<(), String> {
    let conv = FilmToRgb::new(opts.colour_space, opts.observer, &img.grid, opts.cat)
        .map_err(|e| e.to_string())?;
    let rgb: Vec<[f32; 3]> = noise
        .chunks_exact(img.grid.n)
        .map(|px| conv.rgb_std_error(px))
        .collect();
    rgb_channels(ch, "noise.", (&rgb, k), opts.half);
    let y: Vec<f32> = noise
        .chunks_exact(img.grid.n)
        .map(|px| {
            let var: f64 = px
                .iter()
                .zip(&conv.xyz.w)
                .map(|(e, w)| (*e as f64 * w[1]).powi(2))
                .sum();
            var.sqrt() as f32 * k
        })
        .collect();
    ch.push(AnyChannel::new(
        Text::from("noise.Y"),
        samples(y, opts.half),
    ));
    if opts.spectral_layers {
        spectral_channels(ch, "noise.", img, noise, opts.half);
    }
    Ok(())
}
