//! The paper's estimators inside the render engine: a cube of chromatic fog under a parallel
//! light, seen by an orthographic camera (the setting of the paper's Figure 4). Fixed seeds;
//! per-bin comparisons with stated z-bounds. The scene pins `direct = "photons"` (the paper's
//! pure method); the next-event tests set `integrator.direct=nee`.

mod common;
#[path = "engine_media/forward_scattering.rs"]
mod forward_scattering;

use std::f64::consts::PI;

use brume::film::SpectralImage;
use brume::integrator::Budget;
use brume::spectrum::{SpectralGrid, power_law};
use common::*;

const Z: f64 = 4.0;
const BINS: usize = 4;

/// sigma_s = 1.5 (lambda/550)^-4 per m (Rayleigh-like: 6.6 /m in the first bin, 0.4 /m in the
/// last), sigma_a = 0.2 /m, g = 0.5, in the cube [-0.5, 0.5]^3; light travelling along
/// (0.5, -0.5, -0.7071); camera looking along -Z at the central 0.4 x 0.4 m.
fn fog_text(extra: &str) -> String {
    format!(
        r#"
[film]
bins = {BINS}
[camera]
type = "orthographic"
width = 8
height = 8
position = [0, 0, 3]
look_at = [0, 0, 0]
view_width = 0.4
view_height = 0.4
[integrator]
radius = 0.01
forward_rays = 100000
direct = "photons"
{extra}
[spectra.rayleigh]
power_law = {{ k = 1.5, p = 4.0 }}
[media.fog]
sigma_s = "rayleigh"
sigma_a = 0.2
g = 0.5
[[shapes]]
type = "box"
size = [1, 1, 1]
interior = "fog"
[[lights]]
type = "directional"
direction = [0.5, -0.5, -0.70710678]
irradiance = 4.0
spectrum = 1.0
"#
    )
}

fn grid() -> SpectralGrid {
    SpectralGrid::new(BINS, 380.0, 780.0)
}

fn sigma_s() -> Vec<f64> {
    let s = power_law(1.5, 550.0, 4.0, &grid());
    (0..BINS).map(|b| s[b] as f64).collect()
}

fn hg(g: f64, cos: f64) -> f64 {
    (1.0 - g * g) / (4.0 * PI * (1.0 + g * g - 2.0 * g * cos).powf(1.5))
}

fn light_dir() -> [f64; 3] {
    let d = [0.5f64, -0.5, -std::f64::consts::FRAC_1_SQRT_2];
    let l = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
    [d[0] / l, d[1] / l, d[2] / l]
}

/// Distance from `p` (inside the unit cube) to its boundary along `dir`.
fn exit_distance(p: [f64; 3], dir: [f64; 3]) -> f64 {
    (0..3)
        .map(|i| {
            if dir[i] > 0.0 {
                (0.5 - p[i]) / dir[i]
            } else if dir[i] < 0.0 {
                (-0.5 - p[i]) / dir[i]
            } else {
                f64::INFINITY
            }
        })
        .fold(f64::INFINITY, f64::min)
}

/// Single-scattering radiance averaged over the viewed square, per bin, by quadrature:
/// L = int_0^1 e^{-st s} ss p(cos) E e^{-st l(x(s))} ds with l the light's path inside the cube.
fn single_scattering() -> Vec<f64> {
    single_scattering_of(true)
}

