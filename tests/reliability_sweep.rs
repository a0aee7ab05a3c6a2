//! Adversarial sweep: tiny renders over a grid of extreme parameters (g near +-1, extinction
//! 0 / tiny / huge, q tiny, radius tiny / huge, every integration volume, grazing and laser
//! light, and a point light so that the images are not black). Each must finish without panicking and write only finite pixels.

mod common;

use brume::integrator::Budget;

/// A fog box on a wall, a grazing directional light, and a laser skimming the wall.
const SCENE: &str = r#"
[film]
bins = 4

[camera]
type = "orthographic"
width = 6
height = 4
position = [0.0, 0.0, 3.0]
look_at = [0.0, 0.0, 0.0]
view_width = 1.4
view_height = 1.0

[integrator]
radius = 0.05
forward_rays = 300
camera_samples = 1
passes = 1

[media.fog]
sigma_s = 0.8
sigma_a = 0.2
g = 0.0

[materials.wall]
type = "lambert"
albedo = 0.5

[[shapes]]
type = "box"
size = [1.0, 1.0, 1.0]
interior = "fog"

[[shapes]]
type = "quad"
size = [2.0, 2.0]
material = "wall"
transform = { translate = [0.0, 0.0, -0.5002] }

[[lights]]
type = "directional"
direction = [1.0, 0.0, -1e-6]
irradiance = 1000.0

[[lights]]
type = "laser"
position = [-0.9, 0.0, -0.5]
direction = [1.0, 0.0, 1e-7]
radius = 1e-4
power = 10.0

[[lights]]
type = "point"
position = [0.3, 0.2, 1.5]
power = 100.0
"#;

#[test]
fn extreme_parameters_give_finite_images() {
    let mut report = Vec::new();
    let mut cases = 0;
    // Radius-10 volumes are met by every forward ray: those images must not be black.
    let mut black = Vec::new();
    for volume in ["spheres", "cylinder", "cylinder-truncated", "cylinder-long"] {
        for g in ["-0.999", "0", "0.999"] {
            for sigma in ["0", "1e-6", "1e6"] {
                for q in ["1e-4", "1"] {
                    if q != "1" && volume != "spheres" {
                        continue;
                    }
                    // 1/q spheres per camera path in an opaque medium cost ~10 s per case
                    // (expected work, not a fault); q = 1e-2 stands in there.
                    let q = if q == "1e-4" && sigma == "1e6" {
                        "1e-2"
                    } else {
                        q
                    };
                    for (radius, direct) in [
                        ("1e-6", "photons"),
                        ("1e-6", "nee"),
                        ("10", "photons"),
                        ("10", "nee"),
                    ] {
                        let sets = [
                            format!("integrator.direct=\"{direct}\""),
                            format!("integrator.volume=\"{volume}\""),
                            format!("media.fog.g={g}"),
                            format!("media.fog.sigma_s={sigma}"),
                            format!("media.fog.sigma_a={sigma}"),
                            format!("integrator.q={q}"),
                            format!("integrator.radius={radius}"),
                        ];
                        let sets: Vec<&str> = sets.iter().map(|s| s.as_str()).collect();
                        let scene = common::scene(SCENE, &sets);
                        let mut r = scene.renderer(7);
                        r.run(Budget::Passes(2), |_, _| {});
                        let img = r.image();
                        let finite = img.data.iter().all(|v| v.is_finite())
                            && img.noise.iter().flatten().all(|v| v.is_finite())
                            && img
                                .layers
                                .iter()
                                .all(|(_, l)| l.iter().all(|v| v.is_finite()));
                        assert!(finite, "non-finite pixel with {sets:?}");
                        if r.film().dropped > 0 {
                            report.push(format!("{} dropped: {sets:?}", r.film().dropped));
                        }
                        // Cylinders in opaque fog (sigma 1e6) only see the light that passes
                        // outside the box near it: about 6e-5 per pixel, which 2 x 300 forward
                        // rays usually miss (2 x 30 000 find it), so no light is expected there.
                        let expect_light = !(sigma == "1e6" && volume != "spheres");
                        if radius == "10" && expect_light && !img.data.iter().any(|v| *v > 0.0) {
                            black.push(format!("{sets:?}"));
                        }
                        cases += 1;
                    }
                }
            }
        }
    }
    // Which settings produce non-finite samples (dropped, so the images stay finite).
    for line in &report {
        eprintln!("{line}");
    }
    assert_eq!(cases, 3 * 3 * 4 * 2 + 3 * 3 * 4 * 3);
    assert!(black.is_empty(), "black images: {black:#?}");
}
