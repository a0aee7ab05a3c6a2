//! RGB image textures stored as per-texel spectra.

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use glam::Vec2;
use serde::{Deserialize, Serialize};

use crate::spectrum::{MAX_BINS, Spectrum};

#[derive(Debug, thiserror::Error)]
pub enum TextureError {
    #[error("cannot read texture {path}: {message}")]
    Read { path: PathBuf, message: String },
    #[error("texture {path}: unsupported file type (use .png or .exr)")]
    Format { path: PathBuf },
}

/// How a texture's stored values are decoded to linear RGB (`colour_space` in a scene).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Encoding {
    /// The sRGB transfer curve (IEC 61966-2-1): 8-bit colour images.
    Srgb,
    /// Stored values are linear already: EXR files, data such as masks.
    Linear,
}

impl Encoding {
    /// The convention of a file type: EXR stores linear values, other images sRGB-encoded ones.
    pub fn default_for(path: &Path) -> Encoding {
        match lower_extension(path).as_deref() {
            Some("exr") => Encoding::Linear,
            _ => Encoding::Srgb,
        }
    }

    fn decode(self, c: f32) -> f32 {
        match self {
            Encoding::Srgb => srgb_to_linear(c),
            Encoding::Linear => c,
        }
    }
}

/// What a lookup outside [0, 1] sees (`wrap` in a scene).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Wrap {
    /// The image tiles the plane.
    #[default]
    Repeat,
    /// The edge texels extend outwards.
    Clamp,
}

/// Spectral texture: `n` bins per texel, row 0 at the top of the image. Lookups are bilinear;
/// v = 0 is the bottom row (the OBJ / OpenGL convention).
///
/// Texels are stored as indices into a palette of their distinct spectra, each upsampled once.
/// Patterns, labels and masks have a handful of colours: their palette stays in the L1 cache
/// where one spectrum per texel (128 bytes at 32 bins) made every light-pass lookup a cache
/// miss; a photograph's texels cost 4 bytes more each than they would stored whole.
#[derive(Clone, Debug)]
pub struct Texture {
    width: usize,
    height: usize,
    n: usize,
    /// Distinct spectra, `n` floats each.
    palette: Vec<f32>,
    /// Per texel (row-major, top row first), its spectrum's index in `palette`.
    index: Vec<u32>,
    wrap: Wrap,
}

impl Texture {
    /// Builds from linear RGB texels (row-major, top row first); `to_spectrum` upsamples each.
    pub fn from_rgb(
        width: usize,
        height: usize,
        rgb: &[[f32; 3]],
        n_bins: usize,
        to_spectrum: &dyn Fn([f32; 3]) -> Spectrum,
    ) -> Texture {
        let n = n_bins.clamp(1, MAX_BINS);
        let texels = width.max(1) * height.max(1);
        let mut palette = Vec::new();
        let mut index = Vec::with_capacity(texels);
        // Keyed by the colour's bits: equal texels share one upsampling and one entry.
        let mut seen: HashMap<[u32; 3], u32> = HashMap::new();
        for &c in rgb.iter().take(width * height) {
            let i = *seen.entry(c.map(f32::to_bits)).or_insert_with(|| {
                palette.extend_from_slice(to_spectrum(c).as_slice(n));
                (palette.len() / n - 1) as u32
            });
            index.push(i);
        }
        if index.len() < texels {
            // Missing texels are black, as a short buffer always read.
            let black = (palette.len() / n) as u32;
            palette.resize(palette.len() + n, 0.0);
            index.resize(texels, black);
        }
        Texture {
            width: width.max(1),
            height: height.max(1),
            n,
            palette,
            index,
            wrap: Wrap::Repeat,
        }
    }

    /// The same texels, looked up with `wrap` outside [0, 1].
    pub fn with_wrap(mut self, wrap: Wrap) -> Texture {
        self.wrap = wrap;
        self
    }

    /// Loads a PNG (sRGB-encoded: decoded to linear) or an EXR (linear) file.
    pub fn load(
        path: &Path,
        n_bins: usize,
        to_spectrum: &dyn Fn([f32; 3]) -> Spectrum,
    ) -> Result<Texture, TextureError> {
        Self::load_encoded(path, Encoding::default_for(path), n_bins, to_spectrum)
    }

