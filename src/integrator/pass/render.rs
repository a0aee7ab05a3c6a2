//! Rendering one pass: tiles of camera paths (as many rows as the gather budget holds), each
//! tile's gather structure and light pass, the camera paths' own light, and the estimates a
//! pilot pass nests (`nest`).

use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::time::Instant;

use super::Renderer;
use crate::film::PassBuffer;
use crate::integrator::auto::Work;
use crate::integrator::camera_pass::{CameraJob, Halt, camera_pass, splat_direct};
use crate::integrator::gather::Gather;
use crate::integrator::light_pass::{LightJob, light_pass};
use crate::integrator::nest::{self, Nest, NestCounts};
use crate::integrator::record::CameraOutput;
use crate::integrator::{Estimator, Radii};

impl Renderer<'_> {
    /// Renders the pass that draws pass `pass`'s random numbers, with camera paths on the
    /// lattice of every `stride`-th pixel, at the radius of film pass `film_pass`, and forms the
    /// estimates of `nest` in it; None when `stop` was set.
    pub(super) fn render_sampled(
        &mut self,
        (stride, pass): (u32, u64),
        film_pass: u64,
        nest: Option<&Nest>,
        stop: &AtomicBool,
    ) -> Option<(PassBuffer, Work, NestCounts)> {
        self.radii = self.integrator.radii(film_pass);
        let variants = nest.map_or(0, |n| n.variants.len());
        let mut buf = self
            .film
            .pass_buffer()
            .with_variants(variants)
            .with_blend(self.radii.blend);
        let mut counts = NestCounts::default();
        let mut work = Work::default();
        let sensors = self.sensor_pass(pass, stop)?;
        let h = self.scene.camera.resolution().1;
        let mut row = 0;
        let mut tile = 0u64;
        while row < h {
            let t0 = Instant::now();
            let job = CameraJob {
                seed: self.seed,
                pass,
                radii: self.radii,
                first_row: row,
                budget_bytes: self.integrator.settings.gather_budget(),
                light_layers: buf.lights > 0,
                stride,
                nest_paths: nest.map(|n| n.paths),
            };
            let (mut out, next) = self.camera_tile(&job, stop)?;
            let t1 = Instant::now();
            work.volumes += out.volumes.len() as u64;
            if nest.is_some() {
                counts.add_camera(&out);
            }
            let (scene, integrator) = (self.scene, &self.integrator);
            let hook = &mut self.on_large_build;
            let gather = build_gather(hook, &integrator.estimator, self.radii, &mut out, stop)?;
            self.stats.peak_gather_bytes = self.stats.peak_gather_bytes.max(gather.bytes());
            let t2 = Instant::now();
            let spp = integrator.camera_samples as f32;
            let light = LightJob {
                seed: self.seed,
                pass,
                tile,
                norm: 1.0 / (integrator.forward_rays as f32 * spp),
                hits: AtomicU64::new(0),
                segments: AtomicU64::new(0),
                // The sensor paths' records join the first tile's light pass only.
                sensors: sensors.as_ref().filter(|_| tile == 0).map(|s| &s.gather),
                nest,
                nested_hits: Default::default(),
            };
            if !light_pass(scene, integrator, &gather, &light, &mut buf, stop) {
                return None;
            }
            splat_direct(&out, &mut buf, 1.0 / spp);
            let rays = integrator.forward_rays;
            if let Some(nest) = nest {
                nest::add_direct(&mut buf, nest, &out, 1.0 / spp);
                counts.add_light(rays, &light.hits, &light.nested_hits);
            }
            let t3 = Instant::now();
            work.paths += out.paths;
            work.rays += rays;
            work.hits += light.hits.load(Ordering::Relaxed);
            self.stats
                .add_tile(out.paths, rays, &light, [t0, t1, t2, t3]);
            row = next;
            tile += 1;
        }
        if let Some(s) = &sensors {
            s.splat(&mut buf, &self.integrator);
        }
        buf.fold_blend();
        Some((buf, work, counts))
    }

    /// The camera pass of one tile (`camera_pass`), its records counted in the stats; None
    /// when `stop` was set or one row exceeds the gather budget (`over_budget` says so).
    fn camera_tile(&mut self, job: &CameraJob, stop: &AtomicBool) -> Option<(CameraOutput, u32)> {
        let (out, next) = match camera_pass(self.scene, &self.integrator, job, stop) {
            Ok(tile) => tile,
            Err(Halt::Stopped) => return None,
            Err(Halt::OverBudget(e)) => {
                self.over_budget = Some(e);
                return None;
            }
        };
        let peak = crate::integrator::gather::peak_bytes_for(&out);
        self.stats.peak_build_bytes = self.stats.peak_build_bytes.max(peak);
        self.stats.surface_records += out.surfaces.len() as u64;
        self.stats.volume_records += out.volumes.len() as u64;
        Some((out, next))
    }
}

/// The gather structure of a tile's camera paths (None once `stop` is set), said first to
/// the `on_large_build` hook when it is built apart.
fn build_gather(
    hook: &mut Option<Box<dyn FnMut(usize) + '_>>,
    estimator: &Estimator,
    radii: Radii,
    out: &mut CameraOutput,
    stop: &AtomicBool,
) -> Option<Gather> {
    if let (Some(f), true) = (hook, Gather::builds_apart(out)) {
        f(out.surfaces.len() + out.volumes.len());
    }
    Gather::from_output_until(estimator, radii, out, stop)
}
