//! Illuminance sensors (`[[sensors]] type = "illuminance"`): the irradiance
//! `E = ∫ L(x, ω) cos θ dω` over the hemisphere a sensor faces, estimated each pass by the
//! machinery camera paths use, split as camera paths split the light (method notes 6 and 9):
//!
//! * **Sensor paths**: `integrator.sensor_paths` paths per sensor and pass leave the sensor in
//!   cosine-distributed directions (density cos θ / π) and are traced exactly as camera paths
//!   (volumes in media, spheres on diffuse surfaces, next-event estimation, emitters seen); each
//!   estimates the radiance L arriving along its direction, and `E ≈ π mean(L)`. Their records
//!   form a gather structure of their own, which the light pass's forward rays also meet; what
//!   they bring goes to the sensor's slot instead of a pixel, so the image is unchanged.
//! * **Direct light** (unscattered) of lights next-event estimation handles: light samples at
//!   the sensor (`Direct::irradiance`), area lights weighted against the sensor paths that hit
//!   them by the power heuristic.
//! * **Direct light of point-like lights the forward rays keep** (`direct = "photons"`, lasers,
//!   narrow spots): no sampled direction can meet them, so the sensor gathers their forward
//!   rays on their first flight through a disc of the pass's radius R centred on it, facing
//!   its normal: each ray crossing it from the front adds its flux / (π R²). Area lights the
//!   forward rays keep are seen by the sensor paths instead, as a camera sees them.

use std::f32::consts::PI;
use std::sync::atomic::{AtomicBool, Ordering};

use glam::{Vec2, Vec3};
use rand::Rng as _;
use rayon::prelude::*;

use super::by_light::ByLight;
use super::camera_path::{CameraPath, NeeSums};
use super::gather::Gather;
use super::path;
use super::record::{CameraOutput, DirectRecord};
use super::rng::{self, Domain};
use super::{Integrator, Radii};
use crate::film::{PassBuffer, SensorKind};
use crate::geometry::sampling::{Frame, cosine_hemisphere};
use crate::geometry::spawn;
use crate::light::Light;
use crate::world::Scene;

/// Sensor paths per work item (fixed, so that the random streams never depend on threads).
const BATCH: u32 = 64;

/// An illuminance sensor as the integrator uses it.
#[derive(Clone, Copy, Debug)]
pub struct SensorPoint {
    /// Index in the film's sensor list (the slot its splats go to).
    pub index: u32,
    pub position: Vec3,
    pub frame: Frame,
    /// The medium on the sensor's side.
    pub medium: Option<u32>,
}

/// The scene's illuminance sensors (a sensor with a zero normal measures nothing: skipped).
pub fn sensor_points(scene: &Scene) -> Vec<SensorPoint> {
    let sensors = &scene.film_extras.sensors;
    let mut points = Vec::new();
    for (i, s) in sensors.iter().enumerate() {
        match s.kind {
            SensorKind::Illuminance { position, normal } => {
                let (position, normal) = (Vec3::from(position), Vec3::from(normal));
                let Some(n) = normal.try_normalize() else {
                    continue;
                };
                let medium = scene.medium_at(spawn(position, n, n).o);
                points.push(SensorPoint {
                    index: i as u32,
                    position,
                    frame: Frame::new(n),
                    medium,
                });
            }
            SensorKind::Luminance { .. } => {}
        }
    }
    points
}

/// Which sensor paths a pass traces.
pub struct SensorJob<'a> {
    pub seed: u64,
    pub pass: u64,
    pub radii: Radii,
    pub points: &'a [SensorPoint],
}

/// Traces the pass's sensor paths: the records (their `pixel` is the sensor's film index) and
/// the direct estimates, in the radiance units of a camera path (see [`SensorPass::splat`]
/// for their scale). None when `stop` was set.
fn sensor_pass(
    scene: &Scene,
    integrator: &Integrator,
    job: &SensorJob,
    stop: &AtomicBool,
) -> Option<CameraOutput> {
    let paths = integrator.settings.sensor_paths;
    let batches = paths.div_ceil(BATCH);
    let items: Vec<(usize, u32)> = (0..job.points.len())
        .flat_map(|k| (0..batches).map(move |b| (k, b)))
        .collect();
    let outs: Vec<CameraOutput> = items
        .into_par_iter()
        .map(|(k, b)| {
            let count = BATCH.min(paths - b * BATCH);
            trace_batch(scene, integrator, job, k, b, count)
        })
        .collect();
    if stop.load(Ordering::Relaxed) {
        return None;
    }
    let mut all = CameraOutput::new(scene.grid.n);
    for o in outs {
        all.append(o);
    }
    Some(all)
}

