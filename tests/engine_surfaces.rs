//! The surface engine against analytic radiance: integration spheres on diffuse surfaces
//! gathering forward rays (paper sections 1-2; method note 1 on surfaces). Fixed seeds; each
//! comparison is per spectral bin with a stated z-bound. The scenes pin `direct = "photons"`
//! (the paper's surface spheres); the last test checks next-event estimation on the same
//! surfaces.

mod common;

use std::f64::consts::PI;

use brume::spectrum::{SpectralGrid, power_law};
use common::*;

const Z: f64 = 4.0;

/// Lambert quad of spectral albedo rho under a directional light of irradiance E at angle
/// theta, orthographic camera: L = rho E cos(theta) / pi in every bin.
#[test]
fn lambert_quad_under_directional_light() {
    let theta: f64 = 30f64.to_radians();
    let text = format!(
        r#"
[film]
bins = 8
[camera]
type = "orthographic"
width = 24
height = 24
position = [0, 0, 2]
look_at = [0, 0, 0]
view_width = 0.8
view_height = 0.8
[integrator]
direct = "photons"
radius = 0.02
forward_rays = 100000
[spectra.rho]
power_law = {{ k = 0.5, p = 1.0 }}
[materials.paper]
type = "lambert"
albedo = "rho"
[[shapes]]
type = "quad"
size = [1, 1]
material = "paper"
[[lights]]
type = "directional"
direction = [{}, 0, {}]
irradiance = 2.0
spectrum = 1.0
"#,
        theta.sin(),
        -theta.cos()
    );
    let scene = scene(&text, &[]);
    let grid = SpectralGrid::new(8, 380.0, 780.0);
    let rho = power_law(0.5, 550.0, 1.0, &grid);
    let e_per_nm = 2.0 / 400.0;
    let expected: Vec<f64> = (0..8)
        .map(|b| rho[b] as f64 * e_per_nm * theta.cos() / PI)
        .collect();
    let (mean, se) = independent_estimates(&scene, 6, 2, (0, 24, 0, 24));
    assert_bins("lambert", &mean, &se, &expected, Z, 0.0);
}

/// Near the quad's edge a sphere would lose the part of its disc beyond the edge (the band
/// within R of the edge darker by the mean lost fraction, `analytic` below); divided by the
/// part of its disc on the quad (issue 19), the band is as bright as the interior.
#[test]
fn edge_band_is_not_darkened() {
    let text = r#"
[film]
bins = 4
[camera]
type = "orthographic"
width = 40
height = 16
position = [0.45, 0, 2]
look_at = [0.45, 0, 0]
view_width = 0.2
view_height = 0.08
[integrator]
direct = "photons"
forward_rays = 100000
[materials.paper]
type = "lambert"
albedo = 0.5
[[shapes]]
type = "quad"
size = [1, 1]
material = "paper"
[[lights]]
type = "directional"
direction = [0, 0, -1]
irradiance = 1.0
spectrum = 1.0
"#;
    // The view covers x in [0.35, 0.55]; the quad ends at x = 0.5 (pixel 30). Pixels 20..30
    // cover the band x in [0.45, 0.5]. A sphere at distance d < R from the edge keeps only the
    // part of its disc on the quad: the band's expected deficit is the mean lost disc fraction.
    let analytic = |r: f64| {
        let m = 2000;
        (0..m)
            .map(|i| {
                let d = r * (i as f64 + 0.5) / m as f64;
                if d >= r {
                    0.0
                } else {
                    (r * r * (d / r).acos() - d * (r * r - d * d).sqrt()) / (PI * r * r)
                }
            })
            .sum::<f64>()
            / m as f64
    };
    let deficit = |r: f64| {
        let s = scene(
            text,
            &[
                &format!("integrator.radius={r}"),
                "integrator.forward_rays=400000",
            ],
        );
        let img = render(&s, 7, 16);
        let inner = region_mean(&img, &img.data, 0, 10, 0, 16)[0];
        // The band within R of the edge (R / 0.005 pixels).
        let band = (r / 0.005).round() as usize;
        let edge = region_mean(&img, &img.data, 30 - band, 30, 0, 16)[0];
        1.0 - edge / inner
    };
    // Bounds of 4 standard deviations of the deficit at these settings (measured over seeds
    // 7 to 11: 0.0065 over the 10-pixel band of R = 0.05, 0.015 over the 2-pixel band of
    // R = 0.01); the uncorrected deficit of both bands is 0.21, far beyond either.
    for (r, bound) in [(0.05, 0.03), (0.01, 0.06)] {
        let (got, uncorrected) = (deficit(r), analytic(r));
        eprintln!("edge band deficit R={r}: measured {got:.4}, uncorrected {uncorrected:.4}");
        assert!(got.abs() < bound, "R={r}: the edge band is {got} darker");
        assert!(uncorrected > 3.0 * bound, "{uncorrected}");
    }
}

