//! The scene's spectral grid: `film.bins` equal bins over the film's range, plus a narrow bin
//! at every spectral line an emission in the scene uses (a light's `spectrum`, a shape's
//! `emit`). Validation and building both make it here, so a line the grid cannot hold is
//! reported before anything is built, at the key that gives it.

use super::check::Problem;
use super::desc::SceneDesc;
use super::error::SceneError;
use super::loaded::LoadedScene;
use super::spectrum_desc::SpectrumRef;
use crate::spectrum::{GridError, MAX_BINS, SpectralGrid};

/// One line of the scene: its wavelength and the dotted key that gives it.
#[derive(Clone, Debug, PartialEq)]
pub struct SceneLine {
    pub lambda: f64,
    pub key: String,
}

/// Every line of the scene's emission spectra, shapes first then lights, in file order.
pub fn scene_lines(d: &SceneDesc) -> Vec<SceneLine> {
    let shapes = d
        .shapes
        .iter()
        .enumerate()
        .filter_map(|(i, s)| Some((format!("shapes.{i}.emit"), s.common.emit.as_ref()?)));
    let lights =
        d.lights.iter().enumerate().filter_map(|(i, l)| {
            Some((format!("lights.{i}.spectrum"), l.common.spectrum.as_ref()?))
        });
    let mut out = Vec::new();
    for (key, r) in shapes.chain(lights) {
        if let SpectrumRef::Lines(l) = r {
            out.extend(l.entries().into_iter().map(|e| SceneLine {
                lambda: e.lambda,
                key: format!("{key}.{}", e.lambda_key),
            }));
        }
    }
    out
}

/// The scene's grid, or the problem that prevents it, at the key responsible: the film's
/// bins or range, or the first line (in [`scene_lines`] order) that is not a wavelength, lies
/// outside the range, is too close to another, or takes the grid past [`MAX_BINS`].
pub fn scene_grid(d: &SceneDesc) -> Result<SpectralGrid, Problem> {
    let f = &d.film;
    let problem = |key: &str, message: String| Problem {
        key: key.to_string(),
        message,
    };
    if !(1..=MAX_BINS).contains(&f.bins) {
        let message = format!("must be in 1..={MAX_BINS}, got {}", f.bins);
        return Err(problem("film.bins", message));
    }
    if !(f.lambda_min.is_finite() && f.lambda_max.is_finite() && f.lambda_max > f.lambda_min) {
        let message = "must be greater than film.lambda_min".to_string();
        return Err(problem("film.lambda_max", message));
    }
    let lines = scene_lines(d);
    let wavelengths: Vec<f64> = lines.iter().map(|l| l.lambda).collect();
    let grid =
        |k: usize| SpectralGrid::with_lines(f.bins, f.lambda_min, f.lambda_max, &wavelengths[..k]);
    grid(lines.len()).map_err(|whole| {
        // Blame the first line whose addition fails: the grid of the lines before it is fine.
        match (1..=lines.len()).find_map(|k| grid(k).err().map(|e| (k, e))) {
            Some((k, e)) => problem(&lines[k - 1].key, message(&e)),
            None => problem("film.bins", message(&whole)),
        }
    })
}

/// The grid's error in the scene's terms.
fn message(e: &GridError) -> String {
    match e {
        GridError::TooManyBins {
            needed, uniform, ..
        } => format!(
            "with this line the spectral grid would need {needed} bins (film.bins = {uniform}, \
             split around each line), above the {MAX_BINS} brume carries: lower film.bins or \
             use fewer lines"
        ),
        GridError::NotAWavelength { .. }
        | GridError::Outside { .. }
        | GridError::TooClose { .. } => e.to_string(),
    }
}

impl LoadedScene {
    /// The scene's spectral grid (see [`scene_grid`]), its problem placed at its key.
    pub fn grid(&self) -> Result<SpectralGrid, SceneError> {
        scene_grid(&self.desc).map_err(|p| self.source().invalid(&p.key, p.message))
    }
}
