//! Memory of the gather structure per integration sphere on the real fog-cube scene (issue 9
//! target: <= 64 bytes), counted from a real camera pass, not from constants.

use super::{shipped_scene as scene, untiled_pass};
use crate::integrator::Integrator;
use crate::integrator::gather::{Gather, bytes_for};
use crate::world::Scene;

/// (bytes per sphere over all spheres, bytes per volume sphere of the volume part alone,
/// volume spheres) of one untiled pass.
fn bytes_per_sphere((s, integrator): &(Scene, Integrator)) -> (f64, f64, usize) {
    let mut out = untiled_pass(s, integrator, 1);
    let (surfaces, volumes) = (out.surfaces.len(), out.volumes.len());
    let predicted = bytes_for(&out);
    let g = Gather::from_output(&integrator.estimator, integrator.radii(0), &mut out);
    let bytes = g.bytes();
    // Without the surface spheres: the volume part's own bytes.
    let volume_part = Gather::new(
        &integrator.estimator,
        g.radii,
        Vec::new(),
        (g.segments.clone(), g.planes.clone()),
        g.volumes.clone(),
        g.throughputs.clone(),
        g.bins,
    )
    .bytes();
    eprintln!(
        "{volumes} volumes, {surfaces} surface spheres, {} segments, {} throughputs: {bytes} bytes \
         (predicted {predicted}), {:.1} per sphere, volume part {:.1} per volume sphere",
        g.segments.len(),
        g.throughputs.len() / g.bins,
        bytes as f64 / (volumes + surfaces) as f64,
        volume_part as f64 / volumes as f64,
    );
    // The tiling budget relies on the prediction not being too low.
    assert!(predicted >= bytes, "predicted {predicted} < {bytes}");
    (
        bytes as f64 / (volumes + surfaces) as f64,
        volume_part as f64 / volumes as f64,
        volumes,
    )
}

#[test]
fn fog_cube_gather_holds_at_most_64_bytes_per_sphere() {
    for (q, min_volumes) in [("1", 9_000), ("0.1", 90_000)] {
        let s = scene("fog-cube.toml", &[&format!("integrator.q={q}")]);
        let (all, volume_part, volumes) = bytes_per_sphere(&s);
        assert!(volumes >= min_volumes, "q = {q}: only {volumes} volumes");
        assert!(all <= 64.0, "q = {q}: {all} bytes per sphere");
        assert!(
            volume_part <= 64.0,
            "q = {q}: volume part {volume_part} bytes per sphere"
        );
    }
}

/// The figures for docs/performance.md (not a check):
/// `cargo test --lib gather_bytes -- --ignored --nocapture`.
#[test]
#[ignore]
fn report_bytes_per_sphere() {
    for (file, set) in [
        ("fog-cube.toml", "integrator.q=1"),
        ("fog-cube.toml", "integrator.q=0.1"),
        ("fog-cube.toml", "integrator.q=0.03"),
        ("fog-room-laser.toml", "integrator.q=1"),
        ("fog-room-laser.toml", "integrator.q=0.1"),
        ("chromatic-fog.toml", "integrator.q=1"),
        ("chromatic-fog.toml", "integrator.q=0.1"),
    ] {
        eprint!("{file} {set}: ");
        bytes_per_sphere(&scene(file, &[set]));
    }
}
