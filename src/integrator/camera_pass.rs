//! The camera (backward) pass: one path per pixel sample, traced through specular events and
//! media, leaving integration spheres on diffuse surfaces and integration volumes in media.

use glam::Vec3;
use rand::Rng as _;
use rayon::prelude::*;

use super::record::{CLASS_ALL, CLASS_C, SegmentRecord, SurfaceRecord, VolumeRecord, VolumeShape};
use super::rng::{self, Domain, Rng};
use super::throughput::ThroughputTable;
use super::{gather, oct::Oct};
use crate::film::{Layer, PassBuffer};
use crate::geometry::{Hit, Ray, spawn};
use crate::medium::{ChannelPick, Mixture, WalkEnd, sample_extinction};
use crate::scene::Scene;
use crate::scene::desc::{ChannelPickDesc, GatherMode, VolumeKind};
use crate::spectrum::Spectrum;

/// What one row (or any batch of pixels) of the camera pass produced.
#[derive(Default)]
pub struct CameraOutput {
    pub surfaces: Vec<SurfaceRecord>,
    /// Camera segments in media that left volumes; `volumes` point into it.
    pub segments: Vec<SegmentRecord>,
    pub volumes: Vec<VolumeRecord>,
    /// Distinct camera throughputs, shared by the records.
    pub throughputs: ThroughputTable,
    /// Radiance seen directly (emitters), per pixel of the batch: (pixel, value).
    pub direct: Vec<(u32, Spectrum)>,
    /// Camera paths started.
    pub paths: u64,
}

impl CameraOutput {
    /// An empty output for spectra of `n` bins.
    pub fn new(n: usize) -> Self {
        Self {
            throughputs: ThroughputTable::new(n),
            ..Self::default()
        }
    }

    /// Memory the gather structure built from these records will hold (`Gather::bytes()`,
    /// with the BVHs at their measured bytes per primitive).
    pub fn gather_bytes(&self) -> usize {
        let prims = self.surfaces.len() + self.volumes.len();
        self.surfaces.len() * std::mem::size_of::<SurfaceRecord>()
            + self.segments.len() * std::mem::size_of::<SegmentRecord>()
            + self.volumes.len() * std::mem::size_of::<VolumeRecord>()
            + self.throughputs.data_bytes()
            + prims * gather::BVH_BYTES_PER_PRIM
    }

    /// Peak memory while the gather is built: what it keeps, plus the binary BVH and the
    /// boxes the wide BVHs are converted from (freed before the light pass).
    pub fn peak_bytes(&self) -> usize {
        let prims = self.surfaces.len() + self.volumes.len();
        self.gather_bytes() + prims * gather::BUILD_BYTES_PER_PRIM
    }

    /// Appends `other`, rebasing its segment and throughput indices.
    pub fn append(&mut self, mut other: CameraOutput) {
        let remap = self.throughputs.merge(&other.throughputs);
        let base = self.segments.len() as u32;
        other
            .surfaces
            .iter_mut()
            .for_each(|s| s.throughput = remap[s.throughput as usize]);
        other
            .segments
            .iter_mut()
            .for_each(|s| s.throughput = remap[s.throughput as usize]);
        other.volumes.iter_mut().for_each(|v| v.segment += base);
        self.surfaces.append(&mut other.surfaces);
        self.segments.append(&mut other.segments);
        self.volumes.append(&mut other.volumes);
        self.direct.append(&mut other.direct);
        self.paths += other.paths;
    }
}

/// The camera segment's spectral mixture in medium `m` for throughput `w`, with the scene's
/// channel pick and floor. The light pass rebuilds truncated cylinders' P with it.
pub fn camera_mixture(scene: &Scene, w: &Spectrum, m: u32) -> Mixture {
    let s = &scene.settings;
    let pick = match s.channel_pick {
        ChannelPickDesc::Throughput => ChannelPick::Throughput,
        ChannelPickDesc::Uniform => ChannelPick::Uniform,
    };
    Mixture::new(pick, w, &scene.media[m as usize], s.channel_floor)
}

