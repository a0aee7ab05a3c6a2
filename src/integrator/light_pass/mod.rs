//! The light (forward) pass: rays from the lights, traced through surfaces and media; every
//! forward segment in a medium is tested against the integration volumes and every diffuse
//! surface hit against the surface spheres.

use std::f32::consts::PI;
use std::sync::atomic::{AtomicBool, AtomicU64};

use glam::Vec3;
use rand::Rng as _;

use super::Integrator;
use super::camera_splat;
use super::chunk_order::{Shared, WakeOnPanic};

use super::gather::Gather;
use super::nest::{self, Deposit, Nest};
use super::path::{self, MediumStep, PathStep, SurfaceStep};
use super::record::{CLASS_C, CLASS_D};
use super::rng::Rng;
use super::sensors::SensorGather;
use super::target::Target;
use crate::film::{BlendRadius, ChunkSplats, Layer, PassBuffer};
use crate::geometry::{Hit, Ray};
use crate::material::LobeKind;
use crate::medium::{Along, ChannelPick, FlightEnd, ForwardFlight, Tracker, sample_scatter};
use crate::spectrum::Spectrum;
use crate::world::Scene;

mod chunk;
mod nested;
mod volumes;

use chunk::trace_chunk;

/// Forward rays per work item: fixed by the scene, never by the thread count, so that the sum
/// order (and so every bit of the image) does not depend on how many threads ran. Small, so that
/// a pass of a few thousand rays still spreads evenly over the threads (a chunk costs only its
/// splat log to hand over, not a film-sized buffer).
pub fn chunk_size(total: u64) -> u64 {
    (total / 256).clamp(256, 1 << 16)
}

/// Forward rays traced between two looks at the stop flag.
const STOP_CHECK: u64 = 256;

/// Which forward rays a light pass traces and how it weighs them.
pub struct LightJob<'a> {
    pub seed: u64,
    pub pass: u64,
    /// Numbers the gather tiles of a pass (0 unless a memory budget split it), keeping their
    /// random streams apart.
    pub tile: u64,
    /// Scale of every splat: 1 / (forward rays x camera samples per pixel).
    pub norm: f32,
    /// Counts the gather candidates the pass's forward rays met (work, for automatic
    /// settings; a sum, so the same whatever the thread count).
    pub hits: AtomicU64,
    /// Counts the forward segments traced (work, like `hits`).
    pub segments: AtomicU64,
    /// The sensors' records and discs (the first tile of a pass with illuminance sensors).
    pub sensors: Option<&'a SensorGather>,
    /// The estimates nested in the pass (`nest`): the pass's first `nest.rays` rays are those
    /// of its subset.
    pub nest: Option<&'a Nest>,
    /// With a nest, the gather candidates met by the first rays on every record, by every ray
    /// on the first camera paths' records, and by the first rays on those (`NestCounts::hits`
    /// 1..4; `hits` is the first).
    pub nested_hits: [AtomicU64; 3],
}

/// Traces the pass's forward rays against `gather` into `buf`. Returns false, leaving `buf`
/// partial, when `stop` was set (checked every [`STOP_CHECK`] rays: with eq. 2 cylinders in
/// the fog room a forward ray costs about a millisecond, a chunk of 65536 rays a minute).
///
/// Workers take chunks in order and trace them without waiting for each other; a finished
/// chunk is added to `buf` as soon as every earlier chunk has been, so the sums are formed in
/// chunk order whatever the thread count. A worker only runs ahead of the oldest unfinished
/// chunk by a window of chunks, which bounds the memory of finished-but-unadded chunks.
pub fn light_pass(
    scene: &Scene,
    integrator: &Integrator,
    gather: &Gather,
    job: &LightJob,
    buf: &mut PassBuffer,
    stop: &AtomicBool,
) -> bool {
    let total = integrator.forward_rays;
    let chunk = chunk_size(total);
    let workers = rayon::current_num_threads().max(1) as u64;
    let empty = ChunkSplats::for_buffer(buf);
    let shared = Shared::new(buf, total.div_ceil(chunk), 2 * workers);
    rayon::scope(|s| {
        for _ in 0..workers.min(shared.chunks()) {
            s.spawn(|_| {
                // A worker that panics never adds its chunk: wake the others so that they stop
                // instead of waiting for it forever (the panic then reaches the caller).
                let _wake = WakeOnPanic(&shared);
                while let Some((c, mut sink)) = shared.next(stop, &empty) {
                    trace_chunk((scene, integrator, gather), job, c, &mut sink, stop);
                    shared.finish(c, sink);
                }
            });
        }
    });
    !shared.aborted()
}

