//! PNG output: display-referred sRGB, 8 bits, tagged with the sRGB chunk.

use std::fs::File;
use std::io::BufWriter;
use std::path::Path;

use super::{OutputOptions, to_rgb};
use crate::colour::{ColourSpace, FilmToRgb, ViewTransform};
use crate::film::SpectralImage;

pub(super) fn write(path: &Path, img: &SpectralImage, opts: &OutputOptions) -> Result<(), String> {
    // Whatever the EXR's working space, the display is sRGB: Rec.709 primaries, D65.
    let rgb = to_rgb(img, &img.data, ColourSpace::Srgb, opts)?;
    let conv = FilmToRgb::new(ColourSpace::Srgb, opts.observer, &img.grid, opts.cat)
        .map_err(|e| e.to_string())?;
    let stops = opts.exposure.stops(img, &conv, opts.view.white());
    let mut buf = Vec::with_capacity(rgb.len() * 3);
    for p in &rgb {
        let d = opts.view.apply(*p, stops);
        buf.extend(d.map(ViewTransform::encode_u8));
    }
    encode(path, img.width as u32, img.height as u32, &buf)
}

/// Writes 8-bit sRGB pixels `buf` (RGB, row-major) as a PNG tagged sRGB.
pub(super) fn encode(path: &Path, w: u32, h: u32, buf: &[u8]) -> Result<(), String> {
    let file = File::create(path).map_err(|e| e.to_string())?;
    let mut enc = ::png::Encoder::new(BufWriter::new(file), w, h);
    enc.set_color(::png::ColorType::Rgb);
    enc.set_depth(::png::BitDepth::Eight);
    enc.set_source_srgb(::png::SrgbRenderingIntent::Perceptual);
    let mut writer = enc.write_header().map_err(|e| e.to_string())?;
    writer.write_image_data(buf).map_err(|e| e.to_string())?;
    writer.finish().map_err(|e| e.to_string())
}
