//! Helpers shared by the engine tests: render a scene given as TOML text and measure regions.
#![allow(dead_code)]

use std::path::Path;

use brume::film::SpectralImage;
use brume::integrator::{Budget, Integrator, Renderer};
use brume::scene::{Scene, build, build_integrator, load_str};

/// A built scene and the integrator its file describes; derefs to the scene.
pub struct Setup {
    pub scene: Scene,
    pub integrator: Integrator,
}

impl std::ops::Deref for Setup {
    type Target = Scene;
    fn deref(&self) -> &Scene {
        &self.scene
    }
}

impl Setup {
    /// A renderer of this scene with its integrator.
    pub fn renderer(&self, seed: u64) -> Renderer<'_> {
        Renderer::new(&self.scene, self.integrator.clone(), seed)
    }
}

pub fn scene(text: &str, sets: &[&str]) -> Setup {
    let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/test.toml");
    let loaded = load_str(text, &dir, &sets).unwrap_or_else(|e| panic!("{e}"));
    let scene = build(&loaded).unwrap_or_else(|e| panic!("{e}"));
    let integrator = build_integrator(&loaded, &scene).unwrap_or_else(|e| panic!("{e}"));
    Setup { scene, integrator }
}

/// Loads and builds a scene file with `--set` overrides.
pub fn scene_file(file: &Path, sets: &[String]) -> Setup {
    let loaded = brume::scene::load(file, sets).unwrap_or_else(|e| panic!("{e}"));
    let scene = build(&loaded).unwrap_or_else(|e| panic!("{e}"));
    let integrator = build_integrator(&loaded, &scene).unwrap_or_else(|e| panic!("{e}"));
    Setup { scene, integrator }
}

pub fn render(setup: &Setup, seed: u64, passes: u32) -> SpectralImage {
    let mut r = setup.renderer(seed);
    r.run(Budget::Passes(passes), |_, _| {});
    r.image()
}

/// Mean per bin over the pixel rectangle [x0, x1) x [y0, y1) of `data` (one of the image's layers).
pub fn region_mean(
    img: &SpectralImage,
    data: &[f32],
    x0: usize,
    x1: usize,
    y0: usize,
    y1: usize,
) -> Vec<f64> {
    let n = img.grid.n;
    let mut acc = vec![0.0f64; n];
    for y in y0..y1 {
        for x in x0..x1 {
            let i = (y * img.width + x) * n;
            for b in 0..n {
                acc[b] += data[i + b] as f64;
            }
        }
    }
    let count = ((x1 - x0) * (y1 - y0)) as f64;
    acc.iter().map(|a| a / count).collect()
}

/// Independent renders (different seeds) of a region's per-bin mean: (mean, standard error).
pub fn independent_estimates(
    scene: &Setup,
    runs: u64,
    passes: u32,
    region: (usize, usize, usize, usize),
) -> (Vec<f64>, Vec<f64>) {
    let n = scene.grid.n;
    let mut samples: Vec<Vec<f64>> = Vec::new();
    for seed in 0..runs {
        let img = render(scene, 1000 + seed, passes);
        samples.push(region_mean(
            &img, &img.data, region.0, region.1, region.2, region.3,
        ));
    }
    mean_and_se(&samples, n)
}

pub fn mean_and_se(samples: &[Vec<f64>], n: usize) -> (Vec<f64>, Vec<f64>) {
    let k = samples.len() as f64;
    let mut mean = vec![0.0; n];
    let mut se = vec![0.0; n];
    for b in 0..n {
        let m = samples.iter().map(|s| s[b]).sum::<f64>() / k;
        let var = samples.iter().map(|s| (s[b] - m).powi(2)).sum::<f64>() / (k - 1.0);
        mean[b] = m;
        se[b] = (var / k).sqrt();
    }
    (mean, se)
}

/// Asserts |mean - expected| <= z * se per bin (with a small relative floor for the
/// estimator's kernel bias), printing the table.
pub fn assert_bins(name: &str, mean: &[f64], se: &[f64], expected: &[f64], z: f64, rel_floor: f64) {
    for b in 0..mean.len() {
        let tol = z * se[b] + rel_floor * expected[b].abs();
        let zs = (mean[b] - expected[b]) / se[b].max(1e-300);
        eprintln!(
            "{name} bin {b}: got {:.6e} expected {:.6e} se {:.2e} z {:.2}",
            mean[b], expected[b], se[b], zs
        );
        assert!(
            (mean[b] - expected[b]).abs() <= tol,
            "{name} bin {b}: {} vs {} (se {}, z {zs:.2})",
            mean[b],
            expected[b],
            se[b]
        );
    }
}

/// Mean over pixels of the per-pixel variance of layer `layer` ("medium", "surface"), all bins
/// summed, over `runs` one-pass renders (seeds `seed0..`).
pub fn layer_variance(s: &Setup, layer: &str, runs: u64, seed0: u64) -> f64 {
    let n = s.grid.n;
    let per_run: Vec<Vec<f64>> = (0..runs)
        .map(|r| {
            let img = render(s, seed0 + r, 1);
            let (_, data) = img
                .layers
                .iter()
                .find(|(k, _)| k == layer)
                .expect("the film has the layer");
            data.chunks(n)
                .map(|px| px.iter().map(|&v| v as f64).sum())
                .collect()
        })
        .collect();
    let pixels = per_run[0].len();
    let k = runs as f64;
    (0..pixels)
        .map(|p| {
            let m = per_run.iter().map(|r| r[p]).sum::<f64>() / k;
            per_run.iter().map(|r| (r[p] - m).powi(2)).sum::<f64>() / (k - 1.0)
        })
        .sum::<f64>()
        / pixels as f64
}

