//! The camera (backward) pass: one path per pixel sample, traced through specular events and
//! media, leaving integration spheres on diffuse surfaces and the estimator's integration
//! volumes in media.

use std::sync::atomic::{AtomicBool, Ordering};

use glam::Vec3;
use rand::Rng as _;
use rayon::prelude::*;

use super::Integrator;
use super::direct::{Part, Segment};
use super::estimator::{CameraSegment, Estimator, VolumeEstimator};
use super::gather;
use super::oct::Oct;
use super::path::{self, MediumStep, PathStep, SurfaceStep};
use super::record::{CLASS_ALL, CLASS_C, CameraOutput, SegmentRecord, SurfaceRecord, VolumeRecord};
use super::rng::{self, Domain, Rng};
use super::settings::GatherMode;
use crate::film::{Layer, PassBuffer};
use crate::geometry::{Hit, Ray};
use crate::material::LobeKind;
use crate::medium::{Mixture, WalkEnd, sample_extinction, sample_scatter};
use crate::spectrum::Spectrum;
use crate::world::Scene;

/// Rows traced together before the memory budget is checked: fixed, so that where a pass is
/// split into tiles never depends on the thread count.
pub const ROW_BATCH: u32 = 8;

/// Which camera paths a camera pass traces.
#[derive(Clone, Copy, Debug)]
pub struct CameraJob {
    pub seed: u64,
    pub pass: u64,
    /// The pass's gather radius (surface spheres near an edge are renormalised with it).
    pub radius: f32,
    pub first_row: u32,
    /// Peak gather memory after which the pass is split into a tile.
    pub budget_bytes: usize,
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
        let mut nee = NeeSums::default();
        for _ in 0..integrator.camera_samples {
            let px = x as f32 + rng.random::<f32>();
            let py = y as f32 + rng.random::<f32>();
            let ray = scene.camera.generate_ray(px, py);
            let mut cam = CameraPath::new(scene, integrator, pixel, &mut out, &mut nee);
            cam.radius = job.radius;
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

/// Adds the camera pass's directly seen radiance and next-event estimates into the pass buffer.
pub fn splat_direct(out: &CameraOutput, buf: &mut PassBuffer, scale: f32) {
    let n = buf.n;
    for (pixel, v) in &out.direct {
        buf.splat_scaled(Layer::Surface, *pixel as usize, v.as_slice(n), scale);
    }
    for (pixel, v) in &out.nee_medium {
        buf.splat_scaled(Layer::Medium, *pixel as usize, v.as_slice(n), scale);
    }
    for (pixel, v) in &out.nee_surface {
        buf.splat_scaled(Layer::Surface, *pixel as usize, v.as_slice(n), scale);
    }
}

/// A pixel's next-event estimates, summed over its camera paths (one record per pixel, not
/// per path).
#[derive(Default)]
struct NeeSums {
    medium: Option<Spectrum>,
    surface: Option<Spectrum>,
}

impl NeeSums {
    fn push_into(self, out: &mut CameraOutput, pixel: u32) {
        if let Some(v) = self.medium {
            out.nee_medium.push((pixel, v));
        }
        if let Some(v) = self.surface {
            out.nee_surface.push((pixel, v));
        }
    }
}

fn add(sum: &mut Option<Spectrum>, v: Spectrum) {
    *sum.get_or_insert(Spectrum::ZERO) += v;
}

/// One camera path: its state, and what it records into the pass's output.
struct CameraPath<'a> {
    scene: &'a Scene,
    integrator: &'a Integrator,
    out: &'a mut CameraOutput,
    nee: &'a mut NeeSums,
    pixel: u32,
    n: usize,
    /// Spectral throughput from the camera.
    w: Spectrum,
    /// Whether medium segments still leave integration volumes.
    gathering: bool,
    /// Whether the path still sees emitters directly (false once they are gathered by volumes).
    sees_emitters: bool,
    /// The pass's gather radius.
    radius: f32,
    /// Where and with what density the path last left a glossy (non-delta) surface by a BSDF
    /// sample, for the MIS weight of emitters it then hits; None after the camera, a delta
    /// bounce or a medium scattering.
    glossy_from: Option<(Vec3, f32)>,
}

impl<'a> CameraPath<'a> {
    fn new(
        scene: &'a Scene,
        integrator: &'a Integrator,
        pixel: u32,
        out: &'a mut CameraOutput,
        nee: &'a mut NeeSums,
    ) -> Self {
        let n = scene.grid.n;
        Self {
            scene,
            integrator,
            out,
            nee,
            pixel,
            n,
            w: Spectrum::splat(1.0, n),
            gathering: true,
            sees_emitters: true,
            radius: 0.0,
            glossy_from: None,
        }
    }

