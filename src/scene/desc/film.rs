use serde::{Deserialize, Serialize};

use crate::colour::{Cat, ColourSpace, Observer, ViewTransform};
use crate::film::output::{Exposure, Units};

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
    /// Exposure of display outputs: stops, or "auto" (metered). Unset: the units' default
    /// ([`Exposure::default_for`]: 0 stops radiometric, "auto" photometric). Not written when
    /// unset, so that a film file's description reads back as unset.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub exposure: Option<Exposure>,
    /// What EXR colour channels hold: "radiometric" or "photometric" (Y in cd/m²).
    #[serde(skip_serializing_if = "is_radiometric")]
    pub units: Units,
    /// One EXR layer per light (`light0.spot`, ...), their sum the image.
    #[serde(skip_serializing_if = "is_false")]
    pub light_layers: bool,
    /// Also write a false-colour luminance map `NAME-luminance.png` beside each image output.
    #[serde(skip_serializing_if = "is_false")]
    pub false_colour: bool,
    /// The false-colour map's range in cd/m² (default: from the image's percentiles).
    #[serde(
        skip_serializing_if = "Option::is_none",
        deserialize_with = "crate::scene::array::exact_opt"
    )]
    pub false_colour_range: Option<[f32; 2]>,
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
            exposure: None,
            units: Units::default(),
            light_layers: false,
            false_colour: false,
            false_colour_range: None,
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
            exposure: self.exposure.unwrap_or(Exposure::default_for(self.units)),
            units: self.units,
            half: self.half,
            spectral_layers: self.spectral_layers,
            noise_layer: self.noise_layer,
            cat: self.adaptation,
            attributes: Vec::new(),
        }
    }
}

fn is_radiometric(u: &Units) -> bool {
    *u == Units::Radiometric
}

fn is_false(b: &bool) -> bool {
    !*b
}
