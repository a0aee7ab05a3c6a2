//! Unit tests of the engine that need whole scenes.

mod gather_bytes;
mod gather_parts;
mod tiles;

use std::path::Path;
use std::sync::atomic::AtomicBool;

use crate::integrator::Integrator;
use crate::integrator::camera_pass::{CameraJob, camera_pass};
use crate::integrator::record::CameraOutput;
use crate::scene::{build, build_integrator, load};
use crate::world::Scene;

/// A scene of scenes/ with `sets` applied, and its integrator.
fn shipped_scene(file: &str, sets: &[&str]) -> (Scene, Integrator) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("scenes")
        .join(file);
    let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
    let loaded = load(&path, &sets).unwrap();
    let scene = build(&loaded).unwrap();
    let integrator = build_integrator(&loaded, &scene).unwrap();
    (scene, integrator)
}

/// The records of pass 0's camera pass at `seed`, over the whole image in one tile.
fn untiled_pass(scene: &Scene, integrator: &Integrator, seed: u64) -> CameraOutput {
    let job = CameraJob {
        seed,
        pass: 0,
        radii: integrator.radii(0),
        first_row: 0,
        budget_bytes: usize::MAX,
        light_layers: false,
        stride: 1,
        nest_paths: None,
    };
    let (out, rows) = camera_pass(scene, integrator, &job, &AtomicBool::new(false)).unwrap();
    assert_eq!(rows, scene.camera.resolution().1);
    out
}
