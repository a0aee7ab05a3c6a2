//! One chunk of a light pass's forward rays: a tracer of its own, its rays' random numbers,
//! and the counters it adds to the pass's (with a nest, the first rays' apart: `nest`).

use std::sync::atomic::{AtomicBool, Ordering};

use super::{ForwardTracer, LightJob, STOP_CHECK, chunk_size};
use crate::film::ChunkSplats;
use crate::integrator::Integrator;
use crate::integrator::gather::Gather;
use crate::integrator::record::CLASS_C;
use crate::integrator::rng::{self, Domain};
use crate::spectrum::Spectrum;
use crate::world::Scene;

/// Traces chunk `c` of the pass's forward rays against `gather` into `sink`, stopping early
/// (the chunk then unused) once `stop` is set.
pub(super) fn trace_chunk(
    (scene, integrator, gather): (&Scene, &Integrator, &Gather),
    job: &LightJob,
    c: u64,
    sink: &mut ChunkSplats,
    stop: &AtomicBool,
) {
    let total = integrator.forward_rays;
    let chunk = chunk_size(total);
    let mut rng = rng::stream(job.seed, job.pass, Domain::Light, (job.tile << 40) | c);
    // Ray `c * chunk + i` of the pass takes point `c * chunk + i` of the pass's
    // Sobol sequence (rng module comment): the pass's rays are stratified as a
    // whole, whichever worker traces them.
    let sequence = rng::sequence(job.seed, job.pass, Domain::Light, job.tile);
    let mut tracer = ForwardTracer {
        scene,
        integrator,
        gather,
        sensors: job.sensors,
        norm: job.norm,
        buf: sink,
        // NaN bits never equal a real origin's.
        origins: [([u32::MAX; 3], None); 8],
        next_origin: 0,
        flux: Spectrum::ZERO,
        flux0: 0.0,
        light: 0,
        class: CLASS_C,
        deposits: true,
        first_flight: true,
        specular_chain: true,
        // The gather tiles of a pass trace their own forward rays; one set
        // splats.
        splat_norm: (integrator.splat_to_camera && job.tile == 0).then(|| 1.0 / total as f32),
        hits: 0,
        first_paths_hits: 0,
        segments: 0,
        to_discs: false,
        nest: job.nest,
        extra_ray: false,
    };
    // Candidates met by the nest's first rays: on every record, and on the
    // first camera paths' records.
    let mut first_rays_hits = [0u64; 2];
    for i in 0..chunk.min(total - c * chunk) {
        // A chunk cut short is never used: `next` sees `stop` and aborts.
        if i % STOP_CHECK == 0 && stop.load(Ordering::Relaxed) {
            break;
        }
        if integrator.settings.sampler.stratifies() {
            rng.begin_sample(sequence, c * chunk + i);
        }
        let Some(nest) = job.nest else {
            tracer.trace(&mut rng);
            continue;
        };
        tracer.extra_ray = c * chunk + i >= nest.rays;
        let before = [tracer.hits, tracer.first_paths_hits];
        tracer.trace(&mut rng);
        if !tracer.extra_ray {
            first_rays_hits[0] += tracer.hits - before[0];
            first_rays_hits[1] += tracer.first_paths_hits - before[1];
        }
    }
    if job.nest.is_some() {
        let [a, b, c] = &job.nested_hits;
        a.fetch_add(first_rays_hits[0], Ordering::Relaxed);
        b.fetch_add(tracer.first_paths_hits, Ordering::Relaxed);
        c.fetch_add(first_rays_hits[1], Ordering::Relaxed);
    }
    job.hits.fetch_add(tracer.hits, Ordering::Relaxed);
    job.segments.fetch_add(tracer.segments, Ordering::Relaxed);
}
