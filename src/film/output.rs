//! Image writers. The output format follows the file extension: `.exr` (scene-linear) or `.png`
//! (display-referred sRGB). Files are written to a temporary name beside the target and renamed,
//! so an existing output is never left half-written.

use std::path::{Path, PathBuf};

use crate::colour::{ColourSpace, Observer, ViewTransform};

use super::SpectralImage;

#[derive(Clone, Copy, Debug, Default)]
pub struct OutputOptions {
    pub colour_space: ColourSpace,
    pub observer: Observer,
    pub view: ViewTransform,
    /// Exposure in stops applied before the view transform (PNG only).
    pub exposure: f32,
    pub half: bool,
    pub spectral_layers: bool,
    pub noise_layer: bool,
}

#[derive(Debug, thiserror::Error)]
pub enum OutputError {
    #[error("{path}: unsupported output extension (use .exr or .png)")]
    Extension { path: PathBuf },
    #[error("{path}: {message}")]
    Write { path: PathBuf, message: String },
}

/// Output formats brume can write, chosen by extension.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    Exr,
    Png,
}

pub fn format_of(path: &Path) -> Result<Format, OutputError> {
    match path
        .extension()
        .and_then(|e| e.to_str())
        .map(|e| e.to_ascii_lowercase())
        .as_deref()
    {
        Some("exr") => Ok(Format::Exr),
        Some("png") => Ok(Format::Png),
        _ => Err(OutputError::Extension {
            path: path.to_path_buf(),
        }),
    }
}

pub fn write(path: &Path, img: &SpectralImage, opts: &OutputOptions) -> Result<(), OutputError> {
    let format = format_of(path)?;
    let werr = |message: String| OutputError::Write {
        path: path.to_path_buf(),
        message,
    };
    let tmp = temp_name(path);
    let rgb = to_working_rgb(img, opts);
    let result = match format {
        Format::Exr => write_exr(&tmp, img.width, img.height, &rgb),
        Format::Png => write_png(&tmp, img.width, img.height, &rgb, opts),
    };
    if let Err(e) = result {
        let _ = std::fs::remove_file(&tmp);
        return Err(werr(e));
    }
    std::fs::rename(&tmp, path).map_err(|e| {
        let _ = std::fs::remove_file(&tmp);
        werr(e.to_string())
    })
}

fn temp_name(path: &Path) -> PathBuf {
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    // Keep the extension last: some writers infer the format from it.
    path.with_file_name(format!(".{name}.{}.tmp.{}", std::process::id(), ext(path)))
}

fn ext(path: &Path) -> String {
    path.extension()
        .map(|e| e.to_string_lossy().into_owned())
        .unwrap_or_default()
}

/// Gaussian with separate widths left and right of its peak.
fn lobe(l: f64, mu: f64, s1: f64, s2: f64) -> f64 {
    let s = if l < mu { s1 } else { s2 };
    (-0.5 * ((l - mu) / s).powi(2)).exp()
}

/// Analytic multi-lobe fit of the CIE 1931 2-degree observer (Wyman, Sloan, Shirley 2013).
fn cmf_1931_fit(l: f64) -> [f64; 3] {
    let x = 1.056 * lobe(l, 599.8, 37.9, 31.0) + 0.362 * lobe(l, 442.0, 16.0, 26.7)
        - 0.065 * lobe(l, 501.1, 20.4, 26.2);
    let y = 0.821 * lobe(l, 568.8, 46.9, 40.5) + 0.286 * lobe(l, 530.9, 16.3, 31.1);
    let z = 1.217 * lobe(l, 437.0, 11.8, 36.0) + 0.681 * lobe(l, 459.0, 26.0, 13.8);
    [x, y, z]
}

fn to_working_rgb(img: &SpectralImage, _opts: &OutputOptions) -> Vec<[f32; 3]> {
    let g = img.grid;
    let weights: Vec<[f64; 3]> = (0..g.n)
        .map(|i| {
            let (a, b) = g.edges(i);
            let steps = ((b - a).ceil() as usize).max(1);
            let h = (b - a) / steps as f64;
            let mut w = [0.0; 3];
            for k in 0..steps {
                let c = cmf_1931_fit(a + (k as f64 + 0.5) * h);
                for j in 0..3 {
                    w[j] += c[j] * h;
                }
            }
            w
        })
        .collect();
    const M: [[f64; 3]; 3] = [
        [3.2404542, -1.5371385, -0.4985314],
        [-0.9692660, 1.8760108, 0.0415560],
        [0.0556434, -0.2040259, 1.0572252],
    ];
    img.data
        .chunks_exact(g.n)
        .map(|px| {
            let mut xyz = [0.0f64; 3];
            for (v, w) in px.iter().zip(&weights) {
                for j in 0..3 {
                    xyz[j] += *v as f64 * w[j];
                }
            }
            let mut rgb = [0.0f32; 3];
            for (r, row) in rgb.iter_mut().zip(&M) {
                *r = (row[0] * xyz[0] + row[1] * xyz[1] + row[2] * xyz[2]) as f32;
            }
            rgb
        })
        .collect()
}

fn write_exr(path: &Path, w: usize, h: usize, rgb: &[[f32; 3]]) -> Result<(), String> {
    exr::prelude::write_rgb_file(path, w, h, |x, y| {
        let p = rgb[y * w + x];
        (p[0], p[1], p[2])
    })
    .map_err(|e| e.to_string())
}

fn srgb_encode(v: f32) -> f32 {
    if v <= 0.003_130_8 {
        12.92 * v
    } else {
        1.055 * v.powf(1.0 / 2.4) - 0.055
    }
}

fn write_png(
    path: &Path,
    w: usize,
    h: usize,
    rgb: &[[f32; 3]],
    opts: &OutputOptions,
) -> Result<(), String> {
    let scale = 2f32.powf(opts.exposure);
    let mut buf = Vec::with_capacity(w * h * 3);
    for p in rgb {
        for c in p {
            let v = srgb_encode((c * scale).clamp(0.0, 1.0));
            buf.push((v * 255.0 + 0.5) as u8);
        }
    }
    image::save_buffer_with_format(
        path,
        &buf,
        w as u32,
        h as u32,
        image::ColorType::Rgb8,
        image::ImageFormat::Png,
    )
    .map_err(|e| e.to_string())
}
