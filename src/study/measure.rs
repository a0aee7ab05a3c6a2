//! One checkpoint's errors: the study's image brought to the reference's values (spectral bins,
//! or RGB in the working space through the film's own colour conversion), then compared value
//! by value.

use std::borrow::Cow;

use super::StudyError;
use super::clock::Elapsed;
use super::metrics::{LayerErrors, ScaleFit, fit_scale, layer_errors, mean_error};
use super::reference::{Reference, Values, layer};
use crate::colour::FilmToRgb;
use crate::film::SpectralImage;
use crate::film::output::OutputOptions;
use crate::spectrum::SpectralGrid;

/// Errors after one pass of one run.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize)]
pub struct Checkpoint {
    pub passes: u64,
    /// Wall-clock seconds spent rendering passes so far.
    pub seconds: f64,
    /// Process CPU seconds spent rendering passes so far (NaN where there is no CPU clock).
    pub cpu_seconds: f64,
    pub total: LayerErrors,
    /// None when the reference has no medium / surface split.
    pub medium: Option<LayerErrors>,
    pub surface: Option<LayerErrors>,
    /// The reference scaled by the least-squares k (`--fit-scale`).
    pub fit: Option<ScaleFit>,
    /// Mean per-value standard error estimated from the run's own passes.
    pub noise: f64,
    /// Mean signed error (image minus reference) over all values: a bias that persists
    /// across runs shows here, where the MSE cannot tell it from noise.
    pub mean_error: f64,
}

/// Brings a variant's images to the reference's values.
pub(crate) struct Projection {
    /// None: spectral, compared as is.
    rgb: Option<FilmToRgb>,
}

impl Projection {
    /// For images on `grid` rendered with the film options `opts`.
    pub fn new(
        values: &Values,
        grid: &SpectralGrid,
        opts: &OutputOptions,
    ) -> Result<Self, StudyError> {
        match values {
            Values::Spectral(g) if g == grid => Ok(Self { rgb: None }),
            Values::Spectral(g) => Err(StudyError::Mismatch {
                got: format!("{} bins over {}-{} nm", g.n, g.lambda_min, g.lambda_max),
                want: format!(
                    "{} bins over {}-{} nm",
                    grid.n, grid.lambda_min, grid.lambda_max
                ),
            }),
            Values::Rgb(space) => FilmToRgb::new(*space, opts.observer, grid, opts.cat)
                .map(|c| Self { rgb: Some(c) })
                .map_err(|e| StudyError::NoVariant(e.to_string())),
        }
    }

    fn values<'a>(&self, data: &'a [f32], n: usize) -> Cow<'a, [f32]> {
        match &self.rgb {
            None => Cow::Borrowed(data),
            Some(c) => Cow::Owned(data.chunks_exact(n).flat_map(|p| c.rgb(p)).collect()),
        }
    }

    fn noise(&self, noise: &[f32], n: usize) -> f64 {
        let mean = |v: &[f32]| v.iter().map(|&x| x as f64).sum::<f64>() / v.len().max(1) as f64;
        match &self.rgb {
            None => mean(noise),
            Some(c) => {
                let rgb: Vec<f32> = noise
                    .chunks_exact(n)
                    .flat_map(|p| c.rgb_std_error(p))
                    .collect();
                mean(&rgb)
            }
        }
    }
}

/// The errors of `img` (after `passes` passes and `elapsed` time) against `reference`.
pub(crate) fn measure(
    img: &SpectralImage,
    passes: u64,
    elapsed: Elapsed,
    reference: &Reference,
    projection: &Projection,
    fit: bool,
) -> Result<Checkpoint, StudyError> {
    let n = img.grid.n;
    if img.width != reference.width || img.height != reference.height {
        return Err(StudyError::Mismatch {
            got: reference.shape(),
            want: format!("{} x {}", img.width, img.height),
        });
    }
    let total = projection.values(&img.data, n);
    let layer_err = |name: &str, want: &[f32]| {
        layer(img, name).map(|l| layer_errors(&projection.values(l, n), want))
    };
    let (medium, surface) = match &reference.layers {
        Some(l) => (
            layer_err("medium", &l.medium),
            layer_err("surface", &l.surface),
        ),
        None => (None, None),
    };
    Ok(Checkpoint {
        passes,
        seconds: elapsed.wall,
        cpu_seconds: elapsed.cpu,
        total: layer_errors(&total, &reference.total),
        medium,
        surface,
        fit: fit.then(|| fit_scale(&total, &reference.total)).flatten(),
        noise: img.noise.as_ref().map_or(0.0, |v| projection.noise(v, n)),
        mean_error: mean_error(&total, &reference.total),
    })
}