/// `single_scattering` of the Rayleigh fog (`chromatic`) or of a grey fog with sigma_s = 0.8.
fn single_scattering_of(chromatic: bool) -> Vec<f64> {
    let ss = if chromatic {
        sigma_s()
    } else {
        vec![0.8; BINS]
    };
    let d = light_dir();
    let e = 4.0 / 400.0;
    // Light travels along d; it turns towards the camera (+Z): cos = d . (0, 0, 1).
    let phase = hg(0.5, d[2]);
    let (m, k) = (24, 400);
    (0..BINS)
        .map(|b| {
            let st = ss[b] + 0.2;
            let mut acc = 0.0;
            for i in 0..m {
                for j in 0..m {
                    let x = -0.2 + 0.4 * (i as f64 + 0.5) / m as f64;
                    let y = -0.2 + 0.4 * (j as f64 + 0.5) / m as f64;
                    for q in 0..k {
                        let s = (q as f64 + 0.5) / k as f64;
                        let p = [x, y, 0.5 - s];
                        let l = exit_distance(p, [-d[0], -d[1], -d[2]]);
                        acc += (-st * s).exp() * ss[b] * phase * e * (-st * l).exp() / k as f64;
                    }
                }
            }
            acc / (m * m) as f64
        })
        .collect()
}

/// Every integration volume of `integrator.volume` (and q) matches the analytic single-scattering
/// radiance (forward rays stop at their first collision: max_depth = 1). The 1% floor covers the
/// kernel blur and the spheres cut off at the cube's faces (method note 8), both O(R).
#[test]
fn all_volumes_match_analytic_single_scattering() {
    let expected = single_scattering();
    let mut cases: Vec<(String, Vec<String>)> = Vec::new();
    // Channel-averaged unbiasedness: every bin, for q in {1, 0.3, 0.05} and both channel picks.
    for q in ["1", "0.3", "0.05"] {
        for pick in ["throughput", "uniform"] {
            cases.push((
                format!("spheres q={q} {pick}"),
                vec![
                    format!("integrator.q={q}"),
                    format!("integrator.channel_pick={pick}"),
                ],
            ));
        }
    }
    for volume in ["cylinder", "cylinder-truncated", "cylinder-long"] {
        cases.push((
            volume.to_string(),
            vec![format!("integrator.volume={volume}")],
        ));
    }
    // The Sobol sampler: forward rays (stratified emission, first flight and scattering) and
    // camera paths (stratified pixel positions and first segments).
    for q in ["1", "0.3"] {
        cases.push((
            format!("spheres q={q} sobol"),
            vec![
                format!("integrator.q={q}"),
                "integrator.sampler=\"sobol\"".to_string(),
            ],
        ));
    }
    for (name, sets) in cases {
        let mut sets: Vec<&str> = sets.iter().map(String::as_str).collect();
        sets.push("integrator.max_depth=1");
        let s = scene(&fog_text(""), &sets);
        let (mean, se) = independent_estimates(&s, 5, 2, (0, 8, 0, 8));
        assert_bins(&name, &mean, &se, &expected, Z, 0.01);
    }
}