/// Rows traced together before the memory budget is checked: fixed, so that where a pass is
/// split into tiles never depends on the thread count.
pub const ROW_BATCH: u32 = 8;

/// Runs the camera pass of pass `pass` from row `first_row` on, until building the gather
/// structure would need more than `budget_bytes` at its peak (at least one batch of rows). Rows
/// are independent work items merged in row order (so are their throughput tables: indices do
/// not depend on the thread count). Returns the output and the first row not traced.
pub fn camera_pass(
    scene: &Scene,
    seed: u64,
    pass: u64,
    first_row: u32,
    budget_bytes: usize,
) -> (CameraOutput, u32) {
    let (w, h) = scene.camera.resolution();
    let n = scene.grid.n;
    let mut all = CameraOutput::new(n);
    let mut row = first_row;
    while row < h {
        let end = (row + ROW_BATCH).min(h);
        let rows: Vec<CameraOutput> = (row..end)
            .into_par_iter()
            .map(|y| {
                let mut out = CameraOutput::new(n);
                let mut rng = rng::stream(seed, pass, Domain::Camera, y as u64);
                for x in 0..w {
                    let pixel = y * w + x;
                    for _ in 0..scene.settings.camera_samples {
                        let px = x as f32 + rng.random::<f32>();
                        let py = y as f32 + rng.random::<f32>();
                        let ray = scene.camera.generate_ray(px, py);
                        CameraPath::new(scene, pixel).trace(ray, &mut rng, &mut out);
                        out.paths += 1;
                    }
                }
                out
            })
            .collect();
        for r in rows {
            all.append(r);
        }
        row = end;
        if all.peak_bytes() > budget_bytes {
            break;
        }
    }
    (all, row)
}

/// Adds the camera pass's directly seen radiance into the pass buffer.
pub fn splat_direct(out: &CameraOutput, buf: &mut PassBuffer, scale: f32) {
    for (pixel, v) in &out.direct {
        let n = buf.n;
        buf.splat_scaled(Layer::Surface, *pixel as usize, v.as_slice(n), scale);
    }
}

struct CameraPath<'a> {
    scene: &'a Scene,
    pixel: u32,
    n: usize,
    /// Spectral throughput from the camera.
    w: Spectrum,
    /// Whether medium segments still leave integration volumes.
    gathering: bool,
    /// Whether the path still sees emitters directly (false once they are gathered by volumes).
    sees_emitters: bool,
}

/// Null-boundary crossings allowed per path (far more than any sane scene needs).
pub const MAX_CROSSINGS: u32 = 1024;

/// What a surface hit did to a path.
enum Bounce {
    /// The path ended (gathered, absorbed, or no continuation).
    Stop,
    /// Passed an index-matched boundary.
    Crossed,
    /// Reflected or refracted: a real event.
    Scattered,
}

enum Segment {
    /// The path goes on to the surface at the end of the segment.
    Reached,
    /// The path ended inside the medium.
    Ended,
    /// A real scattering at distance `s`; the path continues from there.
    Scattered(f32),
}

impl<'a> CameraPath<'a> {
    fn new(scene: &'a Scene, pixel: u32) -> Self {
        let n = scene.grid.n;
        Self {
            scene,
            pixel,
            n,
            w: Spectrum::splat(1.0, n),
            gathering: true,
            sees_emitters: true,
        }
    }

