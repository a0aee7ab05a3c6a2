//! False-colour luminance maps: each pixel's luminance (cd/m², CIE 1931 V(λ), K_m = 683 lm/W)
//! on a logarithmic scale through the viridis colour map (`colorous`), with a legend bar on the
//! right labelled in cd/m² (an 8x8 bitmap font, `font8x8`).
//!
//! Layout: the image at the top left; a panel [`PANEL`] pixels wide on its right holding the
//! bar ([`BAR_X`].. [`BAR_X`] + [`BAR_W`], from [`BAR_TOP`] to `height - BAR_BOTTOM`, the
//! highest luminance at the top) with a tick and a label per decade (and at 2 and 5 when the
//! range spans less than two decades), and the unit above it. The output is at least
//! [`MIN_HEIGHT`] pixels high so that the legend stays readable under small images.

use std::path::Path;

use super::{OutputError, png};
use crate::colour::photometry;
use crate::film::SpectralImage;

pub const PANEL: usize = 104;
pub const BAR_X: usize = 10;
pub const BAR_W: usize = 16;
pub const BAR_TOP: usize = 20;
pub const BAR_BOTTOM: usize = 10;
pub const MIN_HEIGHT: usize = 200;
/// Background of the panel and of the area below a short image.
pub const BACKGROUND: [u8; 3] = [24, 24, 24];
/// Colour of ticks and labels.
pub const INK: [u8; 3] = [235, 235, 235];

/// The colour of the map at `t` in [0, 1] (0: the range's low end).
pub fn colour(t: f64) -> [u8; 3] {
    let c = colorous::VIRIDIS.eval_continuous(t.clamp(0.0, 1.0));
    [c.r, c.g, c.b]
}

/// Each pixel's luminance in cd/m².
pub fn luminance(img: &SpectralImage) -> Result<Vec<f64>, String> {
    let w = photometry::luminous_weights(&img.grid).map_err(|e| e.to_string())?;
    let n = img.grid.n;
    Ok(img
        .data
        .chunks_exact(n)
        .map(|px| photometry::photometric(&w, px))
        .collect())
}

/// The range shown: `range` if given, else from the 1st to the 99.5th percentile of the
/// positive luminances (at most 4 decades below the top, at least a factor 10 wide).
pub fn auto_range(lum: &[f64], range: Option<[f32; 2]>) -> [f64; 2] {
    if let Some([lo, hi]) = range {
        return [lo as f64, hi as f64];
    }
    let mut v: Vec<f64> = lum
        .iter()
        .copied()
        .filter(|v| *v > 0.0 && v.is_finite())
        .collect();
    if v.is_empty() {
        return [1e-3, 1.0];
    }
    v.sort_by(f64::total_cmp);
    let at = |q: f64| v[((v.len() - 1) as f64 * q) as usize];
    let hi = at(0.995);
    let lo = at(0.01).max(hi * 1e-4).min(hi / 10.0);
    [lo, hi]
}

/// Position of `value` on the map's log scale over `[lo, hi]`, clamped to [0, 1].
pub fn position(value: f64, [lo, hi]: [f64; 2]) -> f64 {
    if value.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
        return 0.0;
    }
    ((value.log10() - lo.log10()) / (hi.log10() - lo.log10())).clamp(0.0, 1.0)
}

/// The labelled ticks within `[lo, hi]`: every decade, and 2 and 5 times each when fewer than
/// two decades are in the range.
pub fn ticks([lo, hi]: [f64; 2]) -> Vec<f64> {
    let (a, b) = (lo.log10().floor() as i32, hi.log10().ceil() as i32);
    let decades: Vec<f64> = (a..=b).map(|e| 10f64.powi(e)).collect();
    let inside = |v: &f64| *v >= lo * (1.0 - 1e-9) && *v <= hi * (1.0 + 1e-9);
    let mut t: Vec<f64> = decades.iter().copied().filter(inside).collect();
    if t.len() < 2 {
        t = decades
            .iter()
            .flat_map(|d| [*d, 2.0 * d, 5.0 * d])
            .filter(inside)
            .collect();
    }
    t
}

