//! The camera (backward) pass: one path per pixel sample, traced through specular events and
//! media, leaving integration spheres on diffuse surfaces and the estimator's integration
//! volumes in media.

use std::sync::atomic::{AtomicBool, Ordering};

use rand::Rng as _;
use rayon::prelude::*;

use super::camera_path::{CameraPath, NeeSums};
use super::gather;
use super::path;
use super::record::CameraOutput;
use super::rng::{self, Domain};
use super::{Integrator, Radii};
use crate::film::{Layer, PassBuffer};
use crate::world::Scene;

/// Rows traced together before the memory budget is checked: fixed, so that where a pass is
/// split into tiles never depends on the thread count.
pub const ROW_BATCH: u32 = 8;

/// Which camera paths a camera pass traces.
#[derive(Clone, Copy, Debug)]
pub struct CameraJob {
    pub seed: u64,
    pub pass: u64,
    /// The pass's gather radii (surface spheres near an edge are renormalised with them).
    pub radii: Radii,
    pub first_row: u32,
    /// Peak gather memory after which the pass is split into a tile.
    pub budget_bytes: usize,
    /// Whether next-event estimates are kept per light (the film has light layers).
    pub light_layers: bool,
}

/// Runs the camera pass of `job.pass` from row `job.first_row` on, until building the gather
/// structure would need more than `job.budget_bytes` at its peak (at least one batch of rows).
/// Rows are independent work items merged in row order (so are their throughput tables: indices
/// do not depend on the thread count). Returns the output and the first row not traced, or None
/// when `stop` was set (checked before every pixel: one row can hold 32768 pixels of 4096
/// samples each, minutes of work).
pub fn camera_pass(
    scene: &Scene,
    integrator: &Integrator,
    job: &CameraJob,
    stop: &AtomicBool,
) -> Option<(CameraOutput, u32)> {
    let h = scene.camera.resolution().1;
    let mut all = CameraOutput::new(scene.grid.n);
    let mut row = job.first_row;
    while row < h {
        if stop.load(Ordering::Relaxed) {
            return None;
        }
        let end = (row + ROW_BATCH).min(h);
        let rows: Vec<CameraOutput> = (row..end)
            .into_par_iter()
            .map(|y| trace_row(scene, integrator, job, y, stop))
            .collect();
        // A row cut short by `stop` is incomplete: the pass is abandoned.
        if stop.load(Ordering::Relaxed) {
            return None;
        }
        for r in rows {
            all.append(r);
        }
        row = end;
        if gather::peak_bytes_for(&all) > job.budget_bytes {
            break;
        }
    }
    Some((all, row))
}

/// Traces the camera paths of row `y` of pass `pass`; stops early (an incomplete row) once
/// `stop` is set.
fn trace_row(
    scene: &Scene,
    integrator: &Integrator,
    job: &CameraJob,
    y: u32,
    stop: &AtomicBool,
) -> CameraOutput {
    let w = scene.camera.resolution().0;
    let mut out = CameraOutput::new(scene.grid.n);
    let mut rng = rng::stream(job.seed, job.pass, Domain::Camera, y as u64);
    let max_depth = integrator.settings.max_depth;
    for x in 0..w {
        if stop.load(Ordering::Relaxed) {
            break;
        }
        let pixel = y * w + x;
        let mut nee = NeeSums::new(job.light_layers);
        for _ in 0..integrator.camera_samples {
            let px = x as f32 + rng.random::<f32>();
            let py = y as f32 + rng.random::<f32>();
            let ray = scene.camera.generate_ray(px, py);
            let mut cam = CameraPath::new(scene, integrator, pixel, &mut out, &mut nee);
            cam.radii = job.radii;
            path::trace(
                scene,
                max_depth,
                ray,
                scene.camera_medium,
                &mut cam,
                &mut rng,
            );
            out.paths += 1;
        }
        nee.push_into(&mut out, pixel);
    }
    out
}

/// Adds the camera pass's directly seen radiance and next-event estimates into the pass buffer
/// (and into the layers of the lights they came from).
pub fn splat_direct(out: &CameraOutput, buf: &mut PassBuffer, scale: f32) {
    let n = buf.n;
    for (layer, records) in [
        (Layer::Surface, &out.direct),
        (Layer::Medium, &out.nee_medium),
        (Layer::Surface, &out.nee_surface),
    ] {
        for r in records {
            let v = r.value.as_slice(n);
            buf.splat_scaled_from(layer, r.pixel as usize, r.light, v, scale);
        }
    }
}
