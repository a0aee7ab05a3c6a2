//! The reference image a study measures against, from any of three files:
//!
//! - `reference.bin`, brume's own exact format (`bin.rs`), written by a study that rendered its
//!   reference;
//! - a film file (`.brume`, from `brume render --checkpoint` or `-o NAME.brume`): spectral, with
//!   both layers and the per-pixel standard error;
//! - an OpenEXR file (`openexr.rs`): brume's own (spectral channels when it has them, else
//!   RGB, with its `medium.` / `surface.` layers) or another renderer's RGB image, converted to
//!   the study's working space.

use std::path::Path;

use super::StudyError;
use crate::colour::{Cat, ColourSpace};
use crate::film::SpectralImage;
use crate::spectrum::SpectralGrid;

mod bin;
mod openexr;

pub use bin::REFERENCE_MAGIC;

/// What a reference's values are; the study's images are brought to the same before comparing.
#[derive(Clone, Debug, PartialEq)]
pub enum Values {
    /// Spectral radiance per bin of this grid (brume's own references).
    Spectral(SpectralGrid),
    /// Scene-linear RGB in this working space (an RGB EXR, converted to the film's space).
    Rgb(ColourSpace),
}

impl Values {
    /// Values per pixel.
    pub fn channels(&self) -> usize {
        match self {
            Values::Spectral(g) => g.n,
            Values::Rgb(_) => 3,
        }
    }

    pub fn describe(&self) -> String {
        match self {
            Values::Spectral(g) => format!(
                "spectral radiance, {} bins over {}-{} nm",
                g.n, g.lambda_min, g.lambda_max
            ),
            Values::Rgb(s) => format!("RGB in {} (the film's working space)", space_name(*s)),
        }
    }
}

/// The scene-file name of a working space.
pub fn space_name(s: ColourSpace) -> &'static str {
    match s {
        ColourSpace::Srgb => "srgb",
        ColourSpace::Acescg => "acescg",
        ColourSpace::Xyz => "xyz",
    }
}

/// The film's two component layers, in the reference's values.
#[derive(Clone, Debug, PartialEq)]
pub struct Layers {
    pub medium: Vec<f32>,
    pub surface: Vec<f32>,
}

#[derive(Clone, Debug, PartialEq)]
pub struct Reference {
    pub width: usize,
    pub height: usize,
    pub values: Values,
    pub passes: u64,
    pub seconds: f64,
    /// Per pixel, `values.channels()` values, row-major from the top.
    pub total: Vec<f32>,
    /// The medium / surface split, when the reference has it (brume's references do).
    pub layers: Option<Layers>,
    /// Per-pixel standard error of the reference itself, when known.
    pub noise: Option<Vec<f32>>,
    /// How the file was read (colour space, conversion), for the study's summary.
    pub notes: Vec<String>,
}

/// How to read a reference file.
#[derive(Clone, Debug)]
pub struct ReferenceOptions {
    /// The colour space an RGB EXR is in, when stated (`--reference-space`): overrides the
    /// file's `chromaticities`.
    pub space: Option<ColourSpace>,
    /// The study's working space (the film's `colour_space`): RGB references are converted to it.
    pub working: ColourSpace,
    /// Chromatic adaptation for that conversion (the film's `cat`).
    pub cat: Cat,
    /// The study's spectral grid: an EXR with spectral channels on it is compared spectrally.
    pub grid: SpectralGrid,
}

/// Reference files, by extension.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Format {
    Bin,
    Film,
    Exr,
}

fn format_of(path: &Path) -> Option<Format> {
    let ext = path.extension()?.to_str()?.to_ascii_lowercase();
    match ext.as_str() {
        "bin" => Some(Format::Bin),
        "brume" => Some(Format::Film),
        "exr" => Some(Format::Exr),
        _ => None,
    }
}

/// A named layer of the image.
pub(crate) fn layer<'a>(img: &'a SpectralImage, name: &str) -> Option<&'a [f32]> {
    img.layers
        .iter()
        .find(|(n, _)| n == name)
        .map(|(_, l)| l.as_slice())
}

impl Reference {
    /// A spectral reference from a rendered image (its layers and noise when it has them).
    pub fn from_image(img: &SpectralImage, passes: u64, seconds: f64) -> Self {
        let layers = match (layer(img, "medium"), layer(img, "surface")) {
            (Some(m), Some(s)) => Some(Layers {
                medium: m.to_vec(),
                surface: s.to_vec(),
            }),
            _ => None,
        };
        Self {
            width: img.width,
            height: img.height,
            values: Values::Spectral(img.grid.clone()),
            passes,
            seconds,
            total: img.data.clone(),
            layers,
            noise: img.noise.clone(),
            notes: Vec::new(),
        }
    }

    /// Reads a reference file of any supported kind (by extension).
    pub fn open(path: &Path, opts: &ReferenceOptions) -> Result<Self, StudyError> {
        let unsupported = || StudyError::Reference {
            path: path.to_path_buf(),
            message: "unknown kind of file (use reference.bin, a .brume film file or an .exr)"
                .into(),
        };
        match format_of(path).ok_or_else(unsupported)? {
            Format::Bin => Self::load(path),
            Format::Film => Self::from_film_file(path),
            Format::Exr => openexr::read(path, opts),
        }
    }

    /// A film file's mean image, layers and standard error.
    pub fn from_film_file(path: &Path) -> Result<Self, StudyError> {
        let file = crate::film::checkpoint::read(path).map_err(|e| StudyError::Reference {
            path: path.to_path_buf(),
            message: e.to_string(),
        })?;
        let mut r = Self::from_image(&file.film.image(), file.film.passes, 0.0);
        r.notes
            .push("film file: its rendering time is not recorded (reported as 0 s)".into());
        Ok(r)
    }

    /// "W x H x N bins" (or "x RGB") for messages.
    pub fn shape(&self) -> String {
        match &self.values {
            Values::Spectral(g) => format!("{} x {} x {} bins", self.width, self.height, g.n),
            Values::Rgb(s) => format!("{} x {} RGB ({})", self.width, self.height, space_name(*s)),
        }
    }

    /// Mean squared standard error of the reference: the floor its own noise adds to every
    /// measured MSE. None when the reference carries no standard error.
    pub fn noise_mse(&self) -> Option<f64> {
        let n = self.noise.as_ref().filter(|n| !n.is_empty())?;
        Some(n.iter().map(|&v| (v as f64).powi(2)).sum::<f64>() / n.len() as f64)
    }

    /// The reference as a spectral image (for its PNG); None for an RGB reference.
    pub fn to_image(&self) -> Option<SpectralImage> {
        let Values::Spectral(grid) = &self.values else {
            return None;
        };
        let mut img = SpectralImage::new(self.width, self.height, grid.clone());
        img.data = self.total.clone();
        Some(img)
    }
}