    fn first_extinction(&self) -> bool {
        self.integrator.settings.mode == GatherMode::FirstExtinction
    }

    /// The mixture of a camera segment in medium `m` with the path's throughput.
    fn mixture(&self, m: u32) -> Mixture {
        let med = &self.scene.media[m as usize];
        self.integrator.settings.channels().mixture(&self.w, med)
    }

    /// Leaves the estimator's volumes on the segment along `ray` in medium `m`. The segment is
    /// recorded with its first volume, so that one that leaves none (transmitted before the
    /// first sub-step of a sphere walk) costs nothing.
    fn leave_volumes<E: VolumeEstimator>(
        &mut self,
        e: &E,
        m: u32,
        ray: &Ray,
        len: f32,
        mix: &Mixture,
        rng: &mut Rng,
    ) -> WalkEnd {
        let classes = if self.first_extinction() {
            CLASS_ALL
        } else {
            CLASS_C
        };
        let cam = CameraSegment {
            medium: &self.scene.media[m as usize],
            medium_id: m,
            dir: ray.d,
            radius: self.radius,
            mix,
            len,
            first_extinction: self.first_extinction(),
        };
        let (out, pixel, w, n) = (&mut *self.out, self.pixel, &self.w, self.n);
        let mut segment = None;
        e.camera_segment(&cam, rng, |s, scale| {
            let segment = *segment.get_or_insert_with(|| {
                let throughput = out.throughputs.insert(w.as_slice(n));
                out.segments.push(SegmentRecord {
                    origin: ray.o,
                    pixel,
                    dir: ray.d,
                    throughput,
                    medium: m as u16,
                    classes,
                });
                out.segments.len() as u32 - 1
            });
            out.volumes.push(VolumeRecord { segment, s, scale });
        })
    }

    /// Applies the end of a medium segment to the path (method note 4).
    fn after_walk(&mut self, end: WalkEnd) -> MediumStep {
        match end {
            WalkEnd::Transmitted { weight } => {
                self.w *= weight;
                MediumStep::Reached
            }
            WalkEnd::Absorbed { .. } => MediumStep::Ended,
            WalkEnd::Scattered { s, weight } => {
                if self.first_extinction() {
                    MediumStep::Ended
                } else {
                    self.w *= weight;
                    MediumStep::Scattered(s)
                }
            }
        }
    }
}

impl PathStep for CameraPath<'_> {
    /// One straight camera segment of length `len` inside medium `m` (method notes 2-5).
    fn medium(&mut self, m: u32, ray: &Ray, len: f32, rng: &mut Rng) -> MediumStep {
        let mix = self.mixture(m);
        if !self.gathering {
            // Free flight without gathering: the continuation of a see-through path (note 4).
            let end = sample_extinction(&self.scene.media[m as usize], &mix, len, rng);
            return self.after_walk(end);
        }
        if !self.first_extinction() {
            // See-through: volumes gather class C on this first medium segment only.
            self.gathering = false;
        }
        let integrator = self.integrator;
        if let Some(direct) = &integrator.direct {
            // Direct light over the whole segment, whatever the walk does on it (note 9).
            let seg = Segment {
                medium: m,
                ray,
                len,
                mix: &mix,
            };
            let mut acc = Spectrum::ZERO;
            direct.medium_segment(self.scene, &seg, rng, &mut acc);
            add(&mut self.nee.medium, acc * self.w);
        }
        let end = match &integrator.estimator {
            Estimator::Spheres(e) => self.leave_volumes(e, m, ray, len, &mix, rng),
            Estimator::Cylinder(e) => self.leave_volumes(e, m, ray, len, &mix, rng),
            Estimator::TruncatedCylinder(e) => self.leave_volumes(e, m, ray, len, &mix, rng),
            Estimator::LongCylinder(e) => self.leave_volumes(e, m, ray, len, &mix, rng),
        };
        self.after_walk(end)
    }