/// `count` paths of batch `b` of sensor `k`.
fn trace_batch(
    scene: &Scene,
    integrator: &Integrator,
    job: &SensorJob,
    k: usize,
    b: u32,
    count: u32,
) -> CameraOutput {
    let s = &job.points[k];
    let mut out = CameraOutput::new(scene.grid.n);
    let index = ((k as u64) << 32) | b as u64;
    let mut rng = rng::stream(job.seed, job.pass, Domain::Sensor, index);
    let mut nee = NeeSums::new(false);
    for _ in 0..count {
        out.paths += 1;
        let local = cosine_hemisphere(Vec2::new(rng.random(), rng.random()));
        let pdf = local.z / PI;
        if let Some(direct) = &integrator.direct {
            let mut e = ByLight::new(false);
            direct.irradiance(scene, s.position, s.frame.n, s.medium, &mut rng, &mut e);
            // In the units of the paths' radiance: the pass multiplies them all by pi / paths.
            out.direct.push(DirectRecord {
                pixel: s.index,
                light: None,
                value: e.sum() * (1.0 / PI),
                extra: false,
            });
        }
        if pdf <= 0.0 {
            continue;
        }
        let d = s.frame.to_world(local);
        let ray = spawn(s.position, s.frame.n, d);
        let mut cam = CameraPath::new(scene, integrator, s.index, &mut out, &mut nee);
        cam.radii = job.radii;
        cam.primary = false;
        cam.glossy_from = Some((s.position, pdf));
        let max_depth = integrator.settings.max_depth;
        path::trace(scene, max_depth, ray, s.medium, &mut cam, &mut rng);
    }
    nee.push_into(&mut out, s.index, false);
    out
}

/// One pass's sensor paths, ready for the light pass.
pub struct SensorPass {
    /// What the paths found without the light pass (their records are in `gather`).
    pub out: CameraOutput,
    pub gather: SensorGather,
}

impl SensorPass {
    /// Traces the sensor paths of `job` and builds their gather structure; None when `stop`
    /// was set.
    pub fn new(
        scene: &Scene,
        integrator: &Integrator,
        job: &SensorJob,
        stop: &AtomicBool,
    ) -> Option<Self> {
        let mut out = sensor_pass(scene, integrator, job, stop)?;
        let gather = Gather::from_output(&integrator.estimator, job.radii, &mut out);
        let paths = integrator.settings.sensor_paths as f32;
        let (spp, rays) = (
            integrator.camera_samples as f32,
            integrator.forward_rays as f32,
        );
        // The discs take a light's first flight: its direct light.
        let r = job.radii.direct;
        let disc_scale = 1.0 / (rays * PI * r * r);
        Some(Self {
            out,
            gather: SensorGather {
                gather,
                points: job.points.to_vec(),
                path_scale: spp * PI / paths,
                disc_scale,
            },
        })
    }

    /// Adds the sensor paths' emitters seen and next-event estimates to their sensors' slots,
    /// times π / sensor paths (E = π mean L).
    pub fn splat(&self, buf: &mut PassBuffer, integrator: &Integrator) {
        let n = buf.n;
        let scale = PI / integrator.settings.sensor_paths as f32;
        for records in [
            &self.out.direct,
            &self.out.nee_medium,
            &self.out.nee_surface,
        ] {
            for r in records {
                buf.splat_sensor(r.pixel as usize, r.value.as_slice(n), scale);
            }
        }
    }
}

/// What the light pass needs for the sensors: the gather structure over the sensor paths'
/// records, the sensors' discs and the scales of what they gather.
pub struct SensorGather {
    pub gather: Gather,
    pub points: Vec<SensorPoint>,
    /// Multiplies the light pass's pixel scale (1 / (forward rays x camera samples)) for the
    /// sensor paths' records: camera samples x π / sensor paths.
    pub path_scale: f32,
    /// The scale of a forward ray's flux crossing a disc: 1 / (forward rays π R²).
    pub disc_scale: f32,
}

impl SensorGather {
    /// Whether the first flight of light `light`'s forward rays reaches the sensors through
    /// their discs: lights whose direct light no sampled direction can meet (point-like, parallel
    /// and beams) and which next-event estimation does not handle.
    pub fn disc_gathers(&self, scene: &Scene, integrator: &Integrator, light: u32) -> bool {
        if integrator.direct.as_ref().is_some_and(|d| d.handles(light)) {
            return false;
        }
        match scene.lights.lights()[light as usize] {
            Light::Area { .. } => false,
            Light::Directional { .. }
            | Light::Point { .. }
            | Light::Spot { .. }
            | Light::Laser { .. } => true,
        }
    }

    /// Calls `hit(sensor, t)` for each sensor disc the forward segment `o + d t`, `t` in
    /// `[0, len]`, crosses from the front. A segment ending on the disc's plane (a sensor lying
    /// on a surface the ray hits) counts: its end is allowed a spawn offset's slack.
    pub fn crossings(&self, o: Vec3, d: Vec3, len: f32, mut hit: impl FnMut(u32, f32)) {
        let r2 = self.gather.radii.direct * self.gather.radii.direct;
        for s in &self.points {
            let n = s.frame.n;
            let cos = d.dot(n);
            if cos >= 0.0 {
                continue;
            }
            let t = (s.position - o).dot(n) / cos;
            let slack = 1e-4 * (1.0 + s.position.abs().max_element());
            if !(t >= 0.0 && t <= len + slack) {
                continue;
            }
            if (o + d * t).distance_squared(s.position) <= r2 {
                hit(s.index, t);
            }
        }
    }
}