fn point_light_scene(radius: f64, alpha: f64) -> String {
    format!(
        r#"
[film]
bins = 4
[camera]
type = "orthographic"
width = 8
height = 8
position = [0, 3, 0]
look_at = [0, 0, 0]
up = [0, 0, -1]
view_width = 0.2
view_height = 0.2
[integrator]
direct = "photons"
radius = {radius}
alpha = {alpha}
forward_rays = 100000
[materials.floor]
type = "lambert"
albedo = 0.5
[[shapes]]
type = "quad"
size = [6, 6]
material = "floor"
transform = {{ rotate = [-90, 0, 0] }}
[[lights]]
type = "point"
position = [0, 0.5, 0]
power = 10.0
spectrum = 1.0
"#
    )
}

/// Irradiance under a point light of intensity I at height h: E = I cos^3(theta) / h^2.
/// The estimate at a point is E averaged over the sphere's disc; with R = 0.15 that blur is a
/// clear negative bias at the peak, which the test predicts by quadrature, and progressive
/// radius reduction removes.
#[test]
fn point_light_above_plane_and_progressive_radius() {
    let h = 0.5f64;
    let intensity_per_nm = 10.0 / (4.0 * PI) / 400.0;
    let rho = 0.5;
    let irradiance = |x: f64, z: f64| intensity_per_nm * h / (h * h + x * x + z * z).powf(1.5);
    // Mean over the viewed square [-0.1, 0.1]^2 of E blurred by a disc of radius r.
    let expected = |r: f64| {
        let (m, k) = (40, 24);
        let mut acc = 0.0;
        for i in 0..m {
            for j in 0..m {
                let x = -0.1 + 0.2 * (i as f64 + 0.5) / m as f64;
                let z = -0.1 + 0.2 * (j as f64 + 0.5) / m as f64;
                if r == 0.0 {
                    acc += irradiance(x, z);
                    continue;
                }
                let mut disc = 0.0;
                for a in 0..k {
                    for b in 0..k {
                        // Uniform disc samples on a polar grid (area-weighted radii).
                        let rr = r * ((a as f64 + 0.5) / k as f64).sqrt();
                        let phi = 2.0 * PI * (b as f64 + 0.5) / k as f64;
                        disc += irradiance(x + rr * phi.cos(), z + rr * phi.sin());
                    }
                }
                acc += disc / (k * k) as f64;
            }
        }
        rho / PI * acc / (m * m) as f64
    };
    let exact = expected(0.0);
    let blurred = expected(0.15);
    eprintln!(
        "exact {exact:.6e}, blurred by R=0.15 {blurred:.6e} ({:.2}% low)",
        100.0 * (1.0 - blurred / exact)
    );

    // Fixed small radius: unbiased up to a tiny blur.
    let s = scene(&point_light_scene(0.01, 1.0), &[]);
    let (mean, se) = independent_estimates(&s, 6, 2, (0, 8, 0, 8));
    let small = expected(0.01);
    assert_bins("point R=0.01", &mean, &se, &[small; 4], Z, 0.0);

    // Fixed large radius: the estimate matches the blurred value, not the exact one.
    let s = scene(&point_light_scene(0.15, 1.0), &[]);
    let (mean, se) = independent_estimates(&s, 6, 2, (0, 8, 0, 8));
    assert_bins("point R=0.15 blurred", &mean, &se, &[blurred; 4], Z, 0.0);
    let z_exact = (mean[0] - exact) / se[0];
    assert!(
        z_exact < -6.0,
        "a large fixed radius must be measurably biased (z = {z_exact})"
    );

    // Progressive reduction from the same radius (alpha = 0.3): R^2 after p passes is about
    // p^-0.7 of the start, and the blur bias (second order in R) falls with it; averaged over
    // 100 passes the expected bias is about 0.15 of the fixed-radius one.
    let s = scene(
        &point_light_scene(0.15, 0.3),
        &["integrator.forward_rays=20000"],
    );
    let img = render(&s, 3, 100);
    let prog = region_mean(&img, &img.data, 0, 8, 0, 8)[0];
    let bias_fixed = exact - blurred;
    let bias_prog = exact - prog;
    eprintln!("bias fixed {bias_fixed:.3e}, progressive {bias_prog:.3e}");
    assert!(
        bias_prog.abs() < 0.5 * bias_fixed,
        "progressive radius must shrink the bias"
    );
}