/// One worker's forward rays: the state of the ray being traced and where its splats go.
struct ForwardTracer<'a> {
    scene: &'a Scene,
    integrator: &'a Integrator,
    gather: &'a Gather,
    sensors: Option<&'a SensorGather>,
    norm: f32,
    buf: &'a mut ChunkSplats,
    /// Recent emission origins (as bits) and their media.
    origins: [([u32; 3], Option<u32>); 8],
    next_origin: usize,
    /// The current ray's flux, its largest bin at emission, and its class (method note 6).
    flux: Spectrum,
    flux0: f32,
    /// The light that emitted the ray (its index in the scene's `LightSet`).
    light: u32,
    class: u8,
    /// Whether the ray deposits in volumes and surface spheres: false on the first flight of a
    /// light whose direct light next-event estimation handles, until its first scattering or
    /// surface event (method note 9).
    deposits: bool,
    /// Whether the ray is still on its first flight from the light (no scattering, no
    /// non-null surface event): what it deposits is direct light, gathered at the direct radius
    /// (`radius::Radii`).
    first_flight: bool,
    /// Whether the ray has met only index-matched boundaries and specular reflections or
    /// refractions since its emission: what it deposits now is direct or caustic light, which
    /// the splat to the camera takes where the camera sees it directly (`camera_splat`).
    specular_chain: bool,
    /// `1 / forward rays` when first surface hits are splatted to the camera by this pass's
    /// forward rays (`camera_splat`; the first gather tile's).
    splat_norm: Option<f32>,
    /// Gather candidates met (surface spheres and volumes passed to their test).
    hits: u64,
    /// Of them, those of a nested pass's first camera paths (`nest`; not counted without).
    first_paths_hits: u64,
    /// Segments traced (`PathStep::medium` and `vacuum` calls, one geometry intersection each).
    segments: u64,
    /// Whether the ray is on its first flight from a light whose direct light the sensors'
    /// discs gather (`SensorGather::disc_gathers`).
    to_discs: bool,
    /// The estimates nested in the pass, and whether the ray being traced is one of the extra
    /// rays beyond their subset's (`nest`).
    nest: Option<&'a Nest>,
    extra_ray: bool,
}

