//! The hybrid transport's partition (method note 9, issue 15): with `direct = "nee"` camera
//! paths estimate direct light and forward rays of those lights deposit only after their first
//! event; with `direct = "photons"` forward rays carry everything. Both count every light path
//! once, so on the shipped scenes they agree per layer and per bin, at q = 1 and q = 0.3 and for
//! both channel picks: |z| <= 4, z from independent renders of each mode (tiny images, the
//! layers' image means). One difference is by design: next-event estimation also reflects point
//! and spot lights in glossy coats, which no forward ray can bring to a camera path (the pure
//! method has no glossy highlight of a delta light); on the room's floor, seen at grazing
//! angles, it stays below these tests' noise.

mod common;

use std::path::Path;

use common::*;

const Z: f64 = 4.0;
const RUNS: u64 = 10;

fn check(name: &str, file: &str, extra: &[&str]) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("scenes")
        .join(file);
    let mut worst = 0.0f64;
    for q in ["1", "0.3"] {
        for pick in ["throughput", "uniform"] {
            let mut sets: Vec<String> = [
                "camera.width=16",
                "camera.height=12",
                "film.bins=8",
                "integrator.camera_samples=2",
            ]
            .iter()
            .map(|s| s.to_string())
            .collect();
            sets.push(format!("integrator.q={q}"));
            sets.push(format!("integrator.channel_pick=\"{pick}\""));
            sets.extend(extra.iter().map(|s| s.to_string()));
            let mut by_mode = Vec::new();
            for mode in ["nee", "photons"] {
                let mut s = sets.clone();
                s.push(format!("integrator.direct=\"{mode}\""));
                by_mode.push(layer_means(&scene_file(&path, &s), RUNS, 900));
            }
            let what = format!("{name} q={q} {pick}");
            let w = assert_layers_agree(&what, ("nee", "photons"), &by_mode[0], &by_mode[1], Z);
            worst = worst.max(w);
        }
    }
    eprintln!("{name}: largest |z| {worst:.2}");
}

#[test]
fn fog_cube_partition() {
    check("fog-cube", "fog-cube.toml", &[]);
}

#[test]
fn chromatic_fog_partition() {
    check(
        "chromatic-fog",
        "chromatic-fog.toml",
        &[
            "integrator.forward_rays=100000",
            "integrator.camera_samples=8",
        ],
    );
}

#[test]
fn glass_sphere_fog_partition() {
    check(
        "glass-sphere-fog",
        "glass-sphere-fog.toml",
        &["integrator.forward_rays=40000"],
    );
}

#[test]
fn fog_room_partition_with_and_without_laser() {
    check("fog-room-laser", "fog-room-laser.toml", &[]);
    // Without its laser (its power made negligible, so that it draws no forward rays).
    check("fog-room", "fog-room-laser.toml", &["lights.3.power=1e-12"]);
    // One spot's direct light left with the forward rays (`direct = "photons"` on that light).
    check(
        "fog-room, mixed",
        "fog-room-laser.toml",
        &["lights.3.power=1e-12", "lights.0.direct=\"photons\""],
    );
}