/// Full multiple scattering against two independent simulations written here, which must agree
/// with each other: analog photons from the light, per bin, with a next-event estimate towards
/// the camera at every collision inside the viewed column, and the backward path tracer of
/// `forward_scattering` (its standard error 5-10x smaller, the one the estimators are held to).
#[test]
fn multiple_scattering_matches_brute_force() {
    use rand::{Rng, SeedableRng};
    let ss = sigma_s();
    let d = light_dir();
    let e = 4.0 / 400.0;
    // Photons start on a disc of radius 0.9 normal to d, behind the cube.
    let radius = 0.9f64;
    let (t1, t2) = {
        let a = if d[0].abs() < 0.9 {
            [1.0, 0.0, 0.0]
        } else {
            [0.0, 1.0, 0.0]
        };
        let c = [
            d[1] * a[2] - d[2] * a[1],
            d[2] * a[0] - d[0] * a[2],
            d[0] * a[1] - d[1] * a[0],
        ];
        let l = (c[0] * c[0] + c[1] * c[1] + c[2] * c[2]).sqrt();
        let t1 = [c[0] / l, c[1] / l, c[2] / l];
        let t2 = [
            d[1] * t1[2] - d[2] * t1[1],
            d[2] * t1[0] - d[0] * t1[2],
            d[0] * t1[1] - d[1] * t1[0],
        ];
        (t1, t2)
    };
    let photons = 400_000;
    let batches = 8;
    let area = 0.4 * 0.4;
    let mut samples: Vec<Vec<f64>> = vec![vec![0.0; BINS]; batches];
    let mut rng = rand_pcg::Pcg64Mcg::seed_from_u64(99);
    for (bi, batch) in samples.iter_mut().enumerate() {
        let _ = bi;
        for (b, slot) in batch.iter_mut().enumerate() {
            let st = ss[b] + 0.2;
            let albedo = ss[b] / st;
            let flux = e * PI * radius * radius / photons as f64;
            let mut acc = 0.0;
            for _ in 0..photons {
                let r = radius * rng.random::<f64>().sqrt();
                let phi = 2.0 * PI * rng.random::<f64>();
                let (a, c) = (r * phi.cos(), r * phi.sin());
                let mut p = [
                    -2.0 * d[0] + a * t1[0] + c * t2[0],
                    -2.0 * d[1] + a * t1[1] + c * t2[1],
                    -2.0 * d[2] + a * t1[2] + c * t2[2],
                ];
                // Enter the cube (slab test).
                let mut tmin = 0.0f64;
                let mut tmax = f64::INFINITY;
                for i in 0..3 {
                    let (lo, hi) = ((-0.5 - p[i]) / d[i], (0.5 - p[i]) / d[i]);
                    tmin = tmin.max(lo.min(hi));
                    tmax = tmax.min(lo.max(hi));
                }
                if tmin >= tmax {
                    continue;
                }
                for i in 0..3 {
                    p[i] += d[i] * (tmin + 1e-9);
                }
                let mut dir = d;
                let mut w = 1.0;
                for _ in 0..200 {
                    let s = -(1.0 - rng.random::<f64>()).ln() / st;
                    if s >= exit_distance(p, dir) {
                        break;
                    }
                    for i in 0..3 {
                        p[i] += dir[i] * s;
                    }
                    w *= albedo;
                    if p[0].abs() < 0.2 && p[1].abs() < 0.2 {
                        // Scattered towards the camera (+Z), attenuated to the front face.
                        acc += w * st * hg(0.5, dir[2]) * (-st * (0.5 - p[2])).exp();
                    }
                    if w < 1e-4 {
                        break;
                    }
                    // Henyey-Greenstein sampling around dir.
                    let g = 0.5;
                    let u = rng.random::<f64>();
                    let sq = (1.0 - g * g) / (1.0 - g + 2.0 * g * u);
                    let cos = (1.0 + g * g - sq * sq) / (2.0 * g);
                    let sin = (1.0 - cos * cos).max(0.0).sqrt();
                    let ph = 2.0 * PI * rng.random::<f64>();
                    let a = if dir[0].abs() < 0.9 {
                        [1.0, 0.0, 0.0]
                    } else {
                        [0.0, 1.0, 0.0]
                    };
                    let mut u1 = [
                        dir[1] * a[2] - dir[2] * a[1],
                        dir[2] * a[0] - dir[0] * a[2],
                        dir[0] * a[1] - dir[1] * a[0],
                    ];
                    let l = (u1[0] * u1[0] + u1[1] * u1[1] + u1[2] * u1[2]).sqrt();
                    u1 = [u1[0] / l, u1[1] / l, u1[2] / l];
                    let u2 = [
                        dir[1] * u1[2] - dir[2] * u1[1],
                        dir[2] * u1[0] - dir[0] * u1[2],
                        dir[0] * u1[1] - dir[1] * u1[0],
                    ];
                    for i in 0..3 {
                        dir[i] = cos * dir[i] + sin * (ph.cos() * u1[i] + ph.sin() * u2[i]);
                    }
                }
            }
            // Collision density x (ss/st) x albedo-weighted flux: the weight already holds the
            // albedo of this collision, so the emission density is w * st * p / st = w * p.
            *slot = acc * flux / st / area;
        }
    }
    let (photons_ref, photons_se) = mean_and_se(&samples, BINS);
    // A second reference, its error 1.6-3.5x smaller (a backward path tracer): the estimators are held
    // to it. Held to the photon reference above (0.24-0.35 %, shared by every row), eq. 2
    // cylinders, whose own error is as small, sat at z = -1.9 to -2.0 in three bins: that
    // reference is 0.3-0.7 % high there. Over 480 renders eq. 2 agrees with a backward
    // reference of 8 M paths per bin within 0.25 % (docs/study.md, "Strong forward scattering").
    let (reference, ref_se): (Vec<f64>, Vec<f64>) = (0..BINS)
        .map(|b| {
            forward_scattering::backward_reference(ss[b], 0.2, 0.5, 0.2, 125_000, 40 + b as u64)
        })
        .unzip();
    let both: Vec<f64> = (0..BINS)
        .map(|b| (photons_se[b].powi(2) + ref_se[b].powi(2)).sqrt())
        .collect();
    assert_bins(
        "photon vs path reference",
        &photons_ref,
        &both,
        &reference,
        Z,
        0.0,
    );
    for (name, sets) in [
        ("spheres q=1", vec!["integrator.q=1"]),
        ("spheres q=0.1", vec!["integrator.q=0.1"]),
        ("cylinder eq.2", vec!["integrator.volume=cylinder"]),
    ] {
        let s = scene(&fog_text(""), &sets);
        let (mean, se) = independent_estimates(&s, 12, 2, (0, 8, 0, 8));
        let combined: Vec<f64> = se
            .iter()
            .zip(&ref_se)
            .map(|(a, b)| (a * a + b * b).sqrt())
            .collect();
        assert_bins(name, &mean, &combined, &reference, Z, 0.01);
    }
}

