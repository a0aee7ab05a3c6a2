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
    // Camera paths and forward rays from Sobol points (camera_pass::trace_row).
    check(
        "fog-cube, sobol",
        "fog-cube.toml",
        &["integrator.sampler=\"sobol\""],
    );
}

#[test]
fn chromatic_fog_partition() {
    check(
        "chromatic-fog",
        "chromatic-fog.toml",
        &[
            "integrator.forward_rays=100000",
            "integrator.camera_samples=8",
            // At this tiny image's automatic radius (0.32 m) the gathered direct light on the
            // surfaces carries a kernel bias of about -11 % (z 3.7 over 60 renders), which the
            // test's 10 renders would only hide: 5 cm keeps the comparison honest.
            "integrator.radius=0.05",
        ],
    );
    // With the Sobol sampler (camera paths and forward rays) the next-event surface's noise
    // falls below the gathered direct light's kernel bias at this tiny image's automatic radius
    // (0.32 m: largest |z| 7.8, the photons surface about 11 % low with either sampler); at
    // 5 cm the two modes agree.
    check(
        "chromatic-fog, sobol",
        "chromatic-fog.toml",
        &[
            "integrator.forward_rays=100000",
            "integrator.camera_samples=8",
            "integrator.sampler=\"sobol\"",
            "integrator.radius=0.05",
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

/// `integrator.sampler = "sobol"` gives each pixel's camera paths of a pass the points of one
/// Owen-scrambled Sobol sequence (and the forward rays theirs): every path is still distributed
/// exactly as with independent numbers, so each layer and bin keeps its mean. Compared with the
/// independent sampler in the same mode at the same radius (so the gathered part's kernel bias
/// is the same on both sides), from independent seeds: |z| <= 4. This is the comparison the
/// partition tests cannot make with the Sobol sampler on chromatic-fog: at these tiny images
/// the automatic radius is about 0.23 m, and the photons mode's gathered surface carries a
/// kernel bias of about -11 % that the independent sampler's next-event noise hides.
#[test]
fn sobol_camera_paths_keep_every_layers_mean() {
    let cases: [(&str, &[&str]); 2] = [
        ("fog-cube.toml", &["integrator.camera_samples=4"]),
        (
            "chromatic-fog.toml",
            &[
                "integrator.forward_rays=100000",
                "integrator.camera_samples=8",
            ],
        ),
    ];
    let mut worst = 0.0f64;
    for (file, extra) in cases {
        let path = Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("scenes")
            .join(file);
        for mode in ["nee", "photons"] {
            let mut by_sampler = Vec::new();
            for (sampler, seed0) in [("independent", 900), ("sobol", 5900)] {
                let mut s: Vec<String> = [
                    "camera.width=16",
                    "camera.height=12",
                    "film.bins=8",
                    "integrator.q=1",
                ]
                .iter()
                .chain(extra)
                .map(|s| s.to_string())
                .collect();
                s.push(format!("integrator.direct=\"{mode}\""));
                s.push(format!("integrator.sampler=\"{sampler}\""));
                by_sampler.push(layer_means(&scene_file(&path, &s), 2 * RUNS, seed0));
            }
            let what = format!("{file} {mode}");
            let names = ("independent", "sobol");
            let w = assert_layers_agree(&what, names, &by_sampler[0], &by_sampler[1], Z);
            worst = worst.max(w);
        }
    }
    eprintln!("sobol vs independent: largest |z| {worst:.2}");
}
