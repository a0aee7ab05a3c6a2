//! `integrator.radius_indirect` (`radius::Radii`): forward rays deposit with the direct radius on
//! their first flight from a light whose direct light the volumes gather, and with the indirect
//! radius after their first scattering or non-null surface event. Both selections are checked
//! exactly: each setting is shown to be the only radius its light sees.

mod common;

use std::path::Path;

use common::*;

fn fog_cube(sets: &[&str]) -> Setup {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/fog-cube.toml");
    let mut all: Vec<String> = [
        "camera.width=24",
        "camera.height=24",
        "film.bins=4",
        "integrator.forward_rays=4000",
        "integrator.camera_samples=2",
    ]
    .iter()
    .map(|s| s.to_string())
    .collect();
    all.extend(sets.iter().map(|s| s.to_string()));
    scene_file(&path, &all)
}

fn pixels(s: &Setup) -> Vec<f32> {
    render(s, 7, 2).data
}

/// With next-event estimation for its only light, fog-cube's volumes and surface spheres gather
/// scattered light only: `radius = 0.01, radius_indirect = 0.03` renders the same bits as
/// `radius = 0.03` (same bounds, same records). Gathering any of it at 0.01 would change them.
#[test]
fn scattered_light_sees_only_the_indirect_radius() {
    let split = pixels(&fog_cube(&[
        "integrator.radius=0.01",
        "integrator.radius_indirect=0.03",
    ]));
    let wide = pixels(&fog_cube(&["integrator.radius=0.03"]));
    let narrow = pixels(&fog_cube(&["integrator.radius=0.01"]));
    assert_eq!(split, wide);
    assert_ne!(split, narrow, "the test must tell the radii apart");
}

/// With `direct = "photons"` and paths of one event, every deposit is a light's first flight:
/// `radius = 0.03, radius_indirect = 0.01` renders the same bits as `radius = 0.03` (same bounds
/// and world box, since both grow by the larger radius), and differs from `radius = 0.01`.
/// Gathering any first flight at the indirect radius would change them.
#[test]
fn direct_light_sees_only_the_direct_radius() {
    let base = [r#"integrator.direct="photons""#, "integrator.max_depth=1"];
    let with = |extra: &[&str]| {
        let mut s: Vec<&str> = base.to_vec();
        s.extend_from_slice(extra);
        pixels(&fog_cube(&s))
    };
    let split = with(&["integrator.radius=0.03", "integrator.radius_indirect=0.01"]);
    let wide = with(&["integrator.radius=0.03"]);
    let narrow = with(&["integrator.radius=0.01"]);
    assert_eq!(split, wide);
    assert_ne!(split, narrow, "the test must tell the radii apart");
}

/// Out-of-range values are refused, naming the key.
#[test]
fn a_bad_indirect_radius_is_refused() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/fog-cube.toml");
    for bad in ["-0.01", "0", "nan"] {
        let sets = vec![format!("integrator.radius_indirect={bad}")];
        let err = match brume::scene::load(&path, &sets) {
            Err(e) => e.to_string(),
            Ok(loaded) => match brume::scene::build(&loaded) {
                Err(e) => e.to_string(),
                Ok(scene) => match brume::scene::build_integrator(&loaded, &scene) {
                    Err(e) => e.to_string(),
                    Ok(_) => panic!("radius_indirect = {bad} was accepted"),
                },
            },
        };
        assert!(err.contains("radius_indirect"), "{err}");
    }
}