/// The measured mean number of spheres per camera segment matches (1/q) sum_l P_l (1 - e^{-st_l T})
/// (method note 2); here P is uniform (throughput 1 with a floor), T = 1 m.
#[test]
fn spheres_per_segment_match_the_formula() {
    let q = 0.1;
    let s = scene(
        &fog_text(""),
        &[
            &format!("integrator.q={q}"),
            "camera.width=128",
            "camera.height=128",
            "integrator.forward_rays=1000",
        ],
    );
    let ss = sigma_s();
    let expected: f64 = (0..BINS)
        .map(|b| (1.0 - (-(ss[b] + 0.2)).exp()) / BINS as f64)
        .sum::<f64>()
        / q;
    let mut r = s.renderer(5);
    r.run(Budget::Passes(1), |_, _| {});
    let got = r.stats.volume_records as f64 / r.stats.camera_paths as f64;
    eprintln!("spheres per segment: measured {got:.4}, formula {expected:.4}");
    // 16384 paths; the count per path has a standard deviation of about 1/q, so the standard
    // error of the mean is under 0.08: 0.3 is about 4 sigma.
    assert!((got - expected).abs() < 0.3, "{got} vs {expected}");
}

/// first-extinction and see-through count every light path once: they agree on fog in front of
/// a diffuse textured wall (full multiple scattering).
#[test]
fn first_extinction_and_see_through_agree() {
    let wall = r#"
[materials.wall]
type = "lambert"
albedo = 0.6
texture = "textures/brume-pattern.png"
[[shapes]]
type = "quad"
size = [1.0, 1.0]
material = "wall"
transform = { translate = [0.0, 0.0, -0.5002] }
"#;
    let text = fog_text("") + wall;
    let mut results = Vec::new();
    for mode in ["first-extinction", "see-through"] {
        let s = scene(
            &text,
            &[&format!("integrator.mode={mode}"), "integrator.q=0.3"],
        );
        results.push(independent_estimates(&s, 6, 2, (0, 8, 0, 8)));
    }
    let (a, sa) = &results[0];
    let (b, sb) = &results[1];
    let combined: Vec<f64> = sa
        .iter()
        .zip(sb)
        .map(|(x, y)| (x * x + y * y).sqrt())
        .collect();
    assert_bins("see-through vs first-extinction", b, &combined, a, Z, 0.0);
}