/// A tick's label: plain decimals from 0.01 to 99 999, else `1e-3` style.
pub fn label(v: f64) -> String {
    if (0.01..100_000.0).contains(&v) {
        let s = format!("{v:.2}");
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        let e = v.log10().floor() as i32;
        let m = (v / 10f64.powi(e)).round();
        format!("{m}e{e}")
    }
}

/// The map as 8-bit sRGB pixels (RGB, row-major) and its size.
pub fn render(
    img: &SpectralImage,
    range: Option<[f32; 2]>,
) -> Result<(usize, usize, Vec<u8>), String> {
    let lum = luminance(img)?;
    let r = auto_range(&lum, range);
    let (w, h) = (img.width + PANEL, img.height.max(MIN_HEIGHT));
    let mut buf = vec![0u8; w * h * 3];
    for px in buf.chunks_exact_mut(3) {
        px.copy_from_slice(&BACKGROUND);
    }
    let mut put = |x: usize, y: usize, c: [u8; 3]| {
        if x < w && y < h {
            let i = (y * w + x) * 3;
            buf[i..i + 3].copy_from_slice(&c);
        }
    };
    for y in 0..img.height {
        for x in 0..img.width {
            put(x, y, colour(position(lum[y * img.width + x], r)));
        }
    }
    let (x0, top, bottom) = (img.width + BAR_X, BAR_TOP, h - BAR_BOTTOM);
    for y in top..bottom {
        let t = (bottom - 1 - y) as f64 / (bottom - 1 - top) as f64;
        for x in x0..x0 + BAR_W {
            put(x, y, colour(t));
        }
    }
    let log = |v: f64| (v.log10() - r[0].log10()) / (r[1].log10() - r[0].log10());
    for v in ticks(r) {
        let y = bottom - 1 - (log(v) * (bottom - 1 - top) as f64).round() as usize;
        for x in x0 + BAR_W..x0 + BAR_W + 4 {
            put(x, y, INK);
        }
        text(&mut put, x0 + BAR_W + 8, y.saturating_sub(4), &label(v));
    }
    text(&mut put, x0, 4, "cd/m2");
    Ok((w, h, buf))
}

/// Draws `s` with its top-left corner at (x, y) in the 8x8 font.
fn text(put: &mut impl FnMut(usize, usize, [u8; 3]), x: usize, y: usize, s: &str) {
    for (k, ch) in s.chars().enumerate() {
        let glyph = font8x8::legacy::BASIC_LEGACY
            .get(ch as usize)
            .copied()
            .unwrap_or([0; 8]);
        for (row, bits) in glyph.iter().enumerate() {
            for col in 0..8 {
                if bits & (1 << col) != 0 {
                    put(x + 8 * k + col, y + row, INK);
                }
            }
        }
    }
}

/// Writes the false-colour map of `img` to `path` (a PNG, atomically).
pub fn write(path: &Path, img: &SpectralImage, range: Option<[f32; 2]>) -> Result<(), OutputError> {
    let werr = |message: String| OutputError::Write {
        path: path.to_path_buf(),
        message,
    };
    let (w, h, buf) = render(img, range).map_err(werr)?;
    crate::film::atomic::replace(path, |tmp| {
        png::encode(tmp, w as u32, h as u32, &buf).map_err(std::io::Error::other)
    })
    .map_err(|e| werr(e.to_string()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ticks_and_labels() {
        assert_eq!(ticks([0.05, 2000.0]), vec![0.1, 1.0, 10.0, 100.0, 1000.0]);
        assert_eq!(ticks([0.3, 4.0]), vec![0.5, 1.0, 2.0]);
        assert_eq!(label(0.05), "0.05");
        assert_eq!(label(2000.0), "2000");
        assert_eq!(label(1e-3), "1e-3");
        assert_eq!(label(1e6), "1e6");
    }
}