/// Per layer ("medium", "surface"), per bin: the image mean over `runs` one-pass renders (seeds
/// `seed0..`) and its standard error.
pub fn layer_means(s: &Setup, runs: u64, seed0: u64) -> LayerMeans {
    let n = s.grid.n;
    let imgs: Vec<SpectralImage> = (0..runs).map(|r| render(s, seed0 + r, 1)).collect();
    let names: Vec<String> = imgs[0].layers.iter().map(|(k, _)| k.clone()).collect();
    names
        .iter()
        .enumerate()
        .map(|(li, name)| {
            let samples: Vec<Vec<f64>> = imgs
                .iter()
                .map(|img| {
                    let data = &img.layers[li].1;
                    let pixels = data.len() / n;
                    (0..n)
                        .map(|b| {
                            (0..pixels).map(|p| data[p * n + b] as f64).sum::<f64>() / pixels as f64
                        })
                        .collect()
                })
                .collect();
            let (mean, se) = mean_and_se(&samples, n);
            (name.clone(), mean, se)
        })
        .collect()
}

/// Layer means of `layer_means`: (layer name, mean per bin, standard error per bin).
pub type LayerMeans = Vec<(String, Vec<f64>, Vec<f64>)>;

/// Asserts that two renders' layer means agree per layer and per bin within |z| <= `z_max`
/// (their standard errors combined as independent); returns the largest |z|. `what` and the
/// two `names` label a failure.
pub fn assert_layers_agree(
    what: &str,
    names: (&str, &str),
    a: &LayerMeans,
    b: &LayerMeans,
    z_max: f64,
) -> f64 {
    let mut worst = 0.0f64;
    for ((layer, ma, sa), (_, mb, sb)) in a.iter().zip(b) {
        for bin in 0..ma.len() {
            let se = (sa[bin].powi(2) + sb[bin].powi(2)).sqrt();
            let z = if se > 0.0 {
                (ma[bin] - mb[bin]) / se
            } else {
                0.0
            };
            worst = worst.max(z.abs());
            assert!(
                z.abs() <= z_max,
                "{what} {layer} bin {bin}: {} {:.4e} {} {:.4e} (z {z:.2})",
                names.0,
                ma[bin],
                names.1,
                mb[bin]
            );
        }
    }
    worst
}

/// A direction uniform on the unit sphere, by rejection from the cube (the geometry tests'
/// random rays).
pub fn random_dir(rng: &mut rand_pcg::Pcg64Mcg) -> glam::Vec3 {
    use rand::Rng;
    loop {
        let v = glam::Vec3::new(rng.random::<f32>(), rng.random(), rng.random()) * 2.0 - 1.0;
        let l = v.length_squared();
        if l > 1e-4 && l <= 1.0 {
            return v / l.sqrt();
        }
    }
}

/// Random rays from a box around the scene, half of them aimed at random scene points so that
/// many hit; compares closest hits and any-hit answers.
pub fn check_against_brute_force(geo: &brume::geometry::Geometry, n_rays: usize, seed: u64) {
    use brume::geometry::Ray;
    use glam::Vec3;
    use rand::{Rng, SeedableRng};
    let mut rng = rand_pcg::Pcg64Mcg::seed_from_u64(seed);
    let b = geo.bounds();
    let (c, ext) = (b.centre(), b.diagonal());
    let mut hits = 0;
    for k in 0..n_rays {
        let o = c + (Vec3::new(rng.random(), rng.random(), rng.random()) - 0.5) * ext * 1.5;
        // Every seventh ray is axis-parallel (with either sign of zero), a case obvhs mishandles raw.
        let d = if k % 7 == 0 {
            let a = [Vec3::X, Vec3::Y, Vec3::Z][rng.random_range(0..3)];
            if rng.random::<bool>() { -a } else { a }
        } else if k % 2 == 0 {
            let target =
                c + (Vec3::new(rng.random(), rng.random(), rng.random()) - 0.5) * ext * 0.8;
            (target - o).normalize_or(Vec3::Z)
        } else {
            random_dir(&mut rng)
        };
        let ray = Ray::new(o, d);
        let t_max = if k % 3 == 0 {
            rng.random::<f32>() * ext.length()
        } else {
            f32::INFINITY
        };
        let fast = geo.intersect(&ray, t_max);
        let slow = geo.intersect_brute_force(&ray, t_max);
        match (fast, slow) {
            (None, None) => {}
            (Some(f), Some(s)) => {
                hits += 1;
                assert_eq!(f.t, s.t, "ray {k}: closest t differs");
                // Equal t on two shapes where they touch: the same shape wins in both, ranked alike.
                assert_eq!(f.shape, s.shape, "ray {k}");
                assert!((f.p - s.p).length() < 1e-4);
            }
            _ => panic!("ray {k}: bvh {fast:?} vs brute force {slow:?}"),
        }
        assert_eq!(
            geo.occluded(&ray, t_max),
            slow.is_some(),
            "ray {k}: any-hit differs"
        );
    }
    // Not vacuous: a good share of rays must hit.
    assert!(hits > n_rays / 5, "only {hits} hits");
}