/// A memory budget smaller than one pass's records splits the pass into tiles of rows, each with
/// its own gather structure and light pass, instead of failing; every tile stays within the
/// budget (issue 31: tiles were checked only after batches of 8 rows, so a pass overshot it by
/// up to a batch); the estimate stays unbiased.
#[test]
fn memory_budget_splits_passes_into_tiles() {
    let expected = single_scattering();
    // Fixed budgets: automatic ones would render pilot passes, whose tiles and gathers the
    // stats would count too.
    let sets = [
        "integrator.q=0.3",
        "integrator.forward_rays=50000",
        "integrator.camera_samples=1",
        "integrator.max_depth=1",
        "camera.width=32",
        "camera.height=32",
    ];
    let whole = scene(&fog_text(""), &sets);
    let mut r = whole.renderer(9);
    r.run(Budget::Passes(1), |_, _| {});
    let (full, kept) = (r.stats.peak_build_bytes, r.stats.peak_gather_bytes);
    // A budget of a fifth of the pass: 5 or 6 tiles of whole rows.
    let budget = full / 5;
    let set = format!("integrator.max_gather_bytes={budget}");
    let s = scene(&fog_text(""), &[&sets[..], &[set.as_str()]].concat());
    let mut r = s.renderer(9);
    r.run(Budget::Passes(1), |_, _| {});
    eprintln!(
        "untiled peak {full} bytes; tiled: {} tiles, peak {} bytes (budget {budget})",
        r.stats.tiles, r.stats.peak_build_bytes
    );
    assert!((5..=7).contains(&r.stats.tiles), "{} tiles", r.stats.tiles);
    assert!(r.stats.peak_build_bytes <= budget);
    assert!(r.stats.peak_gather_bytes < kept / 3);
    let (mean, se) = independent_estimates(&s, 5, 2, (0, 32, 0, 32));
    assert_bins("tiled q=0.3", &mean, &se, &expected, Z, 0.01);
}

/// Per-pixel, per-bin variance across `runs` independent renders of `passes` passes, averaged
/// over the pixels, per bin.
fn pixel_variance(s: &Setup, runs: u64, passes: u32) -> Vec<f64> {
    let imgs: Vec<_> = (0..runs).map(|r| render(s, 500 + r, passes)).collect();
    let n = s.grid.n;
    let pixels = imgs[0].data.len() / n;
    let mut var = vec![0.0; n];
    for p in 0..pixels {
        for (b, v) in var.iter_mut().enumerate() {
            let x: Vec<f64> = imgs.iter().map(|i| i.data[p * n + b] as f64).collect();
            let m = x.iter().sum::<f64>() / runs as f64;
            *v += x.iter().map(|a| (a - m).powi(2)).sum::<f64>() / (runs - 1) as f64;
        }
    }
    var.iter().map(|v| v / pixels as f64).collect()
}

/// Next-event estimation alone (forward rays deposit nothing on their first flight and stop at
/// their first collision: max_depth = 1) matches the closed-form single scattering in every
/// bin with no kernel allowance (|z| <= 4), in the chromatic cube and in the grey one of
/// scenes/fog-cube.toml (sigma_s = 0.8, sigma_a = 0.2).
#[test]
fn nee_matches_analytic_single_scattering() {
    for (name, extra) in [("chromatic", None), ("grey", Some("media.fog.sigma_s=0.8"))] {
        let expected = single_scattering_of(extra.is_none());
        let mut sets = vec!["integrator.direct=nee", "integrator.max_depth=1"];
        sets.extend(extra);
        let nee = scene(&fog_text(""), &sets);
        let (mean, se) = independent_estimates(&nee, 6, 2, (0, 8, 0, 8));
        assert_bins(&format!("nee {name}"), &mean, &se, &expected, Z, 0.0);
    }
}

