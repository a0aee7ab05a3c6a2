//! A human-readable summary of a loaded scene (`brume info`).

use std::fmt;

use super::loaded::LoadedScene;

pub struct Summary {
    pub file: String,
    pub width: u32,
    pub height: u32,
    pub bins: usize,
    pub lambda: (f64, f64),
    pub shapes: usize,
    pub lights: usize,
    pub materials: usize,
    pub media: usize,
    pub spectra: usize,
    pub volume: String,
    pub mode: String,
    pub q: f32,
    pub radius: f32,
    pub forward_rays: u64,
    pub memory: crate::integrator::MemoryEstimate,
}

pub fn summarise(scene: &LoadedScene) -> Summary {
    let d = &scene.desc;
    Summary {
        file: scene.file.display().to_string(),
        width: d.camera.width,
        height: d.camera.height,
        bins: d.film.bins,
        lambda: (d.film.lambda_min, d.film.lambda_max),
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
            d.camera.width as u64 * d.camera.height as u64,
            d.film.bins,
            !d.media.is_empty(),
        ),
    }
}

/// How a value is written in a scene file (serde's name for it), for unit enum variants.
fn spelling<T: serde::Serialize + fmt::Debug>(v: &T) -> String {
    match serde_json::to_value(v) {
        Ok(serde_json::Value::String(s)) => s,
        // Not a unit variant: no single word to show; Debug is the honest fallback.
        _ => format!("{v:?}"),
    }
}

impl fmt::Display for Summary {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let mib = |b: f64| b / (1024.0 * 1024.0);
        writeln!(f, "scene:        {}", self.file)?;
        writeln!(f, "image:        {} x {} pixels", self.width, self.height)?;
        writeln!(
            f,
            "spectrum:     {} bins over {}-{} nm",
            self.bins, self.lambda.0, self.lambda.1
        )?;
        writeln!(
            f,
            "contents:     {} shapes, {} lights, {} materials, {} media, {} named spectra",
            self.shapes, self.lights, self.materials, self.media, self.spectra
        )?;
        writeln!(
            f,
            "integrator:   volume {}, mode {}, q = {}, radius = {} m, {} forward rays per pass",
            self.volume, self.mode, self.q, self.radius, self.forward_rays
        )?;
        let m = &self.memory;
        writeln!(
            f,
            "gather:       ~{:.0} integration volumes per pass (upper estimate), {:.1} MiB",
            m.gather_volumes,
            mib(m.gather_bytes)
        )?;
        writeln!(f, "film:         {:.1} MiB", mib(m.film_bytes))?;
        writeln!(f, "memory:       ~{:.1} MiB in total", mib(m.total()))
    }
}