    /// Loads a PNG or EXR file whose values are decoded from `encoding` to linear RGB before
    /// `to_spectrum` upsamples them.
    pub fn load_encoded(
        path: &Path,
        encoding: Encoding,
        n_bins: usize,
        to_spectrum: &dyn Fn([f32; 3]) -> Spectrum,
    ) -> Result<Texture, TextureError> {
        let read_err = |message: String| TextureError::Read {
            path: path.to_path_buf(),
            message,
        };
        let (w, h, rgb) = match lower_extension(path).as_deref() {
            Some("png") => {
                let img = image::ImageReader::open(path)
                    .map_err(|e| read_err(e.to_string()))?
                    .decode()
                    .map_err(|e| read_err(e.to_string()))?
                    .to_rgb32f();
                let (w, h) = (img.width() as usize, img.height() as usize);
                let rgb = img
                    .pixels()
                    .map(|p| p.0.map(|c| encoding.decode(c)))
                    .collect();
                (w, h, rgb)
            }
            Some("exr") => {
                let img = exr::prelude::read_first_rgba_layer_from_file(
                    path,
                    |res, _| (res.width(), vec![[0.0f32; 3]; res.width() * res.height()]),
                    |(w, px): &mut (usize, Vec<[f32; 3]>),
                     pos,
                     (r, g, b, _a): (f32, f32, f32, f32)| {
                        px[pos.y() * *w + pos.x()] = [r, g, b];
                    },
                )
                .map_err(|e| read_err(e.to_string()))?;
                let size = img.layer_data.size;
                let (_, mut px) = img.layer_data.channel_data.pixels;
                if encoding != Encoding::Linear {
                    for p in &mut px {
                        *p = p.map(|c| encoding.decode(c));
                    }
                }
                (size.width(), size.height(), px)
            }
            _ => {
                return Err(TextureError::Format {
                    path: path.to_path_buf(),
                });
            }
        };
        if w == 0 || h == 0 {
            return Err(read_err("empty image".into()));
        }
        Ok(Self::from_rgb(w, h, &rgb, n_bins, to_spectrum))
    }

    /// Decodes a PNG or JPEG image held in memory (a glTF's embedded texture) to linear RGB
    /// texels, top row first: (width, height, texels). The size is read from the header and
    /// refused above `max_pixels` before the pixels are allocated.
    pub fn decode_memory(
        bytes: &[u8],
        encoding: Encoding,
        max_pixels: u64,
    ) -> Result<(usize, usize, Vec<[f32; 3]>), String> {
        let reader = || {
            image::ImageReader::new(std::io::Cursor::new(bytes))
                .with_guessed_format()
                .map_err(|e| e.to_string())
        };
        let (w, h) = reader()?.into_dimensions().map_err(|e| e.to_string())?;
        if w == 0 || h == 0 || w as u64 * h as u64 > max_pixels {
            return Err(format!(
                "{w} x {h} pixels: outside the 1..={max_pixels} pixels accepted"
            ));
        }
        let img = reader()?.decode().map_err(|e| e.to_string())?.to_rgb32f();
        let rgb = img
            .pixels()
            .map(|p| p.0.map(|c| encoding.decode(c)))
            .collect();
        Ok((w as usize, h as usize, rgb))
    }

    pub fn resolution(&self) -> (usize, usize) {
        (self.width, self.height)
    }

    pub fn wrap(&self) -> Wrap {
        self.wrap
    }

    /// Largest and smallest value of any texel in any of its bins.
    pub fn value_range(&self) -> (f32, f32) {
        self.palette
            .iter()
            .fold((f32::INFINITY, f32::NEG_INFINITY), |(lo, hi), &v| {
                (lo.min(v), hi.max(v))
            })
    }

    fn texel(&self, x: usize, y: usize) -> &[f32] {
        let i = self.index[y * self.width + x] as usize * self.n;
        &self.palette[i..i + self.n]
    }

