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

/// A glossy floor under an area light (an emitting quad), seen where the light's reflection
/// is: with `direct = "photons"` the camera paths' glossy samples that hit the emitter carry its
/// reflection and surface spheres its diffuse light; with `nee` light samples weighted against
/// the glossy samples by the power heuristic carry it, the samples that hit the emitter taking
/// the complementary weight. Both agree per bin (|z| <= 4), for a rough and a sharp coat, and
/// for a coat with no diffuse base (albedo 0) seen below the emitter, where nothing but the
/// coat's reflection is noisy: there the light samples' missing weight shows at z = 17 (over
/// the whole image with a diffuse base, only at z = 4.1 and 4.8). A missing or doubled weight on
/// either side fails.
#[test]
fn glossy_reflection_of_an_area_light_agrees_between_direct_modes() {
    let text = r#"
[film]
bins = 2
[camera]
type = "perspective"
width = 12
height = 12
position = [0, 1, 2]
look_at = [0, 0, 0]
fov = 50.0
[integrator]
radius = 0.03
forward_rays = 100000
camera_samples = 16
[materials.floor]
type = "glossy"
albedo = 0.05
ior = 1.5
roughness = 0.2
[[shapes]]
type = "quad"
size = [3, 3]
material = "floor"
transform = { rotate = [-90, 0, 0] }
[[shapes]]
type = "quad"
size = [0.8, 0.8]
emit = 1.0
transform = { rotate = [60, 0, 0], translate = [0, 0.8, -1.2] }
"#;
    let mut wrong = Vec::new();
    for (roughness, albedo) in [
        ("0.2", "0.05"),
        ("0.08", "0.05"),
        ("0.03", "0.05"),
        ("0.08", "0"),
    ] {
        let mut by_mode = Vec::new();
        for direct in ["nee", "photons"] {
            let s = scene(
                text,
                &[
                    &format!("integrator.direct=\"{direct}\""),
                    &format!("materials.floor.roughness={roughness}"),
                    &format!("materials.floor.albedo={albedo}"),
                ],
            );
            // Without a diffuse base, the rows below the emitter (rows 0-1 hold it, whose
            // edges' pixel coverage would be the noise): its reflection and the dark floor.
            let rows = if albedo == "0" { 3 } else { 0 };
            by_mode.push(independent_estimates(&s, 12, 2, (0, 12, rows, 12)));
        }
        let ((a, sa), (b, sb)) = (&by_mode[0], &by_mode[1]);
        for bin in 0..a.len() {
            let se = (sa[bin].powi(2) + sb[bin].powi(2)).sqrt();
            let z = (a[bin] - b[bin]) / se;
            eprintln!(
                "roughness {roughness} albedo {albedo} bin {bin}: nee {:.5e} +- {:.1e}, photons {:.5e} +- {:.1e} (z {z:.2})",
                a[bin], sa[bin], b[bin], sb[bin]
            );
            if z.abs() > Z {
                wrong.push(format!(
                    "roughness {roughness} albedo {albedo} bin {bin}: z = {z:.2}"
                ));
            }
        }
    }
    assert!(wrong.is_empty(), "{}", wrong.join("\n"));
}

/// A glossy floor straight under a point light, seen from above (orthographic): next-event
/// estimation reflects the light with the whole BSDF (the diffuse base and the coat), so the
/// image is `f(wo, wi) I cos / d^2` with `f` the material's own evaluation, pixel by pixel
/// (|z| <= 4 over the 8 x 8 image; forward rays deposit nothing here: max_depth = 1). The pure
/// photon method has no way to this highlight (a point light cannot be hit by a glossy
/// sample), so only `nee` is compared.
#[test]
fn glossy_highlight_of_a_point_light() {
    use brume::geometry::Hit;
    use brume::material::Material;
    use glam::{Vec2, Vec3};
    let text = r#"
[film]
bins = 2
[camera]
type = "orthographic"
width = 8
height = 8
position = [0, 3, 0]
look_at = [0, 0, 0]
up = [0, 0, -1]
view_width = 0.6
view_height = 0.6
[integrator]
radius = 0.01
forward_rays = 1000
max_depth = 1
camera_samples = 4
[materials.floor]
type = "glossy"
albedo = 0.3
ior = 1.5
roughness = 0.15
[[shapes]]
type = "quad"
size = [6, 6]
material = "floor"
transform = { rotate = [-90, 0, 0] }
[[lights]]
type = "point"
position = [0.1, 0.5, 0.05]
power = 10.0
spectrum = 1.0
"#;
    let material = Material::glossy(brume::spectrum::Spectrum::splat(0.3, 2), 1.5, 0.15, 2);
    let light = Vec3::new(0.1, 0.5, 0.05);
    let intensity = 10.0 / 400.0 / (4.0 * PI);
    let radiance = |x: f32, z: f32| {
        let p = Vec3::new(x, 0.0, z);
        let hit = Hit {
            t: 1.0,
            p,
            ng: Vec3::Y,
            ns: Vec3::Y,
            uv: Vec2::ZERO,
            shape: 0,
        };
        let d = light - p;
        let wi = d.normalize();
        let f = material.eval(Vec3::Y, wi, &hit)[0] as f64;
        f * intensity * wi.y as f64 / d.length_squared() as f64
    };
    let sub = 16;
    let expected: f64 = (0..8 * sub)
        .flat_map(|i| (0..8 * sub).map(move |j| (i, j)))
        .map(|(i, j)| {
            let x = -0.3 + 0.6 * (i as f32 + 0.5) / (8 * sub) as f32;
            let z = -0.3 + 0.6 * (j as f32 + 0.5) / (8 * sub) as f32;
            radiance(x, z)
        })
        .sum::<f64>()
        / (64 * sub * sub) as f64;
    let s = scene(text, &["integrator.direct=\"nee\""]);
    let (mean, se) = independent_estimates(&s, 6, 2, (0, 8, 0, 8));
    assert_bins("glossy highlight", &mean, &se, &[expected; 2], Z, 0.0);
    let diffuse_only: f64 = {
        let s = scene(
            text,
            &["integrator.direct=\"photons\"", "integrator.max_depth=32"],
        );
        independent_estimates(&s, 2, 2, (0, 8, 0, 8)).0[0]
    };
    eprintln!(
        "with the coat's highlight {expected:.4e}; photons (diffuse base only) {diffuse_only:.4e}"
    );
}

#[path = "engine_surfaces/sensors.rs"]
mod sensors;

#[path = "engine_surfaces/layers.rs"]
mod layers;