/// At equal passes, NEE's per-pixel variance of single scattering is at least 10x lower than
/// the gathered estimate's in the grey cube (measured 113x). In the chromatic cube one
/// distance density serves bins whose extinctions differ 11-fold; at one NEE sample per segment
/// the extreme bins gain only ~3x (asserted >= 2.5x); at 4 samples, stratified over distance
/// and over the bins the density picks, every bin gains >= 10x (measured 66x to 272x).
#[test]
fn nee_has_ten_times_less_variance_than_gathered_single_scattering() {
    let cases: [(&str, &[&str], f64); 3] = [
        ("grey", &["media.fog.sigma_s=0.8"], 10.0),
        ("chromatic", &[], 2.5),
        (
            "chromatic, 4 NEE samples",
            &["integrator.nee_samples=4"],
            10.0,
        ),
    ];
    for (name, extra, bound) in cases {
        // Independent numbers: the claim is about the estimators. The Sobol sampler lowers
        // both, the photons' more (30 runs, chromatic bin 0: photons 16x, NEE 5x lower), so
        // their ratio is the sampler's as much as the estimators'.
        // Fixed q and camera paths: the same passes for both estimators. Left automatic, each
        // variant's pilots chose its own, and the ratio measured the choices as much as the
        // estimators.
        let mut sets = vec![
            "integrator.max_depth=1",
            "integrator.sampler=\"independent\"",
            "integrator.q=1",
            "integrator.camera_samples=1",
        ];
        sets.extend(extra);
        let photons = scene(&fog_text(""), &sets);
        sets.push("integrator.direct=nee");
        let nee = scene(&fog_text(""), &sets);
        let (vn, vp) = (pixel_variance(&nee, 6, 2), pixel_variance(&photons, 6, 2));
        let bins = if name == "grey" { 1 } else { BINS };
        for b in 0..bins {
            let ratio = vp[b] / vn[b];
            eprintln!(
                "{name} bin {b}: per-pixel variance photons {:.3e}, nee {:.3e}, ratio {ratio:.1}",
                vp[b], vn[b]
            );
            assert!(
                ratio >= bound,
                "{name} bin {b}: variance ratio only {ratio:.2}"
            );
        }
    }
}

/// The fog cube of scenes/fog-cube.toml (grey fog sigma_s = 0.8, sigma_a = 0.2, g = 0.5, a wall
/// of albedo 0.4 just behind its back face, a parallel light at 45 degrees), 64 x 64 pixels
/// over exactly the 1 m wall, so that the outermost pixels' surface spheres reach past the
/// wall's edges.
fn wall_text(texture: bool) -> String {
    let tex = if texture {
        "texture = \"textures/brume-pattern.png\""
    } else {
        ""
    };
    format!(
        r#"
[film]
bins = 2
[camera]
type = "orthographic"
width = 64
height = 64
position = [0, 0, 3]
look_at = [0, 0, 0]
view_width = 1.0
view_height = 1.0
[integrator]
radius = 0.01
forward_rays = 100000
camera_samples = 4
max_depth = 1
[media.fog]
sigma_s = 0.8
sigma_a = 0.2
g = 0.5
[materials.wall]
type = "lambert"
albedo = 0.4
{tex}
[[shapes]]
type = "box"
size = [1, 1, 1]
interior = "fog"
[[shapes]]
type = "quad"
size = [1, 1]
material = "wall"
transform = {{ translate = [0, 0, -0.5002] }}
[[lights]]
type = "directional"
direction = [0.5, -0.5, -0.70710678]
irradiance = 4.0
spectrum = 1.0
"#
    )
}

