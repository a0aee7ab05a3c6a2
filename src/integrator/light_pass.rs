//! The light (forward) pass: rays from the lights, traced through surfaces and media; every
//! forward segment in a medium is tested against the integration volumes and every diffuse
//! surface hit against the surface spheres.

use std::collections::BTreeMap;
use std::f32::consts::PI;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::{Condvar, Mutex, MutexGuard, PoisonError};

use glam::Vec3;
use rand::Rng as _;

use super::camera_pass::{MAX_CROSSINGS, camera_mixture};
use super::gather::Gather;
use super::record::{CLASS_C, CLASS_D, VolumeShape};
use super::rng::{self, Domain, Rng};
use super::volume;
use crate::film::{ChunkSplats, Layer, PassBuffer};
use crate::geometry::{Hit, Ray, spawn};
use crate::material::LobeKind;
use crate::medium::{FlightEnd, ForwardFlight};
use crate::scene::Scene;
use crate::spectrum::Spectrum;

/// Forward rays per work item: fixed by the scene, never by the thread count, so that the sum
/// order (and so every bit of the image) does not depend on how many threads ran. Small, so that
/// a pass of a few thousand rays still spreads evenly over the threads (a chunk costs only its
/// splat log to hand over, not a film-sized buffer).
pub fn chunk_size(total: u64) -> u64 {
    (total / 256).clamp(256, 1 << 16)
}

/// Traces the pass's forward rays against `gather`; `tile` numbers the gather tiles of a pass
/// (0 unless a memory budget split it), keeping their random streams apart.
///
/// Workers take chunks in order and trace them without waiting for each other; a finished
/// chunk is added to `buf` as soon as every earlier chunk has been, so the sums are formed in
/// chunk order whatever the thread count. A worker only runs ahead of the oldest unfinished
/// chunk by a window of chunks, which bounds the memory of finished-but-unadded chunks.
pub fn light_pass(
    scene: &Scene,
    gather: &Gather,
    seed: u64,
    pass: u64,
    tile: u64,
    norm: f32,
    buf: &mut PassBuffer,
) {
    let total = scene.settings.forward_rays;
    let chunk = chunk_size(total);
    let chunks = total.div_ceil(chunk);
    let workers = rayon::current_num_threads().max(1) as u64;
    let window = 2 * workers;
    let (pixels, n) = (buf.pixels, buf.n);
    let order = Mutex::new(Order {
        next_add: 0,
        finished: BTreeMap::new(),
        spare: Vec::new(),
        buf,
    });
    let added = Condvar::new();
    let next_chunk = AtomicU64::new(0);
    let aborted = AtomicBool::new(false);
    let long = scene.settings.volume == crate::scene::desc::VolumeKind::CylinderLong;
    rayon::scope(|s| {
        for _ in 0..workers.min(chunks) {
            s.spawn(|_| {
                // A worker that panics never adds its chunk: wake the others so that they stop
                // instead of waiting for it forever (the panic then reaches the caller).
                let _wake = WakeOnPanic(&aborted, &added, &order);
                loop {
                    let c = next_chunk.fetch_add(1, Ordering::Relaxed);
                    if c >= chunks {
                        return;
                    }
                    let mut sink = {
                        let mut o = lock(&order);
                        while c >= o.next_add + window {
                            if aborted.load(Ordering::Relaxed) {
                                return;
                            }
                            o = added.wait(o).unwrap_or_else(PoisonError::into_inner);
                        }
                        o.spare.pop()
                    }
                    .unwrap_or_else(|| ChunkSplats::new(pixels, n));
                    let mut rng = rng::stream(seed, pass, Domain::Light, (tile << 40) | c);
                    let rays = chunk.min(total - c * chunk);
                    let mut tracer = ForwardTracer {
                        scene,
                        long,
                        gather,
                        norm,
                        buf: &mut sink,
                        // NaN bits never equal a real origin's.
                        origins: [([u32::MAX; 3], None); 8],
                        next_origin: 0,
                    };
                    for _ in 0..rays {
                        tracer.trace(&mut rng);
                    }
                    let mut o = lock(&order);
                    o.finished.insert(c, sink);
                    o.add_ready();
                    added.notify_all();
                }
            });
        }
    });
}

/// The ordered hand-over of finished chunks into the pass buffer.
struct Order<'b> {
    next_add: u64,
    finished: BTreeMap<u64, ChunkSplats>,
    spare: Vec<ChunkSplats>,
    buf: &'b mut PassBuffer,
}

impl Order<'_> {
    fn add_ready(&mut self) {
        while let Some(mut sink) = self.finished.remove(&self.next_add) {
            sink.drain_into(self.buf);
            self.spare.push(sink);
            self.next_add += 1;
        }
    }
}

struct WakeOnPanic<'a, 'b>(&'a AtomicBool, &'a Condvar, &'a Mutex<Order<'b>>);

