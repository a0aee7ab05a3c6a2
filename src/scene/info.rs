//! What `brume info --json` prints and `brume.Scene.info()` returns: the scene's image size,
//! spectral bins, each medium's coefficients per bin with its visibility, the radius the
//! render starts from and the memory estimate. The same values as the text of `brume info`
//! (`summary`), as numbers.

use serde_json::{Value, json};

use super::desc::MediumDesc;
use super::loaded::LoadedScene;
use super::media::build_medium;
use super::spectra::SpectrumResolver;
use super::{SceneError, SceneWarning};
use crate::colour::photometry::meteorological_optical_range;
use crate::medium::droplets::visibility;

/// The scene summarised as JSON, and the warnings building it gave. Building reads every
/// texture, mesh and spectrum file, so their errors are reported here as by `brume info`.
pub fn info_json(scene: &LoadedScene) -> Result<(Value, Vec<SceneWarning>), SceneError> {
    let d = &scene.desc;
    let grid = scene.grid()?;
    let (built, warnings) = super::build_with_warnings(scene)?;
    let integrator = super::build_integrator(scene, &built)?;
    let footprint = crate::integrator::radius::pixel_footprint(&built.camera, &built.geometry);
    let memory = crate::integrator::MemoryEstimate::new(
        &d.integrator,
        (d.camera.width, d.camera.height),
        grid.n,
        !d.media.is_empty(),
    );
    let edges: Vec<f64> = (0..grid.n)
        .map(|i| grid.edges(i).0)
        .chain([grid.edges(grid.n - 1).1])
        .collect();
    let names: Vec<&str> = d.media.keys().map(String::as_str).collect();
    let value = json!({
        "file": scene.file.display().to_string(),
        "width": d.camera.width,
        "height": d.camera.height,
        "bins": grid.n,
        "equal_bins": d.film.bins,
        "lines": grid.lines(),
        "wavelengths": grid.centres(),
        "bin_edges": edges,
        "counts": {
            "shapes": d.shapes.len(), "lights": d.lights.len(), "materials": d.materials.len(),
            "media": d.media.len(), "spectra": d.spectra.len(), "sensors": d.sensors.len(),
        },
        "integrator": serde_json::to_value(&d.integrator).unwrap_or(Value::Null),
        "radius": {
            "r0": integrator.radius.r0,
            "indirect": integrator.radii(0).indirect,
            "pixel_footprint": footprint,
        },
        "memory": {
            "gather_volumes": memory.gather_volumes,
            "gather_bytes": memory.gather_bytes,
            "gather_held_bytes": memory.gather_held(),
            "tiles": memory.tiles(),
            "film_bytes": memory.film_bytes,
            "total_bytes": memory.total(),
        },
        "media": media(scene, &grid)?,
        "density": super::density_report::density_report(&built, &names),
        "warnings": warnings.iter().map(|w| w.to_string()).collect::<Vec<_>>(),
    });
    Ok((value, warnings))
}

/// Per medium (its density left out: coefficients at density 1), per bin: extinction,
/// albedo, mean cosine and visibility, and the meteorological optical range.
fn media(scene: &LoadedScene, grid: &crate::spectrum::SpectralGrid) -> Result<Value, SceneError> {
    let source = scene.source();
    let spectra = SpectrumResolver::new(source, grid.clone(), &scene.desc.spectra);
    let mut out = serde_json::Map::new();
    for (name, desc) in &scene.desc.media {
        let plain = MediumDesc {
            density: None,
            ..desc.clone()
        };
        let b = build_medium(source, &spectra, grid, (name, &plain), None)?;
        let m = &b.medium;
        let sigma_t = m.sigma_t.as_slice(grid.n).to_vec();
        let mor = meteorological_optical_range(&sigma_t, grid).ok().flatten();
        out.insert(
            name.clone(),
            json!({
                "phase": m.phase.describe(),
                "sigma_t": sigma_t,
                "sigma_s": m.sigma_s.as_slice(grid.n),
                "albedo": m.albedo().as_slice(grid.n),
                "g": m.phase.g_bins(m.n).as_slice(grid.n),
                "visibility": sigma_t.iter().map(|s| visibility(*s as f64)).collect::<Vec<_>>(),
                "meteorological_optical_range": mor,
                "droplets": b.droplets.as_ref().map(|o| json!({
                    "effective_radius_um": o.effective_radius,
                    "number_density_per_cm3": o.number_density,
                    "liquid_water_content_g_m3": o.liquid_water_content,
                })),
            }),
        );
    }
    Ok(Value::Object(out))
}
