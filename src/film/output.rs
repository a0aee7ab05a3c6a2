//! Image writers. The output format follows the file extension: `.exr` (scene-linear, in the
//! chosen working space, optionally with spectral and noise layers) or `.png` (display-referred
//! sRGB). Files are written atomically (`atomic::replace`), so an existing output is never left
//! half-written.

mod exposure;
mod exr;
mod exr_header;
pub mod false_colour;
mod png;
pub mod probe;
pub mod sensors;

use std::path::{Path, PathBuf};

use crate::colour::{Cat, ColourSpace, FilmToRgb, Observer, ViewTransform};

use super::SpectralImage;

pub use exposure::{Exposure, Units, metered_stops, protected_stops};
pub use exr::{UNITS_ATTRIBUTE, spectral_channel_name};

#[derive(Clone, Debug, Default)]
pub struct OutputOptions {
    /// Working space of the EXR's RGB (the PNG is always display sRGB).
    pub colour_space: ColourSpace,
    pub observer: Observer,
    pub view: ViewTransform,
    /// Exposure applied before the view transform (PNG only): stops, or metered.
    pub exposure: Exposure,
    /// What the EXR's colour channels hold: radiance-scaled values, or cd/m² (Y).
    pub units: Units,
    /// EXR channels as 16-bit half floats instead of 32-bit floats.
    pub half: bool,
    /// Add the Fichet et al. (JCGT 2021) spectral channels `S0.<centre>nm` to the EXR.
    pub spectral_layers: bool,
    /// Add the per-pixel standard error (`noise.*`) to the EXR, when the image has it.
    pub noise_layer: bool,
    /// Chromatic adaptation from the scene's D65 white to a working space with another white.
    pub cat: Cat,
    /// Extra text attributes of the EXR header (name, value), e.g. the automatic settings'
    /// choice (`brumeAutoSettings`).
    pub attributes: Vec<(String, String)>,
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
    check_sizes(img).map_err(werr)?;
    super::atomic::replace(path, |tmp| {
        match format {
            Format::Exr => exr::write(tmp, img, opts),
            Format::Png => png::write(tmp, img, opts),
        }
        .map_err(std::io::Error::other)
    })
    .map_err(|e| werr(e.to_string()))
}

/// `opts` with its exposure fixed to the stops it gives `img` (a metered exposure measured on
/// `img`), so that other images written with the result share `img`'s exposure and compare.
pub fn with_exposure_of(
    opts: &OutputOptions,
    img: &SpectralImage,
) -> Result<OutputOptions, OutputError> {
    let conv =
        FilmToRgb::new(ColourSpace::Srgb, opts.observer, &img.grid, opts.cat).map_err(|e| {
            OutputError::Write {
                path: PathBuf::new(),
                message: e.to_string(),
            }
        })?;
    let mut out = opts.clone();
    out.exposure = Exposure::Stops(opts.exposure.stops(img, &conv, opts.view.white()));
    Ok(out)
}

/// Converts every pixel of `data` (the image's layout) to RGB in `space`.
pub fn to_rgb(
    img: &SpectralImage,
    data: &[f32],
    space: ColourSpace,
    opts: &OutputOptions,
) -> Result<Vec<[f32; 3]>, String> {
    let conv =
        FilmToRgb::new(space, opts.observer, &img.grid, opts.cat).map_err(|e| e.to_string())?;
    Ok(data
        .chunks_exact(img.grid.n)
        .map(|px| conv.rgb(px))
        .collect())
}

fn check_sizes(img: &SpectralImage) -> Result<(), String> {
    let want = img.width * img.height * img.grid.n;
    let bad = |what: &str, len: usize| {
        Err(format!(
            "{what} holds {len} values, expected {want} ({} x {} pixels x {} bins)",
            img.width, img.height, img.grid.n
        ))
    };
    if img.width == 0 || img.height == 0 {
        return Err("empty image".into());
    }
    if img.data.len() != want {
        return bad("image data", img.data.len());
    }
    if let Some(n) = img.noise.as_ref().filter(|n| n.len() != want) {
        return bad("noise layer", n.len());
    }
    for (name, l) in &img.layers {
        if l.len() != want {
            return bad(&format!("layer {name:?}"), l.len());
        }
    }
    Ok(())
}