    fn trace(mut self, mut ray: Ray, rng: &mut Rng, out: &mut CameraOutput) {
        let scene = self.scene;
        let mut medium = scene.camera_medium;
        // Null (index-matched) boundaries are not scattering events: they do not count towards
        // max_depth, but are bounded on their own against degenerate geometry.
        let (mut depth, mut crossings) = (0, 0);
        while depth < scene.settings.max_depth && crossings < MAX_CROSSINGS {
            let hit = scene.geometry.intersect(&ray, f32::INFINITY);
            if let Some(m) = medium {
                let seg_len = match &hit {
                    Some(h) => h.t,
                    None => scene.world_exit(&ray),
                };
                match self.medium_segment(m, &ray, seg_len, rng, out) {
                    Segment::Reached => {}
                    Segment::Ended => return,
                    Segment::Scattered(s) => {
                        // Light reaching the path after a medium scattering is class C light
                        // that the volumes already gathered (method note 6).
                        self.sees_emitters = false;
                        let p = ray.o + ray.d * s;
                        let d = scene.media[m as usize].phase.sample_dir(
                            ray.d,
                            rng.random(),
                            rng.random(),
                        );
                        ray = Ray { o: p, d };
                        depth += 1;
                        if !self.roulette(depth, rng) {
                            return;
                        }
                        continue;
                    }
                }
            }
            let Some(hit) = hit else { return };
            match self.surface(&hit, &mut ray, &mut medium, rng, out) {
                Bounce::Stop => return,
                Bounce::Crossed => crossings += 1,
                Bounce::Scattered => {
                    depth += 1;
                    if !self.roulette(depth, rng) {
                        return;
                    }
                }
            }
        }
    }

    /// Russian roulette on the throughput after a few bounces.
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

    /// Handles a surface hit: emission, null boundaries, gathering on the diffuse part,
    /// continuation through the non-diffuse part.
    fn surface(
        &mut self,
        hit: &Hit,
        ray: &mut Ray,
        medium: &mut Option<u32>,
        rng: &mut Rng,
        out: &mut CameraOutput,
    ) -> Bounce {
        let scene = self.scene;
        let wo = -ray.d;
        let shape = scene.geometry.shape(hit.shape);
        if let Some(l) = shape.light
            && self.sees_emitters
        {
            let le = scene.lights.lights()[l as usize].radiance(hit, wo);
            if !le.is_zero() {
                out.direct.push((self.pixel, le * self.w));
            }
        }
        let Some(mat_id) = shape.material else {
            // Index-matched boundary: straight on, only the medium changes.
            *medium = scene.geometry.medium_after(hit, ray.d);
            *ray = spawn(hit.p, hit.ng, ray.d);
            return Bounce::Crossed;
        };
        let material = &scene.materials[mat_id as usize];
        let pd = material.diffuse_probability(wo, hit);
        if pd > 0.0 && rng.random::<f32>() < pd {
            let n = if hit.ns.dot(wo) >= 0.0 {
                hit.ns
            } else {
                -hit.ns
            };
            let throughput = out.throughputs.insert(self.w.as_slice(self.n));
            out.surfaces.push(SurfaceRecord {
                p: hit.p,
                pixel: self.pixel,
                n: Oct::encode(n),
                wo: Oct::encode(wo),
                shape: hit.shape,
                uv: hit.uv,
                throughput,
                scale: 1.0 / pd,
            });
            return Bounce::Stop;
        }
        let u = Vec3::new(rng.random(), rng.random(), rng.random());
        let Some(s) = material.sample_nondiffuse(wo, hit, u) else {
            return Bounce::Stop;
        };
        self.w *= s.weight * (1.0 / (1.0 - pd));
        if self.w.is_zero() {
            return Bounce::Stop;
        }
        if s.wi.dot(hit.ng).signum() != wo.dot(hit.ng).signum() {
            *medium = scene.geometry.medium_after(hit, s.wi);
        }
        *ray = spawn(hit.p, hit.ng, s.wi);
        Bounce::Scattered
    }

    fn mixture(&self, m: u32) -> Mixture {
        camera_mixture(self.scene, &self.w, m)
    }

