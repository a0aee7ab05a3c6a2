//! Light layers from the integrator (issue 16): every splat names the light it came from, so
//! the layers sum to the image and each holds what a render with only its light shows. A fog
//! box, a floor, an emitting quad seen directly, a point light and a spot: forward rays,
//! next-event estimates in the fog and on the floor, and emitters seen by the camera all
//! reach the layers.

use brume::film::SpectralImage;

use crate::common::{mean_and_se, region_mean, render, scene};

const KINDS: [&str; 3] = ["area", "point", "spot"];

/// The scene with the lights `on` (area, point, spot); the quad stays (a null shape) when its
/// emission is off.
fn text(on: [bool; 3], direct: &str) -> String {
    let emit = if on[0] { "emit = 0.2" } else { "" };
    let mut t = format!(
        r#"
[film]
bins = 4
light_layers = true
[camera]
type = "perspective"
width = 16
height = 12
position = [0, 1.2, 4]
look_at = [0, 0.8, 0]
fov = 50
[integrator]
direct = "{direct}"
radius = 0.05
forward_rays = 60000
camera_samples = 4
[media.fog]
sigma_s = 0.3
sigma_a = 0.05
g = 0.3
[materials.floor]
type = "lambert"
albedo = 0.5
[[shapes]]
type = "quad"
size = [6, 6]
material = "floor"
transform = {{ rotate = [-90, 0, 0] }}
[[shapes]]
type = "box"
size = [3, 2, 3]
interior = "fog"
transform = {{ translate = [0, 1, 0] }}
[[shapes]]
type = "quad"
size = [1.0, 1.0]
{emit}
transform = {{ rotate = [90, 0, 0], translate = [0, 2.2, 0] }}
"#
    );
    if on[1] {
        t += "[[lights]]\ntype = \"point\"\nposition = [1, 1, 0.5]\npower = 200.0\n";
    }
    if on[2] {
        t += "[[lights]]\ntype = \"spot\"\nposition = [-1, 1.5, 0]\ndirection = [0.3, -1, 0]\n\
              angle = 30.0\nsoft_edge = 5.0\npower = 300.0\n";
    }
    t
}

fn layer<'a>(img: &'a SpectralImage, name: &str) -> &'a [f32] {
    &img.layers
        .iter()
        .find(|(n, _)| n == name)
        .unwrap_or_else(|| panic!("no layer {name}"))
        .1
}

/// Per bin over `runs` seeds: mean and standard error of the whole image's mean of `pick`.
fn estimate(
    text: &str,
    runs: u64,
    pick: impl Fn(&SpectralImage) -> Vec<f64>,
) -> (Vec<f64>, Vec<f64>) {
    let s = scene(text, &[]);
    let samples: Vec<Vec<f64>> = (0..runs).map(|k| pick(&render(&s, 40 + k, 3))).collect();
    mean_and_se(&samples, 4)
}

/// Acceptance (issue 16): the light layers add up to the image (to float rounding, in both
/// ways of estimating direct light), and each matches a render with only its light within
/// |z| <= 4 per bin.
#[test]
fn light_layers_sum_to_the_image_and_match_single_light_renders() {
    let names: Vec<String> = KINDS
        .iter()
        .enumerate()
        .map(|(i, k)| format!("light{i}.{k}"))
        .collect();
    for direct in ["nee", "photons"] {
        let img = render(&scene(&text([true; 3], direct), &[]), 1, 2);
        let peak = img.data.iter().fold(0f32, |m, v| m.max(v.abs()));
        let mut worst = 0f32;
        for (i, v) in img.data.iter().enumerate() {
            let sum: f32 = names.iter().map(|n| layer(&img, n)[i]).sum();
            worst = worst.max((sum - v).abs());
        }
        eprintln!("{direct}: largest |sum of layers - image| {worst:.3e} (peak {peak:.3e})");
        assert!(
            peak > 0.0 && worst <= 2e-6 * peak,
            "{direct}: {worst} of {peak}"
        );
    }
    let (w, h) = (16, 12);
    let all = text([true; 3], "nee");
    for (i, name) in names.iter().enumerate() {
        let (a, sa) = estimate(&all, 6, |img| {
            region_mean(img, layer(img, name), 0, w, 0, h)
        });
        let mut on = [false; 3];
        on[i] = true;
        let (b, sb) = estimate(&text(on, "nee"), 6, |img| {
            region_mean(img, &img.data, 0, w, 0, h)
        });
        for bin in 0..4 {
            let z = (a[bin] - b[bin]) / (sa[bin].powi(2) + sb[bin].powi(2)).sqrt();
            eprintln!(
                "{name} bin {bin}: layer {:.5e} (se {:.1e}), alone {:.5e} (se {:.1e}), z = {z:.2}",
                a[bin], sa[bin], b[bin], sb[bin]
            );
            assert!(z.abs() <= 4.0, "{name} bin {bin}: z = {z}");
            // A layer holding 40 % too much or too little would be found.
            assert!(
                sa[bin] < 0.1 * a[bin],
                "{name} bin {bin}: too noisy to test"
            );
        }
    }
}

/// With light layers and an illuminance sensor in the fog, the same seed gives the same film
/// (image, layers, sensor sums) with 1 and 2 threads, in both ways of estimating direct light.
#[test]
fn layers_and_sensors_are_deterministic_across_thread_counts() {
    for direct in ["nee", "photons"] {
        let t = text([true; 3], direct)
            + "[[sensors]]\ntype = \"illuminance\"\nposition = [0.2, 0.5, 0.3]\n\
               normal = [0, 1, 0]\n";
        let s = scene(&t, &["integrator.sensor_paths=100"]);
        let run = |threads: usize| {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .expect("pool");
            pool.install(|| {
                let mut r = s.renderer(9);
                r.run(brume::integrator::Budget::Passes(2), |_, _| {});
                r.into_film()
            })
        };
        let (a, b) = (run(1), run(2));
        assert!(a.sensor_sum.iter().any(|v| *v != 0) && a.light_sum.iter().any(|v| *v != 0));
        assert!(a == b, "{direct}: films differ between 1 and 2 threads");
    }
}
