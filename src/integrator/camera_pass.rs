//! The camera (backward) pass: one path per pixel sample, traced through specular events and
//! media, leaving integration spheres on diffuse surfaces and the estimator's integration
//! volumes in media.

use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};

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

/// Rows traced together (in parallel) while a tile has room: fixed, so that the work never
/// depends on the thread count. Tiles end between any two rows.
pub const ROW_BATCH: u32 = 8;

/// Which camera paths a camera pass traces.
#[derive(Clone, Copy, Debug)]
pub struct CameraJob {
    pub seed: u64,
    pub pass: u64,
    /// The pass's gather radii (surface spheres near an edge are renormalised with them).
    pub radii: Radii,
    pub first_row: u32,
    /// Peak gather memory (`gather::peak_bytes_for`) a tile may reach.
    pub budget_bytes: usize,
    /// Whether next-event estimates are kept per light (the film has light layers).
    pub light_layers: bool,
    /// Camera paths are traced in the pixels of every `stride`-th row and column only (1:
    /// every pixel; automatic settings' pilots sample a lattice, `auto::PILOT_STRIDE`).
    pub stride: u32,
    /// In a nested pass (`nest`), the camera paths per pixel of its subset: a pixel's later
    /// paths are extra ones, and say so in their records.
    pub nest_paths: Option<u32>,
}

/// Why a camera pass gave no tile.
#[derive(Clone, Debug, PartialEq)]
pub enum Halt {
    /// `stop` was set.
    Stopped,
    /// One row of camera paths alone needs more gather memory than the budget.
    OverBudget(OverBudget),
}

/// A row of camera paths whose gather records alone exceed the gather budget: the pass cannot
/// be rendered within it (the estimate before rendering refuses most such settings; this is
/// the bound when the paths leave more than the estimate).
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error(
    "row {row} of pass {pass} alone left more than {} of gather records, over the gather budget \
     of {} per pass (integrator.max_gather_bytes); raise integrator.q, lower \
     integrator.camera_samples or camera.width, or raise integrator.max_gather_bytes",
    super::memory::format_bytes(*.bytes as f64),
    super::memory::format_bytes(*.budget as f64)
)]
pub struct OverBudget {
    pub pass: u64,
    pub row: u32,
    /// What the row had left when it was stopped (a lower bound of its need).
    pub bytes: usize,
    pub budget: usize,
}

/// The gather bytes a batch's rows hold so far (the tile's own included), shared by the rows
/// traced in parallel so that they stop once together they exceed the budget: memory stays
/// bounded even when one camera path leaves millions of volumes.
struct Held<'a> {
    bytes: &'a AtomicUsize,
    budget: usize,
}

