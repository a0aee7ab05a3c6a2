use serde::{Deserialize, Serialize};

use crate::colour::{Cat, ColourSpace, Observer, ViewTransform};

#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct FilmDesc {
    /// Number of equal spectral bins over the range; each spectral line an emission uses adds
    /// a narrow bin of its own (see `LoadedScene::grid`).
    pub bins: usize,
    /// Spectral range in nanometres.
    pub lambda_min: f64,
    pub lambda_max: f64,
    pub observer: Observer,
    pub colour_space: ColourSpace,
    /// Chromatic adaptation to a working space whose white is not D65 (ACEScg).
    pub adaptation: Cat,
    pub view: ViewTransform,
    /// Exposure in stops for display outputs.
    pub exposure: f32,
    /// Half-float EXR channels (false: 32-bit float).
    pub half: bool,
    /// Write per-bin spectral layers into EXR outputs.
    pub spectral_layers: bool,
    /// Write the per-pixel standard-error layer into EXR outputs.
    pub noise_layer: bool,
    /// Outputs written when the command line gives no `-o` (relative to the working directory).
    pub outputs: Vec<String>,
}

impl Default for FilmDesc {
    fn default() -> Self {
        Self {
            bins: 32,
            lambda_min: 380.0,
            lambda_max: 780.0,
            observer: Observer::default(),
            colour_space: ColourSpace::default(),
            adaptation: Cat::default(),
            view: ViewTransform::default(),
            exposure: 0.0,
            half: false,
            spectral_layers: false,
            noise_layer: false,
            outputs: Vec::new(),
        }
    }
}

impl FilmDesc {
    pub fn output_options(&self) -> crate::film::output::OutputOptions {
        crate::film::output::OutputOptions {
            colour_space: self.colour_space,
            observer: self.observer,
            view: self.view,
            exposure: self.exposure,
            half: self.half,
            spectral_layers: self.spectral_layers,
            noise_layer: self.noise_layer,
            cat: self.adaptation,
        }
    }
}