/// Single scattering of `wall_text(false)` at (x, y): the fog along the camera ray plus the
/// wall's direct light seen through the cube.
fn wall_single_scattering(x: f64, y: f64) -> f64 {
    let d = light_dir();
    let e = 4.0 / 400.0;
    let (ss, st) = (0.8, 1.0);
    let phase = hg(0.5, d[2]);
    let back = [-d[0], -d[1], -d[2]];
    let k = 200;
    let mut fog = 0.0;
    for q in 0..k {
        let s = (q as f64 + 0.5) / k as f64;
        let l = exit_distance([x, y, 0.5 - s], back);
        fog += (-st * s).exp() * ss * phase * e * (-st * l).exp() / k as f64;
    }
    let lit = exit_distance([x, y, -0.5], back);
    let wall = (-st * 1.0f64).exp() * 0.4 / PI * e * (-d[2]) * (-st * lit).exp();
    fog + wall
}

/// Means over the outermost ring of pixels (`ring` = 1) or the 2-pixel border (`ring` = 2).
fn border_mean(img: &SpectralImage, data: &[f32], ring: usize) -> f64 {
    let (w, h, n) = (img.width, img.height, img.grid.n);
    let (mut acc, mut count) = (0.0, 0);
    for y in 0..h {
        for x in 0..w {
            if x < ring || y < ring || x >= w - ring || y >= h - ring {
                acc += data[(y * w + x) * n] as f64;
                count += 1;
            }
        }
    }
    acc / count as f64
}

/// The expected border means of `wall_single_scattering`, 4 x 4 points per pixel.
fn expected_border(ring: usize) -> f64 {
    let (w, sub) = (64usize, 4usize);
    let (mut acc, mut count) = (0.0, 0);
    for py in 0..w {
        for px in 0..w {
            if px >= ring && py >= ring && px < w - ring && py < w - ring {
                continue;
            }
            let mut v = 0.0;
            for i in 0..sub {
                for j in 0..sub {
                    let x = -0.5 + (px as f64 + (i as f64 + 0.5) / sub as f64) / w as f64;
                    let y = 0.5 - (py as f64 + (j as f64 + 0.5) / sub as f64) / w as f64;
                    v += wall_single_scattering(x, y);
                }
            }
            acc += v / (sub * sub) as f64;
            count += 1;
        }
    }
    acc / count as f64
}

/// Surface spheres at a wall's edges (issue 19): divided by the part of their disc on the wall,
/// the outermost pixel row and the 2-pixel border agree with the analytic single scattering
/// (|z| <= 4), with direct light gathered by the spheres (`photons`) and by next-event
/// estimation (the default). Without the correction the outermost ring was about 20 % dark.
/// On the textured wall the two modes agree with each other at the border (NEE's wall light
/// has no kernel, so it is an independent reference there).
#[test]
fn wall_edges_are_not_darkened() {
    for ring in [1, 2] {
        let expected = expected_border(ring);
        for direct in ["photons", "nee"] {
            let s = scene(
                &wall_text(false),
                &[&format!("integrator.direct=\"{direct}\"")],
            );
            let samples: Vec<Vec<f64>> = (0..6)
                .map(|r| {
                    let img = render(&s, 40 + r, 2);
                    vec![border_mean(&img, &img.data, ring)]
                })
                .collect();
            let (mean, se) = mean_and_se(&samples, 1);
            assert_bins(
                &format!("ring {ring} {direct}"),
                &mean,
                &se,
                &[expected],
                Z,
                0.0,
            );
        }
    }
    let mut by_mode = Vec::new();
    for direct in ["photons", "nee"] {
        let s = scene(
            &wall_text(true),
            &[&format!("integrator.direct=\"{direct}\"")],
        );
        let samples: Vec<Vec<f64>> = (0..6)
            .map(|r| {
                let img = render(&s, 60 + r, 2);
                vec![border_mean(&img, &img.data, 1)]
            })
            .collect();
        by_mode.push(mean_and_se(&samples, 1));
    }
    let ((a, sa), (b, sb)) = (&by_mode[0], &by_mode[1]);
    let z = (a[0] - b[0]) / (sa[0].powi(2) + sb[0].powi(2)).sqrt();
    eprintln!(
        "textured wall, outermost ring: photons {:.5e} nee {:.5e} (z {z:.2})",
        a[0], b[0]
    );
    assert!(
        z.abs() <= Z,
        "textured wall border: photons vs nee z = {z:.2}"
    );
}

