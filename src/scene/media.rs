//! `[media.*]`: the scene side of building a medium. The medium's own keys, checks and runtime
//! construction (coefficients, phase function, droplet fog by Lorenz-Mie) are in
//! `medium::build`; here its spectra are resolved from the scene and its errors are placed at
//! their keys (a tabulated phase's CSV errors at that file's own line).

use std::collections::BTreeMap;

use glam::Vec3;

use super::desc::MediumDesc;
use super::error::{KeyText, Origin, SceneError};
use super::source::Source;
use super::spectra::SpectrumResolver;
use crate::geometry::Geometry;
use crate::medium::{BuiltMedium, Density, Medium, MediumError, MediumParts};
use crate::spectrum::SpectralGrid;

/// Builds medium `name` of `desc`.
/// `interior` is the box of the shapes holding it (where a noise density is sampled).
pub fn build_medium(
    source: Source,
    spectra: &SpectrumResolver,
    grid: &SpectralGrid,
    (name, desc): (&str, &MediumDesc),
    interior: Option<(Vec3, Vec3)>,
) -> Result<BuiltMedium, SceneError> {
    let key = format!("media.{name}");
    let ss = match &desc.sigma_s {
        Some(s) => Some(spectra.unbounded(s, &format!("{key}.sigma_s"))?),
        None => None,
    };
    let sa = spectra.unbounded(&desc.sigma_a, &format!("{key}.sigma_a"))?;
    let parts = MediumParts {
        sigma_s: ss.as_ref(),
        sigma_a: &sa,
        g: desc.g,
        phase: desc.phase.as_ref(),
        droplets: desc.droplets.as_ref(),
        visibility: desc.grey_visibility(),
    };
    let built = crate::medium::build_medium(parts, grid, &|f| source.resolve(f)).map_err(|e| {
        let k = format!("{key}.{}", e.key);
        match e.error {
            MediumError::PhaseFile {
                file,
                line,
                message,
            } => SceneError::Invalid {
                origin: Origin::File {
                    file,
                    line: Some((line, 1)),
                },
                key: KeyText(k),
                message,
            },
            other => source.invalid(&k, other.to_string()),
        }
    })?;
    let density = match &desc.density {
        None => Density::Uniform,
        Some(d) => d
            .build(&|f| source.resolve(f), interior)
            .map_err(|e| source.invalid(&format!("{key}.density.{}", e.key), e.message))?,
    };
    let block = desc
        .majorant_block
        .map_or(crate::medium::tracking::DEFAULT_BLOCK, |b| b as usize);
    let medium = built
        .medium
        .with_density(density)
        .with_tracking(desc.tracking.unwrap_or_default(), block)
        .map_err(|e| source.invalid(&format!("{key}.tracking"), e.to_string()))?;
    Ok(BuiltMedium { medium, ..built })
}

/// Every medium of the scene, in name order (their ids), in `geometry`.
pub fn build_all(
    source: Source,
    spectra: &SpectrumResolver,
    grid: &SpectralGrid,
    media: &BTreeMap<String, MediumDesc>,
    geometry: &Geometry,
) -> Result<Vec<Medium>, SceneError> {
    media
        .iter()
        .enumerate()
        .map(|(id, (name, desc))| {
            let inside = geometry.interior_bounds(id as u32).map(|b| (b.min, b.max));
            Ok(build_medium(source, spectra, grid, (name, desc), inside)?.medium)
        })
        .collect()
}