impl Drop for WakeOnPanic<'_, '_> {
    fn drop(&mut self) {
        if std::thread::panicking() {
            // Under the lock, so no waiter can miss the flag between its check and its wait.
            let _o = lock(self.2);
            self.0.store(true, Ordering::Relaxed);
            self.1.notify_all();
        }
    }
}

/// A poisoned lock only means another worker panicked; the panic reaches the caller through
/// the scope anyway, so the data is still fine to use here.
fn lock<'m, 'b>(m: &'m Mutex<Order<'b>>) -> MutexGuard<'m, Order<'b>> {
    m.lock().unwrap_or_else(PoisonError::into_inner)
}

struct ForwardTracer<'a> {
    scene: &'a Scene,
    /// Volumes are paper eq. 3 "long" cylinders: gather over whole forward segments.
    long: bool,
    gather: &'a Gather,
    norm: f32,
    buf: &'a mut ChunkSplats,
    /// Recent emission origins (as bits) and their media.
    origins: [([u32; 3], Option<u32>); 8],
    next_origin: usize,
}

impl ForwardTracer<'_> {
    fn trace(&mut self, rng: &mut Rng) {
        let scene = self.scene;
        let u = [
            rng.random(),
            rng.random(),
            rng.random(),
            rng.random(),
            rng.random(),
        ];
        let Some(es) = scene.lights.sample(&scene.geometry, u) else {
            return;
        };
        let mut ray = es.ray;
        let mut flux = es.flux;
        let flux0 = flux.max_value();
        if flux0.is_nan() || flux0 <= 0.0 || !flux.is_finite() {
            return;
        }
        let mut class = CLASS_C;
        let mut medium = self.medium_at(ray.o);
        let (mut depth, mut crossings) = (0, 0);
        while depth < scene.settings.max_depth && crossings < MAX_CROSSINGS {
            let hit = scene.geometry.intersect(&ray, f32::INFINITY);
            if let Some(m) = medium {
                let seg_len = match &hit {
                    Some(h) => h.t,
                    None => scene.world_exit(&ray),
                };
                let med = &scene.media[m as usize];
                let flight =
                    ForwardFlight::sample(med, &flux, scene.settings.channel_floor, seg_len, rng);
                // Paper eq. 3 integrates the forward attenuation deterministically: it needs the
                // whole segment, not the sampled flight.
                let reach = if self.long { seg_len } else { flight.end() };
                self.gather_volumes(Some(m), class, &ray, reach, &flux, Some(&flight));
                match flight.finish(med, &mut flux, 0.0, rng) {
                    FlightEnd::Escaped => {}
                    FlightEnd::Killed { .. } => return,
                    FlightEnd::Scattered { t } => {
                        depth += 1;
                        if !self.roulette(&mut flux, flux0, depth, rng) {
                            return;
                        }
                        let p = ray.o + ray.d * t;
                        let d = med.phase.sample_dir(ray.d, rng.random(), rng.random());
                        ray = Ray { o: p, d };
                        continue;
                    }
                }
            }
            if medium.is_none() && scene.open_media {
                // Integration volumes poking out of index-matched boundaries still see the
                // forward rays that pass their outside part (method note 8).
                let len = hit.as_ref().map_or_else(|| scene.world_exit(&ray), |h| h.t);
                self.gather_volumes(None, class, &ray, len, &flux, None);
            }
            let Some(hit) = hit else { return };
            let shape = scene.geometry.shape(hit.shape);
            let Some(mat_id) = shape.material else {
                medium = scene.geometry.medium_after(&hit, ray.d);
                ray = spawn(hit.p, hit.ng, ray.d);
                crossings += 1;
                continue;
            };
            let material = &scene.materials[mat_id as usize];
            let wo = -ray.d;
            if material.diffuse_probability(wo, &hit) > 0.0 {
                self.gather_surfaces(&hit, ray.d, &flux);
            }
            let u = Vec3::new(rng.random(), rng.random(), rng.random());
            let Some(s) = material.sample(wo, &hit, u) else {
                return;
            };
            if s.kind == LobeKind::Diffuse {
                class = CLASS_D;
            }
            flux *= s.weight;
            if s.wi.dot(hit.ng).signum() != wo.dot(hit.ng).signum() {
                medium = scene.geometry.medium_after(&hit, s.wi);
            }
            ray = spawn(hit.p, hit.ng, s.wi);
            depth += 1;
            if !self.roulette(&mut flux, flux0, depth, rng) {
                return;
            }
        }
    }

    /// `Scene::medium_at` through a few remembered origins: point and spot lights emit every
    /// ray from the same point, so most lookups repeat one of a handful of answers.
    fn medium_at(&mut self, p: Vec3) -> Option<u32> {
        let key = p.to_array().map(f32::to_bits);
        if let Some((_, m)) = self.origins.iter().find(|(k, _)| *k == key) {
            return *m;
        }
        let m = self.scene.medium_at(p);
        self.origins[self.next_origin] = (key, m);
        self.next_origin = (self.next_origin + 1) % self.origins.len();
        m
    }

    fn roulette(&mut self, flux: &mut Spectrum, flux0: f32, depth: u32, rng: &mut Rng) -> bool {
        if depth < 2 {
            return flux.max_value() > 0.0;
        }
        let p = (flux.max_value() / flux0).min(1.0);
        if p.is_nan() || p <= 0.0 || rng.random::<f32>() >= p {
            return false;
        }
        *flux *= 1.0 / p;
        true
    }

    fn gather_surfaces(&mut self, hit: &Hit, v: Vec3, flux: &Spectrum) {
        let scene = self.scene;
        let n = scene.grid.n;
        let gather = self.gather;
        let wi = -v;
        let ng = if hit.ng.dot(wi) >= 0.0 {
            hit.ng
        } else {
            -hit.ng
        };
        let inv_area = 1.0 / (PI * gather.radius * gather.radius);
        gather.surfaces_at(hit.p, |rec| {
            let rn = rec.n.decode();
            // Same side of the same surface as the camera path's hit.
            if rn.dot(wi) <= 0.0 || rn.dot(ng) < 0.5 {
                return;
            }
            let Some(mat) = scene.geometry.shape(rec.shape).material else {
                return;
            };
            let at = Hit {
                t: 0.0,
                p: rec.p,
                ng: rn,
                ns: rn,
                uv: rec.uv,
                shape: rec.shape,
            };
            let f = scene.materials[mat as usize].eval_diffuse(rec.wo.decode(), wi, &at);
            let factor = f * *flux * (inv_area * rec.scale);
            let w = gather.throughput(rec.throughput);
            let norm = self.norm;
            self.buf
                .splat(Layer::Surface, rec.pixel as usize, w, &factor.0[..n], norm);
        });
    }

    /// Gathers a forward segment in medium `m` (None: vacuum) into the volumes it meets.
    /// Volumes of another medium count too when their medium is bounded only by index-matched
    /// boundaries, across which the radiance field is continuous (method note 8).
    fn gather_volumes(
        &mut self,
        m: Option<u32>,
        class: u8,
        ray: &Ray,
        len: f32,
        flux: &Spectrum,
        flight: Option<&ForwardFlight>,
    ) {
        let scene = self.scene;
        let n = scene.grid.n;
        let gather = self.gather;
        let radius = gather.radius;
        let norm = self.norm;
        let buf = &mut *self.buf;
        let seg_medium = m.map_or(u16::MAX, |m| m as u16);
        gather.volumes_along(ray.o, ray.d, len, |seg, rec| {
            if seg.classes & class == 0 {
                return;
            }
            let same = seg.medium == seg_medium;
            if !same && (seg.shape == VolumeShape::Long || !scene.open_medium(seg.medium as u32)) {
                return;
            }
            // The record's own medium scatters the light towards the camera.
            let med = &scene.media[seg.medium as usize];
            // A grey flight's flux does not change along the segment: skip its survival weights.
            let flight = flight.filter(|f| f.mixture().sigma_t_span() > 0.0);
            let fwd = flight.map(|f| f.mixture());
            // Evaluated only once a candidate's box test became a real hit: about half of the
            // candidates miss their sphere or cylinder.
            let phase = || med.phase.eval(-ray.d.dot(seg.dir));
            let w = gather.throughput(seg.throughput);
            let factor: Spectrum = match seg.shape {
                VolumeShape::Sphere => {
                    let centre = seg.at(rec.s);
                    let Some(chord) = volume::segment_sphere(ray.o, ray.d, len, centre, radius)
                    else {
                        return;
                    };
                    let f = phase();
                    let at = flight.map_or(*flux, |fl| fl.flux_at(flux, chord.mid()));
                    let k = f * volume::track_length_density(&chord, radius);
                    at * gather.sphere_weight(med, seg, rec, k)
                }
                _ => {
                    let axis = volume::CameraAxis {
                        origin: seg.origin,
                        dir: seg.dir,
                        len: rec.s,
                    };
                    let Some(chord) = volume::segment_cylinder(&axis, radius, ray.o, ray.d, len)
                    else {
                        return;
                    };
                    let k = match (seg.shape, fwd) {
                        (VolumeShape::Cylinder, Some(mix)) => {
                            volume::cylinder_eq2_fwd(med, mix, &chord, radius)
                        }
                        (VolumeShape::Cylinder, None) => volume::cylinder_eq2(med, &chord, radius),
                        (VolumeShape::Long, _) => volume::long_eq3_exact(med, &chord, radius),
                        _ => {
                            let cam =
                                camera_mixture(scene, &Spectrum::from_slice(w), seg.medium as u32);
                            volume::cylinder_truncated(med, &cam, fwd, &chord, radius)
                        }
                    };
                    *flux * k * phase()
                }
            };
            buf.splat(Layer::Medium, seg.pixel as usize, w, &factor.0[..n], norm);
        });
    }
}
