//! A human-readable summary of a loaded scene (`brume info`).

use std::fmt;

use super::desc::MediumDesc;
use super::loaded::LoadedScene;
use super::media::build_medium;
use super::spectra::SpectrumResolver;
use crate::colour::photometry::meteorological_optical_range;
use crate::medium::droplets::visibility;

pub struct Summary {
    pub file: String,
    pub width: u32,
    pub height: u32,
    /// Bins in all: the film's equal bins, split around a narrow bin at each line.
    pub bins: usize,
    pub lambda: (f64, f64),
    /// `film.bins`, and the spectral lines given a bin of their own (nm).
    pub equal_bins: usize,
    pub lines: Vec<f64>,
    pub shapes: usize,
    pub lights: usize,
    pub materials: usize,
    pub media: usize,
    pub spectra: usize,
    pub volume: String,
    pub mode: String,
    pub q: crate::integrator::setting::Setting<f32>,
    pub radius: crate::integrator::setting::Setting<f32>,
    pub forward_rays: crate::integrator::setting::Setting<u64>,
    pub memory: crate::integrator::MemoryEstimate,
    /// Per medium: its phase function and per range of bins its optical properties.
    pub media_report: Vec<String>,
    /// One line per light and per sensor: its key, kind and keys as the scene gives them.
    pub lights_report: Vec<String>,
    pub sensors_report: Vec<String>,
    /// What each glTF shape brought.
    pub imports: Vec<super::import_report::GltfReport>,
}

pub fn summarise(scene: &LoadedScene) -> Summary {
    let d = &scene.desc;
    // A loaded scene has a grid (loading validates it); the equal bins stand in otherwise.
    let (bins, lines) = match scene.grid() {
        Ok(g) => (g.n, g.lines().to_vec()),
        Err(_) => (d.film.bins, Vec::new()),
    };
    Summary {
        file: scene.file.display().to_string(),
        width: d.camera.width,
        height: d.camera.height,
        bins,
        lambda: (d.film.lambda_min, d.film.lambda_max),
        equal_bins: d.film.bins,
        lines,
        shapes: d.shapes.len(),
        lights: d.lights.len(),
        materials: d.materials.len(),
        media: d.media.len(),
        spectra: d.spectra.len(),
        volume: spelling(&d.integrator.volume),
        mode: spelling(&d.integrator.mode),
        q: d.integrator.q,
        radius: d.integrator.radius,
        forward_rays: d.integrator.forward_rays,
        memory: crate::integrator::MemoryEstimate::new(
            &d.integrator,
            (d.camera.width, d.camera.height),
            bins,
            !d.media.is_empty(),
        ),
        media_report: media_report(scene),
        lights_report: d
            .lights
            .iter()
            .enumerate()
            .map(|(i, l)| format!("  lights.{i}: {}", keys_line(l)))
            .collect(),
        sensors_report: d
            .sensors
            .iter()
            .enumerate()
            .map(|(i, s)| format!("  sensors.{i} ({}): {}", s.name(i), keys_line(s)))
            .collect(),
        imports: scene.imports.clone(),
    }
}

/// A `type`-tagged table as one line: its type, then its keys as TOML (`laser, position =
/// [0.0, 1.0, 2.0], power = 1.0, spectrum = { line = 532.0 }`).
fn keys_line<T: serde::Serialize>(table: &T) -> String {
    let Ok(toml::Value::Table(mut t)) = toml::Value::try_from(table) else {
        // Every light and sensor description is a table; nothing else to show.
        return String::new();
    };
    let kind = match t.remove("type") {
        Some(toml::Value::String(k)) => k,
        _ => String::new(),
    };
    let keys = t.iter().map(|(k, v)| format!("{k} = {v}"));
    std::iter::once(kind)
        .chain(keys)
        .collect::<Vec<_>>()
        .join(", ")
}

/// How a value is written in a scene file (serde's name for it), for unit enum variants.
fn spelling<T: serde::Serialize + fmt::Debug>(v: &T) -> String {
    match serde_json::to_value(v) {
        Ok(serde_json::Value::String(s)) => s,
        // Not a unit variant: no single word to show; Debug is the honest fallback.
        _ => format!("{v:?}"),
    }
}

/// At most this many rows per medium: bins are grouped into ranges beyond it.
const MEDIUM_ROWS: usize = 8;