/// A phase function that differs per spectral bin (a per-wavelength table: Henyey-Greenstein
/// with g from 0.1 at 380 nm to 0.85 at 780 nm, tabulated every 0.5 degrees) in the grey cube:
/// per-bin single scattering matches the closed form with each bin's own phase value (as the
/// built medium evaluates it) within |z| <= 4 (1 % kernel floor), for spheres at q = 1 and 0.3
/// and eq. 2 cylinders (the paper's estimators, `direct = "photons"`) and for next-event
/// estimation. A renderer that used one phase for all bins is off by tens of percent here.
#[test]
fn per_bin_phase_single_scattering() {
    let dir = tempfile::tempdir().expect("temp dir");
    let waves = [380.0f64, 480.0, 580.0, 680.0, 780.0];
    let g_of = |w: f64| 0.1 + 0.75 * (w - 380.0) / 400.0;
    let mut csv = String::from("angle");
    for w in waves {
        csv += &format!(",{w}");
    }
    csv += "\n";
    for i in 0..=360 {
        let deg = i as f64 * 0.5;
        csv += &format!("{deg}");
        for w in waves {
            csv += &format!(",{:.9e}", hg(g_of(w), deg.to_radians().cos()));
        }
        csv += "\n";
    }
    std::fs::write(dir.path().join("phase.csv"), csv).expect("write table");
    let text = fog_text("").replace(
        "g = 0.5",
        &format!(
            "phase = {{ type = \"tabulated\", file = \"{}\" }}",
            dir.path().join("phase.csv").display()
        ),
    );
    let d = light_dir();
    let grey = |sets: &[&str]| {
        let mut all = vec!["media.fog.sigma_s=0.8", "integrator.max_depth=1"];
        all.extend(sets);
        scene(&text, &all)
    };
    let probe = grey(&[]);
    let phase = probe.media[0].phase_bins(d[2] as f32);
    let flat = single_scattering_of(false);
    let at_half = hg(0.5, d[2]);
    // single_scattering_of uses HG g = 0.5: rescale each bin to its own phase value.
    let expected: Vec<f64> = (0..BINS)
        .map(|b| flat[b] * phase[b] as f64 / at_half)
        .collect();
    eprintln!("per-bin phase at the view: {:?}", &phase.0[..BINS]);
    assert!(phase[0] > 2.0 * phase[BINS - 1], "the bins' phases differ");
    let cases: [(&str, &[&str]); 4] = [
        ("spheres q=1", &["integrator.direct=\"photons\""]),
        (
            "spheres q=0.3",
            &["integrator.direct=\"photons\"", "integrator.q=0.3"],
        ),
        (
            "cylinder",
            &[
                "integrator.direct=\"photons\"",
                "integrator.volume=\"cylinder\"",
            ],
        ),
        ("nee", &["integrator.direct=\"nee\""]),
    ];
    for (name, sets) in cases {
        let s = grey(sets);
        let (mean, se) = independent_estimates(&s, 5, 2, (0, 8, 0, 8));
        assert_bins(
            &format!("per-bin phase, {name}"),
            &mean,
            &se,
            &expected,
            Z,
            0.01,
        );
    }
}

#[path = "engine_media/sensors.rs"]
mod sensors;
