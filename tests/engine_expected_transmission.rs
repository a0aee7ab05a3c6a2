//! `integrator.expected_transmission`: first-extinction camera paths go on past every medium
//! segment weighted by its transmittance, instead of only when their walk gets through. It
//! replaces an indicator by its expectation, so the image keeps its mean per layer and per
//! bin (|z| <= 4 between independent renders, at q = 1 and q = 0.3, in a grey and in a
//! chromatic fog), and the surface seen through the fog loses the indicator's variance.

mod common;

use std::path::Path;

use common::*;

const Z: f64 = 4.0;
const RUNS: u64 = 10;

fn setup(file: &str, q: &str, on: bool, extra: &[&str]) -> Setup {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("scenes")
        .join(file);
    let mut sets: Vec<String> = [
        "camera.width=16",
        "camera.height=12",
        "film.bins=8",
        "integrator.camera_samples=2",
        "integrator.mode=\"first-extinction\"",
    ]
    .iter()
    .map(|s| s.to_string())
    .collect();
    sets.push(format!("integrator.q={q}"));
    sets.push(format!("integrator.expected_transmission={on}"));
    sets.extend(extra.iter().map(|s| s.to_string()));
    scene_file(&path, &sets)
}

fn agree(file: &str, extra: &[&str]) {
    let mut worst = 0.0f64;
    for q in ["1", "0.3"] {
        let on = layer_means(&setup(file, q, true, extra), RUNS, 700);
        let off = layer_means(&setup(file, q, false, extra), RUNS, 800);
        let what = format!("{file} q={q}");
        worst = worst.max(assert_layers_agree(
            &what,
            ("expected", "sampled"),
            &on,
            &off,
            Z,
        ));
    }
    eprintln!("{file}: largest |z| {worst:.2}");
}

#[test]
fn fog_cube_keeps_its_mean() {
    agree("fog-cube.toml", &[]);
}

#[test]
fn chromatic_fog_keeps_its_mean() {
    agree("chromatic-fog.toml", &["integrator.forward_rays=50000"]);
}

/// fog-cube's wall is reached by 37 % of the camera paths without the setting (e^-1 through 1 m
/// of fog), each with weight 1: that coin alone has a relative variance of 1.7 per sample.
/// Measured: 10x to 50x lower surface variance with the setting; 4x is the bound (a wrong
/// weight, such as the walk's outcome kept as well, would not lower it).
#[test]
fn fog_cube_surface_variance_falls() {
    let on = layer_variance(
        &setup("fog-cube.toml", "1", true, &[]),
        "surface",
        RUNS,
        500,
    );
    let off = layer_variance(
        &setup("fog-cube.toml", "1", false, &[]),
        "surface",
        RUNS,
        500,
    );
    eprintln!(
        "surface variance: sampled {off:.3e}, expected {on:.3e} ({:.1}x)",
        off / on
    );
    assert!(off > 4.0 * on, "sampled {off:.3e} expected {on:.3e}");
}