/// Each medium's phase function and, per range of bins, its extinction, albedo, mean cosine
/// and visibility (meteorological optical range); droplet fog adds its Lorenz-Mie inputs.
fn media_report(scene: &LoadedScene) -> Vec<String> {
    let grid = match scene.grid() {
        Ok(g) => g,
        Err(e) => return vec![format!("media: cannot be described: {e}")],
    };
    let source = scene.source();
    let spectra = SpectrumResolver::new(source, grid.clone(), &scene.desc.spectra);
    let mut out = Vec::new();
    for (name, desc) in &scene.desc.media {
        // The coefficients only: the density field (and its transport) is reported from the
        // built scene.
        let plain = MediumDesc {
            density: None,
            tracking: None,
            ..desc.clone()
        };
        let b = match build_medium(source, &spectra, &grid, (name, &plain), None) {
            Ok(b) => b,
            Err(e) => {
                out.push(format!("medium {name}: cannot be built: {e}"));
                continue;
            }
        };
        let m = &b.medium;
        out.push(format!("medium {name}: phase {}", m.phase.describe()));
        if let Some(o) = &b.droplets {
            out.push(format!(
                "  droplets: r_eff {:.3} µm, {:.4} per cm³, liquid water {:.4} g/m³, index {}, \
                 Lorenz-Mie at {} wavelengths ({} radii each)",
                o.effective_radius,
                o.number_density,
                o.liquid_water_content,
                o.refractive_index,
                o.samples.len(),
                o.nodes
            ));
        }
        out.push(mor_line(&m.sigma_t, &grid));
        out.push("  bins (nm)       sigma_t (1/m)  albedo     g        visibility (m)".into());
        let (albedo, g) = (m.albedo(), m.phase.g_bins(m.n));
        let per = m.n.div_ceil(MEDIUM_ROWS);
        for start in (0..m.n).step_by(per) {
            let end = (start + per).min(m.n);
            // Averages over the wavelength range the rows' bins cover (bins differ in width
            // when lines split them).
            let span = grid.edges(end - 1).1 - grid.edges(start).0;
            let avg = |s: &crate::spectrum::Spectrum| {
                (start..end)
                    .map(|i| s.0[i] as f64 * grid.bin_width(i))
                    .sum::<f64>()
                    / span
            };
            let st = avg(&m.sigma_t);
            out.push(format!(
                "  {:>5.1}-{:<7.1}  {:<13.6}  {:<9.6}  {:<7.4}  {:.4}",
                grid.edges(start).0,
                grid.edges(end - 1).1,
                st,
                avg(&albedo),
                avg(&g),
                visibility(st)
            ));
        }
    }
    out
}

/// The medium's meteorological optical range (CIE: where a collimated 2700 K beam keeps 5 % of
/// its luminous flux; see `colour::photometry`).
fn mor_line(sigma_t: &crate::spectrum::Spectrum, grid: &crate::spectrum::SpectralGrid) -> String {
    let head = "  meteorological optical range (CIE, 2700 K, V(λ)):";
    match meteorological_optical_range(sigma_t.as_slice(grid.n), grid) {
        Ok(Some(d)) => format!("{head} {d:.6} m"),
        Ok(None) => format!("{head} unbounded (no extinction where V(λ) > 0)"),
        Err(e) => format!("{head} unknown ({e})"),
    }
}

impl fmt::Display for Summary {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(f, "scene:        {}", self.file)?;
        writeln!(f, "image:        {} x {} pixels", self.width, self.height)?;
        write!(
            f,
            "spectrum:     {} bins over {}-{} nm",
            self.bins, self.lambda.0, self.lambda.1
        )?;
        if self.lines.is_empty() {
            writeln!(f)?;
        } else {
            let nm: Vec<String> = self.lines.iter().map(|l| format!("{l}")).collect();
            writeln!(
                f,
                " ({} equal, split around a {} nm bin at each line: {} nm)",
                self.equal_bins,
                crate::spectrum::LINE_WIDTH,
                nm.join(", ")
            )?;
        }
        writeln!(
            f,
            "contents:     {} shapes, {} lights, {} materials, {} media, {} named spectra",
            self.shapes, self.lights, self.materials, self.media, self.spectra
        )?;
        writeln!(
            f,
            "integrator:   volume {}, mode {}, q = {}, radius = {} (m), forward rays per pass {}",
            self.volume, self.mode, self.q, self.radius, self.forward_rays
        )?;
        let m = &self.memory;
        let bytes = crate::integrator::format_bytes;
        writeln!(
            f,
            "gather:       ~{:.0} integration volumes per pass (upper estimate), {} at its peak \
             in one piece; at most {} per tile (the budget), {} tiles per pass",
            m.gather_volumes,
            bytes(m.gather_bytes),
            bytes(m.gather_held()),
            m.tiles()
        )?;
        writeln!(f, "film:         {}", bytes(m.film_bytes))?;
        if !self.imports.is_empty() {
            writeln!(f, "gltf:         {} files", self.imports.len())?;
            for r in &self.imports {
                write!(f, "{r}")?;
            }
        }
        writeln!(f, "lights:       {}", self.lights_report.len())?;
        for line in &self.lights_report {
            writeln!(f, "{line}")?;
        }
        if !self.sensors_report.is_empty() {
            writeln!(f, "sensors:      {}", self.sensors_report.len())?;
            for line in &self.sensors_report {
                writeln!(f, "{line}")?;
            }
        }
        for line in &self.media_report {
            writeln!(f, "{line}")?;
        }
        writeln!(f, "memory:       ~{} in total", bytes(m.total()))
    }
}