/// Runs the camera pass of `job.pass` from row `job.first_row` on: the longest run of whole rows
/// whose gather records, summed row by row, stay within `job.budget_bytes` at their peak
/// (`gather::peak_bytes_for`). Which rows make a tile depends only on each row's own records,
/// never on the thread count: rows are traced in parallel batches but their outputs are
/// appended in row order, and a row that stopped because the batch together ran out of room is
/// traced again alone, where it stops only if it cannot fit. Rows are independent work items
/// merged in row order (so are their throughput tables: indices do not depend on the thread
/// count). Returns the output and the first row not traced. `stop` is checked before every
/// pixel (one row can hold 32768 pixels of 4096 samples each, minutes of work).
pub fn camera_pass(
    scene: &Scene,
    integrator: &Integrator,
    job: &CameraJob,
    stop: &AtomicBool,
) -> Result<(CameraOutput, u32), Halt> {
    let h = scene.camera.resolution().1;
    let mut all = CameraOutput::new(scene.grid.n);
    // Sum of the appended rows' peak bytes: an upper bound of `peak_bytes_for(&all)` (merging
    // throughput tables only removes duplicates).
    let mut held = 0usize;
    let mut row = job.first_row;
    let mut batch = ROW_BATCH;
    while row < h {
        if stop.load(Ordering::Relaxed) {
            return Err(Halt::Stopped);
        }
        let end = (row + batch).min(h);
        let counter = AtomicUsize::new(held);
        let room = Held {
            bytes: &counter,
            budget: job.budget_bytes,
        };
        let rows: Vec<Option<CameraOutput>> = (row..end)
            .into_par_iter()
            .map(|y| trace_row(scene, integrator, job, y, &room, stop))
            .collect();
        // A row cut short by `stop` is incomplete: the pass is abandoned.
        if stop.load(Ordering::Relaxed) {
            return Err(Halt::Stopped);
        }
        let alone = batch == 1;
        batch = ROW_BATCH;
        for r in rows {
            let fits = r
                .as_ref()
                .map(gather::peak_bytes_for)
                .filter(|b| held + b <= job.budget_bytes);
            match (r, fits) {
                (Some(r), Some(b)) => {
                    held += b;
                    all.append(r);
                    row += 1;
                }
                // Stopped for lack of room while other rows were in flight: alone it may fit.
                (None, _) if !alone => {
                    batch = 1;
                    break;
                }
                // Does not fit after the rows before it: the tile ends here.
                _ if row > job.first_row => return Ok((all, row)),
                (r, _) => {
                    let bytes = r.map_or(counter.load(Ordering::Relaxed), |r| {
                        gather::peak_bytes_for(&r)
                    });
                    return Err(Halt::OverBudget(OverBudget {
                        pass: job.pass,
                        row,
                        bytes,
                        budget: job.budget_bytes,
                    }));
                }
            }
        }
    }
    Ok((all, row))
}

/// Traces the camera paths of row `y` of pass `pass`. None when `stop` was set or the gather
/// bytes `room` counts (this row's included, checked after every camera path) exceed its
/// budget.
fn trace_row(
    scene: &Scene,
    integrator: &Integrator,
    job: &CameraJob,
    y: u32,
    room: &Held,
    stop: &AtomicBool,
) -> Option<CameraOutput> {
    let w = scene.camera.resolution().0;
    let mut out = CameraOutput::new(scene.grid.n);
    let stride = job.stride.max(1);
    if !y.is_multiple_of(stride) {
        return Some(out);
    }
    let mut rng = rng::stream(job.seed, job.pass, Domain::Camera, y as u64);
    let max_depth = integrator.settings.max_depth;
    let mut counted = 0;
    for x in (0..w).step_by(stride as usize) {
        if stop.load(Ordering::Relaxed) {
            return None;
        }
        let pixel = y * w + x;
        let mut nee = NeeSums::new(job.light_layers);
        // A nested pass's extra paths sum their next-event estimates apart (`nest`).
        let mut extra_nee = NeeSums::new(job.light_layers);
        // With the Sobol sampler the pixel's camera paths of this pass are the points of its
        // own sequence (rng module comment): their pixel positions and first numbers are
        // stratified among themselves, scrambled apart from other pixels' and passes'.
        let sequence = integrator
            .settings
            .sampler
            .stratifies()
            .then(|| rng::sequence(job.seed, job.pass, Domain::Camera, pixel as u64));
        for s in 0..integrator.camera_samples {
            if let Some(key) = sequence {
                rng.begin_sample(key, s as u64);
            }
            let px = x as f32 + rng.random::<f32>();
            let py = y as f32 + rng.random::<f32>();
            let ray = scene.camera.generate_ray(px, py);
            let extra = job.nest_paths.is_some_and(|k| s >= k);
            let sums = if extra { &mut extra_nee } else { &mut nee };
            let mut cam = CameraPath::new(scene, integrator, pixel, &mut out, sums);
            cam.radii = job.radii;
            cam.extra = extra;
            path::trace(
                scene,
                max_depth,
                ray,
                scene.camera_medium,
                &mut cam,
                &mut rng,
            );
            out.paths += 1;
            out.extra_paths += u64::from(extra);
            let now = gather::peak_bytes_for(&out);
            let total = room.bytes.fetch_add(now - counted, Ordering::Relaxed) + now - counted;
            counted = now;
            if total > room.budget {
                return None;
            }
        }
        nee.push_into(&mut out, pixel, false);
        extra_nee.push_into(&mut out, pixel, true);
    }
    Some(out)
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