/// A parallel beam turned down by a 45-degree mirror onto a floor: the forward rays pass the
/// specular bounce and are gathered at the diffuse receiver, L = rho R_m E / pi (the value of a
/// floor lit directly by the reflected beam).
#[test]
fn mirror_caustic_conserves_energy() {
    let text = r#"
[film]
bins = 4
[camera]
type = "orthographic"
width = 8
height = 8
position = [-2, 2, 0]
look_at = [0, 0, 0]
view_width = 0.12
view_height = 0.12
[integrator]
direct = "photons"
radius = 0.01
forward_rays = 200000
[materials.floor]
type = "lambert"
albedo = 0.6
[materials.mirror]
type = "mirror"
albedo = 0.9
[[shapes]]
type = "quad"
size = [4, 4]
material = "floor"
transform = { rotate = [-90, 0, 0] }
[[shapes]]
type = "quad"
size = [0.5, 0.5]
material = "mirror"
transform = { rotate = [0, -90, 45], translate = [0, 1, 0] }
[[lights]]
type = "directional"
direction = [1, 0, 0]
irradiance = 4.0
spectrum = 1.0
"#;
    let s = scene(text, &[]);
    let expected = 0.6 * 0.9 * (4.0 / 400.0) / PI;
    let (mean, se) = independent_estimates(&s, 6, 2, (0, 8, 0, 8));
    assert_bins("caustic", &mean, &se, &[expected; 4], Z, 0.0);
}

/// The same seed renders the same bits with 1 and 2 threads.
#[test]
fn deterministic_across_thread_counts() {
    let text = point_light_scene(0.05, 0.7);
    let s = scene(&text, &["integrator.forward_rays=30000"]);
    let run = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .expect("pool");
        pool.install(|| render(&s, 42, 3))
    };
    let a = run(1);
    let b = run(2);
    let bits =
        |img: &brume::film::SpectralImage| img.data.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
    assert_eq!(bits(&a), bits(&b));
    let c = pool_other_seed(&s);
    assert_ne!(
        bits(&a),
        bits(&c),
        "a different seed must give a different image"
    );
}

fn pool_other_seed(s: &Setup) -> brume::film::SpectralImage {
    render(s, 43, 3)
}

/// A diffuse furnace: a point light of power P at the centre of a closed Lambert sphere of
/// radius 1 and albedo 0.8, seen from the centre. Every bounce inside a sphere spreads the
/// reflected light uniformly, so the wall's radiance is `rho / (1 - rho) * E1 / pi` with
/// `E1 = P / (4 pi)` (the integrating-sphere formula): 80 % of it has bounced at least twice,
/// and forward rays pass Russian roulette (survival `max flux / emitted flux`, from the second
/// event on) at almost every bounce. Dropping roulette's reweighting, or truncating the paths,
/// shows far beyond |z| = 4. Both direct-light modes.
#[test]
fn diffuse_furnace_with_russian_roulette() {
    let text = r#"
[film]
bins = 2
[camera]
type = "perspective"
width = 8
height = 8
position = [0, 0, 0]
look_at = [0, 0, 1]
fov = 30.0
[integrator]
radius = 0.02
forward_rays = 20000
max_depth = 400
[materials.white]
type = "lambert"
albedo = 0.8
[[shapes]]
type = "sphere"
radius = 1.0
material = "white"
[[lights]]
type = "point"
position = [0, 0, 0]
power = 100.0
spectrum = 1.0
"#;
    let rho = 0.8;
    let e1 = 100.0 / 400.0 / (4.0 * PI);
    let expected = rho / (1.0 - rho) * e1 / PI;
    for direct in ["nee", "photons"] {
        let s = scene(text, &[&format!("integrator.direct=\"{direct}\"")]);
        let (mean, se) = independent_estimates(&s, 6, 2, (0, 8, 0, 8));
        assert_bins(
            &format!("furnace {direct}"),
            &mean,
            &se,
            &[expected; 2],
            Z,
            0.003,
        );
    }
}

/// The noise layer (the film's standard error of each pixel's mean over its passes) agrees
/// with the spread of the same pixel between independent renders: over 64 pixels and 2 bins,
/// the mean ratio of the stated standard error to the measured one is 1 within 10 % (16
/// renders of 8 passes: each measured variance has 15 degrees of freedom, so the mean over
/// 128 ratios is known to about 3 %). Without the 1/passes it would be off by sqrt(8).
#[test]
fn noise_layer_matches_the_spread_of_independent_renders() {
    let s = scene(
        &point_light_scene(0.05, 1.0),
        &["integrator.forward_rays=5000"],
    );
    let runs: Vec<_> = (0..16).map(|r| render(&s, 300 + r, 8)).collect();
    let n = s.grid.n;
    let values = runs[0].data.len();
    let mut ratio = 0.0;
    for i in 0..values {
        let x: Vec<f64> = runs.iter().map(|img| img.data[i] as f64).collect();
        let m = x.iter().sum::<f64>() / x.len() as f64;
        let sd = (x.iter().map(|a| (a - m).powi(2)).sum::<f64>() / (x.len() - 1) as f64).sqrt();
        let stated: f64 = runs
            .iter()
            .map(|img| img.noise.as_ref().expect("noise layer")[i] as f64)
            .sum::<f64>()
            / runs.len() as f64;
        ratio += stated / sd;
    }
    let ratio = ratio / values as f64;
    eprintln!("stated / measured standard error over {values} values ({n} bins): {ratio:.3}");
    assert!(
        (ratio - 1.0).abs() < 0.1,
        "noise layer off: ratio {ratio:.3}"
    );
}
