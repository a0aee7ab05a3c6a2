//! Turning the scene's spectrum references into per-bin values, in the way each parameter needs
//! (reflectances bounded, emission illuminant-shaped, coefficients unbounded).

use std::collections::BTreeMap;

use super::error::SceneError;
use super::source::Source;
use super::spectrum_desc::{LinesDesc, RgbKind, SpectrumDesc, SpectrumRef};
use crate::spectrum::{self, Extrapolation, SpectralGrid, Spectrum};

pub struct SpectrumResolver<'a> {
    source: Source<'a>,
    grid: SpectralGrid,
    named: &'a BTreeMap<String, SpectrumDesc>,
}

impl<'a> SpectrumResolver<'a> {
    /// `named`: the scene's `[spectra]`.
    pub fn new(
        source: Source<'a>,
        grid: SpectralGrid,
        named: &'a BTreeMap<String, SpectrumDesc>,
    ) -> Self {
        Self {
            source,
            grid,
            named,
        }
    }

    /// Whether the scene's [spectra] defines `name` (which then wins over built-in names).
    pub fn defines(&self, name: &str) -> bool {
        self.named.contains_key(name)
    }

    fn error(&self, key: &str, message: String) -> SceneError {
        self.source.invalid(key, message)
    }

    /// A reference whose RGB form means `kind`.
    pub fn resolve(
        &self,
        r: &SpectrumRef,
        kind: RgbKind,
        key: &str,
    ) -> Result<Spectrum, SceneError> {
        match r {
            SpectrumRef::Constant(v) => Ok(spectrum::constant(*v as f32, &self.grid)),
            SpectrumRef::Rgb(rgb) => self.rgb([rgb[0] as f32, rgb[1] as f32, rgb[2] as f32], kind),
            SpectrumRef::Named(name) => match self.named.get(name) {
                Some(desc) => self.named_spectrum(name, desc, kind),
                None => self.file_or_builtin(name, None, key),
            },
            SpectrumRef::Lines(l) => match kind {
                RgbKind::Emission => self.lines(l, key),
                RgbKind::Reflectance | RgbKind::Unbounded => Err(self.error(
                    key,
                    "spectral lines are an emission, not a reflectance or a coefficient".into(),
                )),
            },
        }
    }

    /// Each line's power as the density (per nm) over its narrow bin.
    fn lines(&self, l: &LinesDesc, key: &str) -> Result<Spectrum, SceneError> {
        let lines: Vec<(f64, f64)> = l.entries().iter().map(|e| (e.lambda, e.power)).collect();
        spectrum::lines(&lines, &self.grid).map_err(|lambda| {
            let message = format!(
                "the spectral grid has no bin for the line at {lambda} nm (the grid was made \
                 without it)"
            );
            self.error(key, message)
        })
    }

    fn file_or_builtin(
        &self,
        spec: &str,
        column: Option<&str>,
        key: &str,
    ) -> Result<Spectrum, SceneError> {
        // Relative files resolve from the scene's folder; built-in names are tried first.
        let resolved = if spectrum::builtin_table(spec.split(':').next().unwrap_or(spec)).is_some()
        {
            spec.to_string()
        } else {
            self.source.resolve(spec).to_string_lossy().into_owned()
        };
        let data = spectrum::resolve(&resolved, column, false)
            .map_err(|e| self.error(key, e.to_string()))?;
        Ok(data.bin_averages(&self.grid, Extrapolation::Clamp))
    }

    fn named_spectrum(
        &self,
        name: &str,
        d: &SpectrumDesc,
        kind: RgbKind,
    ) -> Result<Spectrum, SceneError> {
        let key = format!("spectra.{name}");
        let base = if let Some(f) = &d.file {
            self.file_or_builtin(f, d.column.as_deref(), &format!("{key}.file"))?
        } else if let Some(b) = &d.builtin {
            self.file_or_builtin(b, d.column.as_deref(), &format!("{key}.builtin"))?
        } else if let Some(v) = d.value {
            spectrum::constant(v as f32, &self.grid)
        } else if let Some(rgb) = d.rgb {
            // The spectrum's own rgb_kind wins over the use site's.
            let _ = kind;
            self.rgb([rgb[0] as f32, rgb[1] as f32, rgb[2] as f32], d.rgb_kind)?
        } else if let Some(p) = &d.power_law {
            spectrum::power_law(p.k, p.lambda_ref, p.p, &self.grid)
        } else {
            return Err(self.error(&key, "no source given".into()));
        };
        Ok(base * d.scale.unwrap_or(1.0) as f32)
    }

    fn rgb(&self, rgb: [f32; 3], kind: RgbKind) -> Result<Spectrum, SceneError> {
        let kind = match kind {
            RgbKind::Reflectance => crate::colour::RgbKind::Reflectance,
            RgbKind::Emission => crate::colour::RgbKind::Illuminant,
            RgbKind::Unbounded => crate::colour::RgbKind::Unbounded,
        };
        crate::colour::rgb_to_spectrum(rgb, kind, &self.grid)
            .map_err(|e| self.error("", e.to_string()))
    }

    pub fn reflectance(&self, r: &SpectrumRef, key: &str) -> Result<Spectrum, SceneError> {
        self.resolve(r, RgbKind::Reflectance, key)
    }

    pub fn emission(&self, r: &SpectrumRef, key: &str) -> Result<Spectrum, SceneError> {
        self.resolve(r, RgbKind::Emission, key)
    }

    pub fn unbounded(&self, r: &SpectrumRef, key: &str) -> Result<Spectrum, SceneError> {
        self.resolve(r, RgbKind::Unbounded, key)
    }

    /// Texel conversion for textures (sRGB-encoded values already decoded to linear).
    pub fn rgb_reflectance(&self, rgb: [f32; 3]) -> Spectrum {
        self.rgb(rgb, RgbKind::Reflectance)
            .unwrap_or(Spectrum::ZERO)
    }
}