    fn scatter(&mut self, m: u32, ray: &Ray, t: f32, depth: u32, rng: &mut Rng) -> Option<Ray> {
        // Light reaching the path after a medium scattering is class C light that the volumes
        // already gathered (method note 6).
        self.sees_emitters = false;
        self.glossy_from = None;
        let p = ray.o + ray.d * t;
        let med = &self.scene.media[m as usize];
        let ch = self.integrator.settings.channels();
        let (d, factors) = sample_scatter(med, ray.d, &self.w, ch.pick, ch.floor, rng);
        if let Some(f) = factors {
            self.w *= f;
        }
        self.roulette(depth, rng).then_some(Ray { o: p, d })
    }

    fn vacuum(&mut self, _ray: &Ray, _hit: Option<&Hit>) {}

    /// Emission, gathering on the diffuse part, continuation through the non-diffuse part.
    fn surface(&mut self, hit: &Hit, ray: &Ray, rng: &mut Rng) -> SurfaceStep {
        let scene = self.scene;
        let wo = -ray.d;
        let shape = scene.geometry.shape(hit.shape);
        if let Some(l) = shape.light
            && self.sees_emitters
        {
            let le = scene.lights.lights()[l as usize].radiance(hit, wo);
            if !le.is_zero() {
                let v = match (&self.integrator.direct, self.glossy_from) {
                    (Some(d), Some((from, pdf))) => {
                        le * self.w * d.emission_weight(scene, l, ray, hit, from, pdf)
                    }
                    (Some(_), None) | (None, _) => le * self.w,
                };
                self.out.direct.push((self.pixel, v));
            }
        }
        let Some(mat_id) = shape.material else {
            return SurfaceStep::Null;
        };
        let material = &scene.materials[mat_id as usize];
        let pd = material.diffuse_probability(wo, hit);
        if pd > 0.0 && rng.random::<f32>() < pd {
            self.gather_here(hit, wo, pd);
            if let Some(direct) = &self.integrator.direct {
                let v = direct.reflected(scene, hit, wo, material, Part::Diffuse, rng);
                add(&mut self.nee.surface, v * self.w * (1.0 / pd));
            }
            return SurfaceStep::Stop;
        }
        if let Some(direct) = &self.integrator.direct
            && material.has_glossy()
        {
            let v = direct.reflected(scene, hit, wo, material, Part::Glossy, rng);
            add(&mut self.nee.surface, v * self.w * (1.0 / (1.0 - pd)));
        }
        let u = Vec3::new(rng.random(), rng.random(), rng.random());
        let Some(s) = material.sample_nondiffuse(wo, hit, u) else {
            return SurfaceStep::Stop;
        };
        self.glossy_from = match s.kind {
            LobeKind::Glossy => Some((hit.p, material.pdf_nondiffuse(wo, s.wi, hit))),
            LobeKind::Specular | LobeKind::Diffuse => None,
        };
        self.w *= s.weight * (1.0 / (1.0 - pd));
        if self.w.is_zero() {
            return SurfaceStep::Stop;
        }
        SurfaceStep::Scattered(s.wi)
    }

    /// Camera throughput starts at 1 and only falls through events: after the first three
    /// bounces (which carry most of the image, so they are never cut) the path survives with
    /// probability `max_l W_l` (at most 1) and is reweighted by its inverse.
    fn roulette(&mut self, depth: u32, rng: &mut Rng) -> bool {
        if depth < 3 {
            return true;
        }
        let p = self.w.max_value().min(1.0);
        if p <= 0.0 || rng.random::<f32>() >= p {
            return false;
        }
        self.w *= 1.0 / p;
        true
    }
}

impl CameraPath<'_> {
    /// Leaves a surface sphere on the diffuse part chosen with probability `pd`. Near an edge
    /// of its surface the sphere's weight is divided by the fraction of its disc on the surface
    /// (`Geometry::disc_fraction`), so that it estimates the mean over the part that can be hit.
    fn gather_here(&mut self, hit: &Hit, wo: Vec3, pd: f32) {
        let n = if hit.ns.dot(wo) >= 0.0 {
            hit.ns
        } else {
            -hit.ns
        };
        let throughput = self.out.throughputs.insert(self.w.as_slice(self.n));
        self.out.surfaces.push(SurfaceRecord {
            p: hit.p,
            pixel: self.pixel,
            n: Oct::encode(n),
            wo: Oct::encode(wo),
            shape: hit.shape,
            uv: hit.uv,
            throughput,
            scale: 1.0
                / (pd
                    * self
                        .scene
                        .geometry
                        .disc_fraction(hit.shape, hit.p, self.radius)),
        });
    }
}