impl<'a> ForwardTracer<'a> {
    fn trace(&mut self, rng: &mut Rng) {
        let scene = self.scene;
        let u = [
            rng.random(),
            rng.random(),
            rng.random(),
            rng.random(),
            rng.random(),
        ];
        let Some((light, es)) = scene.lights.sample(&scene.geometry, u) else {
            return;
        };
        self.flux = es.flux;
        self.flux0 = es.flux.max_value();
        self.light = light;
        if self.flux0.is_nan() || self.flux0 <= 0.0 || !es.flux.is_finite() {
            return;
        }
        self.class = CLASS_C;
        self.first_flight = true;
        self.specular_chain = true;
        self.deposits = !self
            .integrator
            .direct
            .as_ref()
            .is_some_and(|d| d.handles(light));
        self.to_discs = self
            .sensors
            .is_some_and(|s| s.disc_gathers(scene, self.integrator, light));
        let medium = self.medium_at(es.ray.o);
        let max_depth = self.integrator.settings.max_depth;
        path::trace(scene, max_depth, es.ray, medium, self, rng);
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

    /// Gathers a forward ray arriving along `v` at a diffuse surface `hit` into the surface
    /// spheres there (the image's, then the sensor paths').
    fn gather_surfaces(&mut self, hit: &Hit, v: Vec3) {
        let image = Target::Image { light: self.light };
        self.gather_surfaces_in((self.gather, image), hit, v);
        if let Some(s) = self.sensors {
            let target = Target::Sensors {
                scale: s.path_scale,
            };
            self.gather_surfaces_in((&s.gather, target), hit, v);
        }
    }

    /// Whether a camera path's first volumes and surface spheres leave direct and caustic light
    /// to the splat to the camera (in every tile; `camera_splat`).
    #[inline(always)]
    fn skips_primary(&self, target: Target) -> bool {
        self.specular_chain
            && matches!(target, Target::Image { .. })
            && self.integrator.splat_to_camera
    }

    /// Whether this flight's deposits into `target` are also made at the direct radius, for
    /// the film's blend of two radii for scattered light (`film::blend`): scattered light only,
    /// into the image only.
    #[inline(always)]
    fn blends(&self, gather: &Gather, target: Target) -> bool {
        gather.radii.blend
            && !self.first_flight
            && matches!(target, Target::Image { .. })
            && self.buf.keeps_blend()
    }

    fn gather_surfaces_in(&mut self, (gather, target): (&Gather, Target), hit: &Hit, v: Vec3) {
        let scene = self.scene;
        let n = scene.grid.n;
        let flux = &self.flux;
        let wi = -v;
        let ng = if hit.ng.dot(wi) >= 0.0 {
            hit.ng
        } else {
            -hit.ng
        };
        let direct = self.first_flight;
        let skip_primary = self.skips_primary(target);
        let radius = gather.radii.of(direct);
        let inv_area = 1.0 / (PI * radius * radius);
        // The blend's smaller radius takes the records within it, with their disc fraction at
        // it (`SurfaceRecord::scale`).
        let (blend, small) = (self.blends(gather, target), gather.radii.direct);
        let (small2, inv_small) = (small * small, 1.0 / (PI * small * small));
        let mut hits = 0u64;
        let mut first_paths_hits = 0u64;
        let nest = self.nested(target);
        gather.surfaces_at(hit.p, radius, |rec| {
            hits += 1;
            first_paths_hits += u64::from(!rec.extra);
            let rn = rec.n.decode();
            // Same side of the same surface as the camera path's hit (its own shape: the disc
            // fraction that renormalises the record counts only that shape).
            if rec.shape != hit.shape || rn.dot(wi) <= 0.0 || rn.dot(ng) < 0.5 {
                return;
            }
            if skip_primary && rec.primary {
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
            let scale = if direct {
                rec.scale
            } else {
                rec.scale_indirect
            };
            let factor = f * *flux * (inv_area * scale);
            let w = gather.throughput(rec.throughput);
            let (buf, norm) = (&mut *self.buf, self.norm);
            if blend {
                let pixel = rec.pixel as usize;
                let at = (BlendRadius::Large, Layer::Surface);
                buf.splat_blend(at, pixel, w, &factor.0[..n], norm);
                if rec.p.distance_squared(hit.p) < small2 {
                    let inner = f * *flux * (inv_small * rec.scale);
                    let at = (BlendRadius::Small, Layer::Surface);
                    buf.splat_blend(at, pixel, w, &inner.0[..n], norm);
                }
            } else {
                target.splat(buf, Layer::Surface, rec.pixel, w, &factor.0[..n], norm);
            }
            let deposit = Deposit::Gathered {
                extra_path: rec.extra,
            };
            nest::add(buf, nest, deposit, rec.pixel, (w, &factor.0[..n], norm));
        });
        self.hits += hits;
        self.first_paths_hits += first_paths_hits;
    }

    /// Adds the flux of the forward segment `ray` up to `len` (a flight's flux where it crosses)
    /// to the sensors whose discs it crosses (`SensorGather::crossings`).
    fn cross_discs(&mut self, ray: &Ray, len: f32, flight: Option<(&ForwardFlight, &Along)>) {
        let Some(s) = self.sensors else { return };
        let n = self.scene.grid.n;
        let flight = flight.filter(|(f, _)| f.mixture().sigma_t_span() > 0.0);
        let (buf, flux) = (&mut *self.buf, &self.flux);
        s.crossings(ray.o, ray.d, len, |k, t| {
            let at = flight.map_or(*flux, |(f, along)| f.flux_at(flux, along.depth(t)));
            buf.splat_sensor(k as usize, &at.0[..n], s.disc_scale);
        });
    }
}

impl PathStep for ForwardTracer<'_> {
    fn medium(
        &mut self,
        m: u32,
        ray: &Ray,
        (len, _): (f32, Option<&Hit>),
        rng: &mut Rng,
    ) -> MediumStep {
        self.segments += 1;
        let med = &self.scene.media[m as usize];
        let floor = self.integrator.settings.channel_floor;
        // The flight runs in optical depth at density 1 (the distance in a uniform medium) and
        // ends at that depth's distance; in a tracked medium it is a delta-tracking flight in
        // distance (method note 10) and the change of variable is the identity.
        let (along, flight) = match med.tracking.as_deref() {
            None => {
                // The depth is sampled first, so that a grid ray is built only as far as the
                // flight and its gathers reach (eq. 3 gathers along the whole segment).
                let flight = ForwardFlight::sample(med, &self.flux, floor, f32::INFINITY, rng);
                let u_max = if self.integrator.estimator.whole_forward_segment() {
                    f32::INFINITY
                } else {
                    flight.sampled()
                };
                let along = med.density.along_until(ray.o, ray.d, (len, u_max));
                let flight = flight.within(along.depth(len));
                (along, flight)
            }
            Some(t) => {
                let track = Tracker::new(t, ray.o, ray.d);
                let flight = ForwardFlight::tracked(med, &self.flux, floor, (len, &track), rng);
                (Along::Identity, flight)
            }
        };
        let end = along.distance(flight.end()).min(len);
        // Paper eq. 3 integrates the forward attenuation deterministically: it needs the whole
        // segment, not the sampled flight.
        let reach = if self.integrator.estimator.whole_forward_segment() {
            len
        } else {
            end
        };
        if self.deposits {
            self.gather_volumes(Some(m), ray, reach, Some((&flight, &along)));
            let scene = self.scene;
            if let Some(norm) = self.splat_norm.filter(|_| self.specular_chain)
                && let Some(v) = camera_splat::connect_medium(
                    scene,
                    (m, ray),
                    (&flight, &along),
                    &self.flux,
                    rng.random(),
                )
            {
                self.splat_to_camera(Layer::Medium, v, norm);
            }
        }
        if self.to_discs {
            self.cross_discs(ray, end, Some((&flight, &along)));
        }
        match flight.finish(med, &mut self.flux) {
            FlightEnd::Escaped => MediumStep::Reached,
            FlightEnd::Killed { .. } => MediumStep::Ended,
            FlightEnd::Scattered { .. } => MediumStep::Scattered(end),
        }
    }

    fn scatter(&mut self, m: u32, ray: &Ray, t: f32, depth: u32, rng: &mut Rng) -> Option<Ray> {
        self.deposits = true;
        self.first_flight = false;
        self.specular_chain = false;
        self.to_discs = false;
        if !self.roulette(depth, rng) {
            return None;
        }
        let p = ray.o + ray.d * t;
        let med = &self.scene.media[m as usize];
        let floor = self.integrator.settings.channel_floor;
        let (d, factors) =
            sample_scatter(med, ray.d, &self.flux, ChannelPick::Throughput, floor, rng);
        if let Some(f) = factors {
            self.flux *= f;
        }
        Some(Ray { o: p, d })
    }

    fn vacuum(&mut self, ray: &Ray, hit: Option<&Hit>) {
        self.segments += 1;
        let len = || hit.map_or_else(|| self.scene.world_exit(ray), |h| h.t);
        if self.scene.open_media && self.deposits {
            // Integration volumes poking out of index-matched boundaries still see the forward
            // rays that pass their outside part (method note 8).
            self.gather_volumes(None, ray, len(), None);
        }
        if self.to_discs {
            self.cross_discs(ray, len(), None);
        }
    }

    fn surface(&mut self, hit: &Hit, ray: &Ray, rng: &mut Rng) -> SurfaceStep {
        let scene = self.scene;
        let Some(mat_id) = scene.geometry.shape(hit.shape).material else {
            return SurfaceStep::Null;
        };
        let material = &scene.materials[mat_id as usize];
        let wo = -ray.d;
        if self.deposits && material.diffuse_probability(wo, hit) > 0.0 {
            if let Some(norm) = self.splat_norm.filter(|_| self.specular_chain)
                && let Some(v) = camera_splat::connect(scene, hit, ray.d, mat_id, &self.flux)
            {
                self.splat_to_camera(Layer::Surface, v, norm);
            }
            self.gather_surfaces(hit, ray.d);
        }
        self.deposits = true;
        self.first_flight = false;
        self.to_discs = false;
        let u = Vec3::new(rng.random(), rng.random(), rng.random());
        let Some(s) = material.sample(wo, hit, u) else {
            return SurfaceStep::Stop;
        };
        match s.kind {
            LobeKind::Diffuse => {
                self.class = CLASS_D;
                self.specular_chain = false;
            }
            LobeKind::Glossy => self.specular_chain = false,
            LobeKind::Specular => {}
        }
        self.flux *= s.weight;
        SurfaceStep::Scattered(s.wi)
    }

    /// Forward flux is relative to its emitted value `flux0`: the ray survives with probability
    /// `max_l Phi_l / flux0` after its second event (the first two carry the direct and
    /// once-scattered light, never cut), reweighted by the inverse. Before that a ray whose
    /// flux fell to zero (absorbed in every bin) ends.
    fn roulette(&mut self, depth: u32, rng: &mut Rng) -> bool {
        if depth < 2 {
            return self.flux.max_value() > 0.0;
        }
        let p = (self.flux.max_value() / self.flux0).min(1.0);
        if p.is_nan() || p <= 0.0 || rng.random::<f32>() >= p {
            return false;
        }
        self.flux *= 1.0 / p;
        true
    }
}
