//! What building a light, shape or material needs, without the scene description itself (which
//! holds those kinds): where keys are, the spectral grid and spectra, and the ids of named
//! materials and media.

use super::source::Source;
use super::spectra::SpectrumResolver;
use super::spectrum_desc::SpectrumDesc;
use crate::spectrum::SpectralGrid;

pub struct Builder<'a> {
    pub source: Source<'a>,
    pub grid: SpectralGrid,
    pub spectra: SpectrumResolver<'a>,
    /// Material and medium names in id order (name order).
    materials: Vec<&'a str>,
    media: Vec<&'a str>,
    /// The medium filling space outside every shape.
    outside: Option<&'a str>,
    /// `integrator.radius`: integration volumes reach this far beyond the geometry.
    pub radius: f32,
}

/// The scene-wide inputs of a [`Builder`].
pub struct Inputs<'a> {
    pub grid: SpectralGrid,
    pub spectra: &'a std::collections::BTreeMap<String, SpectrumDesc>,
    pub materials: Vec<&'a str>,
    pub media: Vec<&'a str>,
    pub outside: Option<&'a str>,
    pub radius: f32,
}

impl<'a> Builder<'a> {
    pub fn new(source: Source<'a>, inputs: Inputs<'a>) -> Self {
        Builder {
            source,
            spectra: SpectrumResolver::new(source, inputs.grid.clone(), inputs.spectra),
            grid: inputs.grid,
            materials: inputs.materials,
            media: inputs.media,
            outside: inputs.outside,
            radius: inputs.radius,
        }
    }

    /// Id of the material named `name`.
    pub fn material_id(&self, name: &str) -> Option<u32> {
        self.materials
            .iter()
            .position(|k| *k == name)
            .map(|i| i as u32)
    }

    /// Id of the medium named `name`.
    pub fn medium_id(&self, name: &str) -> Option<u32> {
        self.media.iter().position(|k| *k == name).map(|i| i as u32)
    }

    /// The medium outside every shape.
    pub fn outside_medium(&self) -> Option<u32> {
        self.outside.and_then(|m| self.medium_id(m))
    }
}