    /// Records the camera segment along `ray` in medium `m` that leaves volumes of `shape`,
    /// with the current throughput.
    fn segment(&self, out: &mut CameraOutput, m: u32, ray: &Ray, shape: VolumeShape) -> u32 {
        let classes = match self.scene.settings.mode {
            GatherMode::FirstExtinction => CLASS_ALL,
            GatherMode::SeeThrough => CLASS_C,
        };
        let throughput = out.throughputs.insert(self.w.as_slice(self.n));
        out.segments.push(SegmentRecord {
            origin: ray.o,
            pixel: self.pixel,
            dir: ray.d,
            throughput,
            medium: m as u16,
            shape,
            classes,
        });
        out.segments.len() as u32 - 1
    }

    /// A cylinder over the first `len` metres of the segment along `ray`.
    fn cylinder(&self, out: &mut CameraOutput, m: u32, ray: &Ray, len: f32, shape: VolumeShape) {
        let segment = self.segment(out, m, ray, shape);
        out.volumes.push(VolumeRecord {
            segment,
            s: len,
            scale: 1.0,
        });
    }

    /// One straight camera segment of length `seg_len` inside medium `m` (method notes 2-5).
    fn medium_segment(
        &mut self,
        m: u32,
        ray: &Ray,
        seg_len: f32,
        rng: &mut Rng,
        out: &mut CameraOutput,
    ) -> Segment {
        let scene = self.scene;
        let med = &scene.media[m as usize];
        let settings = &scene.settings;
        let mix = self.mixture(m);
        let first_extinction = settings.mode == GatherMode::FirstExtinction;
        if !self.gathering {
            return self.free_flight(&mix, m, seg_len, rng);
        }
        if !first_extinction {
            // See-through: volumes gather class C on this first medium segment only.
            self.gathering = false;
        }
        match settings.volume {
            VolumeKind::Spheres => {
                let this = &*self;
                // The segment is recorded with its first sphere, so that one that leaves none
                // (transmitted before its first sub-step) costs nothing.
                let mut segment = None;
                let end = scene.walk.walk_scaled(med, &mix, seg_len, rng, |s, scale| {
                    let segment = *segment
                        .get_or_insert_with(|| this.segment(out, m, ray, VolumeShape::Sphere));
                    out.volumes.push(VolumeRecord { segment, s, scale });
                });
                self.after_walk(end, first_extinction)
            }
            VolumeKind::Cylinder | VolumeKind::CylinderLong => {
                let shape = if settings.volume == VolumeKind::Cylinder {
                    VolumeShape::Cylinder
                } else {
                    VolumeShape::Long
                };
                self.cylinder(out, m, ray, seg_len, shape);
                if first_extinction {
                    self.w *= med.sigma_t.transmittance(seg_len, self.n);
                    Segment::Reached
                } else {
                    self.free_flight(&mix, m, seg_len, rng)
                }
            }
            VolumeKind::CylinderTruncated => {
                let end = sample_extinction(med, &mix, seg_len, rng);
                let len = match end {
                    WalkEnd::Scattered { s, .. } | WalkEnd::Absorbed { s } => s,
                    WalkEnd::Transmitted { .. } => seg_len,
                };
                self.cylinder(out, m, ray, len, VolumeShape::Truncated);
                self.after_walk(end, first_extinction)
            }
        }
    }

    fn after_walk(&mut self, end: WalkEnd, first_extinction: bool) -> Segment {
        match end {
            WalkEnd::Transmitted { weight } => {
                self.w *= weight;
                Segment::Reached
            }
            WalkEnd::Absorbed { .. } => Segment::Ended,
            WalkEnd::Scattered { s, weight } => {
                if first_extinction {
                    Segment::Ended
                } else {
                    self.w *= weight;
                    Segment::Scattered(s)
                }
            }
        }
    }

    /// Free flight without gathering: the continuation of a see-through path (note 4).
    fn free_flight(&mut self, mix: &Mixture, m: u32, seg_len: f32, rng: &mut Rng) -> Segment {
        let med = &self.scene.media[m as usize];
        let end = sample_extinction(med, mix, seg_len, rng);
        self.after_walk(end, false)
    }
}