    /// Bilinear lookup, wrapping outside [0, 1] as the texture's [`Wrap`] says.
    pub fn lookup(&self, uv: Vec2) -> Spectrum {
        let fx = uv.x * self.width as f32 - 0.5;
        let fy = (1.0 - uv.y) * self.height as f32 - 0.5;
        let (x0, y0) = (fx.floor(), fy.floor());
        let (tx, ty) = (fx - x0, fy - y0);
        let mode = self.wrap;
        let wrap = |i: f32, n: usize| match mode {
            Wrap::Repeat => (i as i64).rem_euclid(n as i64) as usize,
            Wrap::Clamp => (i as i64).clamp(0, n as i64 - 1) as usize,
        };
        let (xa, xb) = (wrap(x0, self.width), wrap(x0 + 1.0, self.width));
        let (ya, yb) = (wrap(y0, self.height), wrap(y0 + 1.0, self.height));
        let mut s = Spectrum::ZERO;
        let corners = [
            (xa, ya, (1.0 - tx) * (1.0 - ty)),
            (xb, ya, tx * (1.0 - ty)),
            (xa, yb, (1.0 - tx) * ty),
            (xb, yb, tx * ty),
        ];
        for (x, y, w) in corners {
            for (o, v) in s.0.iter_mut().zip(self.texel(x, y)) {
                *o += w * v;
            }
        }
        s
    }
}

fn lower_extension(path: &Path) -> Option<String> {
    path.extension()
        .and_then(|e| e.to_str())
        .map(|e| e.to_ascii_lowercase())
}

fn srgb_to_linear(c: f32) -> f32 {
    if c <= 0.04045 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::cell::Cell;

    /// A made-up upsampling that tells bins and colours apart.
    fn up(c: [f32; 3], n: usize) -> Spectrum {
        let mut s = Spectrum::ZERO;
        for (b, v) in s.0[..n].iter_mut().enumerate() {
            *v = c[b % 3] * (b as f32 + 1.0);
        }
        s
    }

    /// Equal texels share one palette entry and one upsampling; every texel reads its own
    /// colour's spectrum, and a lookup between texels blends them bilinearly.
    #[test]
    fn palette_holds_each_colour_once_and_texels_read_their_own() {
        let (w, h, n) = (5, 3, 4);
        // The third colour differs from the first by 1e-4 in blue: a palette entry of its own.
        let colours = [[0.1, 0.2, 0.3], [0.9, 0.5, 0.0], [0.1, 0.2, 0.3001]];
        let rgb: Vec<[f32; 3]> = (0..w * h).map(|i| colours[(i * 7 + i / 5) % 3]).collect();
        let calls = Cell::new(0);
        let counted = |c: [f32; 3]| {
            calls.set(calls.get() + 1);
            up(c, n)
        };
        let t = Texture::from_rgb(w, h, &rgb, n, &counted);
        assert_eq!(calls.get(), 3);
        assert_eq!(t.palette.len(), 3 * n);
        for y in 0..h {
            for x in 0..w {
                assert_eq!(
                    t.texel(x, y),
                    &up(rgb[y * w + x], n).0[..n],
                    "texel ({x}, {y})"
                );
            }
        }
        // Half way between texels (0, 0) and (1, 0) of the top row (v = 1 is the top).
        let (a, b) = (up(rgb[0], n), up(rgb[1], n));
        let mid = t.lookup(Vec2::new(1.0 / w as f32, 1.0 - 0.5 / h as f32));
        for k in 0..n {
            assert!((mid.0[k] - 0.5 * (a.0[k] + b.0[k])).abs() < 1e-6, "bin {k}");
        }
        assert_eq!(t.value_range(), (0.0, 0.9 * 4.0));
    }

    /// Texels the buffer does not hold are black, as before the palette.
    #[test]
    fn a_short_buffer_leaves_the_missing_texels_black() {
        let t = Texture::from_rgb(2, 2, &[[0.5, 0.5, 0.5]], 3, &|c| up(c, 3));
        assert_eq!(t.texel(0, 0), &up([0.5; 3], 3).0[..3]);
        for (x, y) in [(1, 0), (0, 1), (1, 1)] {
            assert_eq!(t.texel(x, y), &[0.0; 3]);
        }
    }
}
