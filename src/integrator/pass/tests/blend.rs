//! A pass with two radii for scattered light (`film::blend`) against passes at each radius
//! alone: the sampling does not depend on the radius (the camera walk's spheres and the forward
//! rays draw the same random numbers), so its larger radius's image is the pass at that radius
//! and its smaller radius's (`data + blend`) the pass at the direct radius, up to the order of
//! the floating-point sums.

use std::path::Path;
use std::sync::atomic::AtomicBool;

use crate::film::LAYERS;
use crate::integrator::Renderer;
use crate::integrator::auto::PassConfig;
use crate::scene::{build, build_integrator, load};

/// A pass's image `data`, its difference layers and its sensors' values.
type Pass = (Vec<f32>, Vec<f32>, Vec<f32>);

/// Renders pass `p` of `file` at `indirect_scale` (2 with the blend when `blend`).
fn one_pass(file: &str, sets: &[&str], scale: f32, blend: bool, p: u64) -> Pass {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("scenes")
        .join(file);
    let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
    let loaded = load(&path, &sets).expect("a shipped scene");
    let scene = build(&loaded).expect("builds");
    let mut integrator = build_integrator(&loaded, &scene).expect("an integrator");
    integrator.blend_allowed = blend;
    let config = PassConfig {
        q: integrator.q.clone(),
        forward_rays: 20_000,
        camera_samples: 1,
        indirect_scale: scale,
    };
    let mut r = Renderer::new(&scene, integrator, 9);
    r.integrator.apply(&config, &scene.media).expect("applies");
    let stop = AtomicBool::new(false);
    let (buf, ..) = r.render_sampled((1, p), 0, None, &stop).expect("rendered");
    (buf.data, buf.blend, buf.sensor_data)
}

/// Largest difference of two images over their largest value.
fn relative(a: &[f32], b: &[f32]) -> f64 {
    let top = a.iter().fold(0.0f32, |m, v| m.max(v.abs())) as f64;
    let diff = a
        .iter()
        .zip(b)
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs() as f64));
    diff / top
}

fn blended_pass_holds_both_radii(file: &str, sets: &[&str]) {
    for p in [0, 3] {
        let (large, diff, sensors) = one_pass(file, sets, 2.0, true, p);
        assert_eq!(
            diff.len(),
            large.len(),
            "{file}: the pass has its difference layers"
        );
        assert_eq!(diff.len() % LAYERS, 0);
        let (alone_large, none, alone_sensors) = one_pass(file, sets, 2.0, false, p);
        assert!(none.is_empty());
        // Sensors are not blended: their values are the larger radius's (up to the sums' order).
        assert_eq!(sensors.len(), alone_sensors.len());
        let (alone_small, _, small_sensors) = one_pass(file, sets, 1.0, false, p);
        if !sensors.is_empty() {
            let e_sensors = relative(&sensors, &alone_sensors);
            assert!(e_sensors < 1e-5, "{file}: the sensors' values {e_sensors}");
            assert!(
                relative(&alone_sensors, &small_sensors) > 1e-4,
                "{file}: the sensors do not see the radius"
            );
        }
        let small: Vec<f32> = large.iter().zip(&diff).map(|(l, d)| l + d).collect();
        let (e_large, e_small) = (
            relative(&large, &alone_large),
            relative(&small, &alone_small),
        );
        // The radii's images differ by far more than the sums' rounding: the test is not vacuous.
        let apart = relative(&alone_large, &alone_small);
        eprintln!("{file} pass {p}: large {e_large:e}, small {e_small:e}, radii apart {apart:e}");
        assert!(
            e_large < 1e-5,
            "{file}: the larger radius's image {e_large}"
        );
        assert!(
            e_small < 1e-5,
            "{file}: the smaller radius's image {e_small}"
        );
        assert!(
            apart > 1e-2,
            "{file}: the radii's images barely differ ({apart})"
        );
    }
}

/// A medium's volumes and a wall's surface records behind it (a directional light, NEE).
#[test]
fn a_blended_pass_holds_both_radii_in_fog_cube() {
    blended_pass_holds_both_radii("fog-cube.toml", &["camera.width=24", "camera.height=24"]);
}

/// Spot lamps in a room with walls: volumes cut by the walls' planes, surface discs at edges;
/// its five illuminance sensors keep the larger radius.
#[test]
fn a_blended_pass_holds_both_radii_in_street_fog() {
    blended_pass_holds_both_radii("street-fog.toml", &["camera.width=32", "camera.height=18"]);
}
