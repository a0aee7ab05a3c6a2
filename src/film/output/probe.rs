//! Reading luminance back from an EXR output (`brume probe`): the Y of its RGB (from the
//! file's `chromaticities`), in cd/m² when the file is photometric, and its standard error from
//! the noise layer.

use std::path::{Path, PathBuf};

use exr::prelude::*;

use super::Units;
use super::exr::UNITS_ATTRIBUTE;
use crate::colour::matrix;

/// Luminance per pixel of an EXR and what it is in.
#[derive(Clone, Debug)]
pub struct ProbeImage {
    pub path: PathBuf,
    pub width: usize,
    pub height: usize,
    /// None for an EXR not written by brume (no units attribute).
    pub units: Option<Units>,
    /// cd/m² of RGB (1, 1, 1) (OpenEXR's `whiteLuminance`), when the file says.
    pub white_luminance: Option<f64>,
    /// Y of each pixel (row-major), in the file's units.
    pub y: Vec<f64>,
    /// Standard error of each pixel's Y: `noise.Y`, or from `noise.R/G/B` as if independent.
    pub noise: Option<Vec<f64>>,
}

/// The mean Y over a region and its standard error.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Probed {
    /// Over the finite pixels (NaN when there is none).
    pub mean: f64,
    /// Treating the pixels' errors as independent (None without a noise layer). A **lower
    /// bound**: the pixels of one pass share its forward rays, so their errors are positively
    /// correlated and the error of their mean can be several times larger (8x measured against
    /// a luminance sensor over the same pixels, which gives the exact error of a region).
    pub std_error: Option<f64>,
    /// Pixels in the mean.
    pub pixels: usize,
    /// Pixels of the region left out: their Y (or its standard error) is NaN or infinite.
    pub non_finite: usize,
}

#[derive(Debug, thiserror::Error)]
#[error("{}: {message}", path.display())]
pub struct ProbeError {
    pub path: PathBuf,
    pub message: String,
}

fn channel<'a>(layer: &'a AnyChannels<FlatSamples>, name: &str) -> Option<&'a FlatSamples> {
    layer
        .list
        .iter()
        .find(|c| c.name.eq(name))
        .map(|c| &c.sample_data)
}

fn values(s: &FlatSamples) -> Vec<f64> {
    (0..s.len())
        .map(|i| s.value_by_flat_index(i).to_f32() as f64)
        .collect()
}

/// Reads the luminance of an EXR file.
pub fn read(path: &Path) -> std::result::Result<ProbeImage, ProbeError> {
    let fail = |message: String| ProbeError {
        path: path.to_path_buf(),
        message,
    };
    let img = read_all_flat_layers_from_file(path).map_err(|e| fail(e.to_string()))?;
    let layer = img
        .layer_data
        .first()
        .ok_or_else(|| fail("no image in the file".into()))?;
    let (width, height) = (layer.size.width(), layer.size.height());
    let rgb: Vec<Vec<f64>> = ["R", "G", "B"]
        .iter()
        .map(|c| channel(&layer.channel_data, c).map(values))
        .collect::<Option<_>>()
        .ok_or_else(|| fail("no R, G, B channels".into()))?;
    let w = match img.attributes.chromaticities {
        Some(c) => {
            let v = |p: Vec2<f32>| [p.0 as f64, p.1 as f64];
            matrix::rgb_to_xyz([v(c.red), v(c.green), v(c.blue)], v(c.white))[1]
        }
        // OpenEXR's default primaries are Rec.709 with a D65 white.
        None => [0.2126, 0.7152, 0.0722],
    };
    let y = (0..width * height)
        .map(|i| w[0] * rgb[0][i] + w[1] * rgb[1][i] + w[2] * rgb[2][i])
        .collect();
    let noise = match channel(&layer.channel_data, "noise.Y") {
        Some(s) => Some(values(s)),
        None => ["noise.R", "noise.G", "noise.B"]
            .iter()
            .map(|c| channel(&layer.channel_data, c).map(values))
            .collect::<Option<Vec<_>>>()
            .map(|e| {
                (0..width * height)
                    .map(|i| (0..3).map(|c| (w[c] * e[c][i]).powi(2)).sum::<f64>().sqrt())
                    .collect()
            }),
    };
    // Custom attributes come back in the layer's or the image's table, by the reader's choice.
    let key = Text::from(UNITS_ATTRIBUTE);
    let attribute = layer
        .attributes
        .other
        .get(&key)
        .or_else(|| img.attributes.other.get(&key));
    let units = match attribute {
        Some(AttributeValue::Text(t)) if t == &Text::from("photometric") => {
            Some(Units::Photometric)
        }
        Some(AttributeValue::Text(t)) if t == &Text::from("radiometric") => {
            Some(Units::Radiometric)
        }
        _ => None,
    };
    Ok(ProbeImage {
        path: path.to_path_buf(),
        width,
        height,
        units,
        white_luminance: layer.attributes.white_luminance.map(|v| v as f64),
        y,
        noise,
    })
}

impl ProbeImage {
    /// The mean over pixels `x0 <= x < x1`, `y0 <= y < y1`; None when the region is empty or
    /// outside the image.
    pub fn region(&self, [x0, y0, x1, y1]: [usize; 4]) -> Option<Probed> {
        if !(x0 < x1 && y0 < y1 && x1 <= self.width && y1 <= self.height) {
            return None;
        }
        let (mut sum, mut var, mut count, mut bad) = (0.0, 0.0, 0usize, 0usize);
        for y in y0..y1 {
            for x in x0..x1 {
                let i = y * self.width + x;
                let n = self.noise.as_ref().map_or(0.0, |n| n[i]);
                if !(self.y[i].is_finite() && n.is_finite()) {
                    bad += 1;
                    continue;
                }
                sum += self.y[i];
                var += n * n;
                count += 1;
            }
        }
        let c = count as f64;
        Some(Probed {
            mean: if count > 0 { sum / c } else { f64::NAN },
            std_error: self
                .noise
                .as_ref()
                .filter(|_| count > 0)
                .map(|_| var.sqrt() / c),
            pixels: count,
            non_finite: bad,
        })
    }
}
