//! Media with a density field (method note 10, docs/media.md): the paper's estimators in a
//! cube of chromatic fog whose density varies in space, under a parallel light, seen by an
//! orthographic camera, against single scattering integrated here by quadrature of the density
//! itself (not of brume's closed forms): per bin, |z| <= 4, for spheres (q = 1, 0.3 and 0.1)
//! with photons and with next-event estimation, in exponential height fog and in a fog bank.
//! Fixed seeds.

mod common;

use std::f64::consts::PI;

use brume::medium::density::grid::{GridData, vol};
use brume::spectrum::{SpectralGrid, power_law};
use common::*;
use glam::Vec3;

const Z: f64 = 4.0;
const BINS: usize = 4;

/// Height fog with its `up` tilted towards the camera, so that the density changes along the
/// camera rays as well as along the light's.
const HEIGHT: &str =
    r#"density = { type = "height", base = -0.5, scale_height = 0.5, up = [0.0, 0.6, 0.8] }"#;
/// A fog bank whose step crosses the cube.
const LAYER: &str =
    r#"density = { type = "layer", top = 0.1, transition = 0.5, up = [0.0, 0.8, 0.6] }"#;

/// The engine_media cube (Rayleigh-like sigma_s = 1.5 (lambda/550)^-4 /m, sigma_a = 0.2 /m at
/// density 1, g = 0.5; light along (0.5, -0.5, -0.7071); camera along -Z over the central
/// 0.4 x 0.4 m) with `density`.
fn fog_text(density: &str) -> String {
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
max_depth = 1
[spectra.rayleigh]
power_law = {{ k = 1.5, p = 4.0 }}
[media.fog]
sigma_s = "rayleigh"
sigma_a = 0.2
g = 0.5
{density}
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

fn unit(v: [f64; 3]) -> [f64; 3] {
    let l = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    [v[0] / l, v[1] / l, v[2] / l]
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// A 6 x 5 x 4 grid filling the cube (the `.vol` file's own box), with a few empty cells.
const GRID_RES: [usize; 3] = [6, 5, 4];

fn grid_value(i: usize, j: usize, k: usize) -> f64 {
    let v = 1.0 + 0.9 * (1.3 * i as f64 + 0.7 * j as f64 - 1.1 * k as f64).sin();
    if (i + 2 * j + k).is_multiple_of(7) {
        0.0
    } else {
        v
    }
}

/// The grid's density statement, its `.vol` file written into `dir` (the cube is the file's
/// own box).
fn grid_density(dir: &std::path::Path) -> String {
    let [nx, ny, nz] = GRID_RES;
    let values = (0..nx * ny * nz)
        .map(|n| grid_value(n % nx, (n / nx) % ny, n / (nx * ny)) as f32)
        .collect();
    let data = GridData {
        res: GRID_RES,
        values,
        bounds: Some((Vec3::splat(-0.5), Vec3::splat(0.5))),
    };
    let path = dir.join("grid.vol");
    std::fs::write(&path, vol::encode(&data)).unwrap();
    format!(
        r#"density = {{ type = "grid", file = "{}" }}"#,
        path.display()
    )
}

/// Mitsuba 3's `gridvolume` lookup, written here from its definition: sample (i, j, k) at the
/// centre of its cell, trilinear between centres, clamped in the outer half cells.
fn grid_rho(p: [f64; 3]) -> f64 {
    let mut idx = [(0usize, 0usize, 0.0f64); 3];
    for a in 0..3 {
        let n = GRID_RES[a];
        let x = ((p[a] + 0.5) * n as f64 - 0.5).clamp(0.0, (n - 1) as f64);
        let i = (x.floor() as usize).min(n - 2);
        idx[a] = (i, i + 1, x - i as f64);
    }
    let mut sum = 0.0;
    for c in 0..8 {
        let pick = |a: usize| {
            if c >> a & 1 == 0 {
                (idx[a].0, 1.0 - idx[a].2)
            } else {
                (idx[a].1, idx[a].2)
            }
        };
        let ((i, wi), (j, wj), (k, wk)) = (pick(0), pick(1), pick(2));
        sum += wi * wj * wk * grid_value(i, j, k);
    }
    sum
}

/// The fields, written from their definitions.
#[derive(Clone, Copy)]
enum Field {
    Height,
    Layer,
    Grid,
}

impl Field {
    fn rho(self, p: [f64; 3]) -> f64 {
        match self {
            Field::Height => (-(dot(unit([0.0, 0.6, 0.8]), p) + 0.5) / 0.5).exp(),
            Field::Layer => {
                let h = dot(unit([0.0, 0.8, 0.6]), p);
                let x = ((h - (0.1 - 0.25)) / 0.5).clamp(0.0, 1.0);
                1.0 - x * x * (3.0 - 2.0 * x)
            }
            Field::Grid => grid_rho(p),
        }
    }

    /// `∫_0^len rho(p + d t) dt` by composite Simpson (finer for the grid, whose slope jumps
    /// where the ray crosses planes through sample centres).
    fn depth(self, p: [f64; 3], d: [f64; 3], len: f64) -> f64 {
        let n = if let Field::Grid = self { 512 } else { 64 };
        let h = len / n as f64;
        let at = |t: f64| self.rho([p[0] + d[0] * t, p[1] + d[1] * t, p[2] + d[2] * t]);
        let mut sum = at(0.0) + at(len);
        for i in 1..n {
            sum += if i % 2 == 1 { 4.0 } else { 2.0 } * at(i as f64 * h);
        }
        sum * h / 3.0
    }
}

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

/// Single-scattering radiance averaged over the viewed square, per bin:
/// `L = ∫_0^1 e^{-st D_cam(s)} ss rho(x(s)) p(cos) E e^{-st D_light(x(s))} ds`.
fn single_scattering(field: Field) -> Vec<f64> {
    let grid = SpectralGrid::new(BINS, 380.0, 780.0);
    single_scattering_of(field, &power_law(1.5, 550.0, 4.0, &grid).0[..BINS])
}

/// Single scattering with the scattering coefficient `ss` per bin (sigma_a = 0.2).
fn single_scattering_of(field: Field, ss: &[f32]) -> Vec<f64> {
    let d = unit([0.5, -0.5, -std::f64::consts::FRAC_1_SQRT_2]);
    let back = [-d[0], -d[1], -d[2]];
    let e = 4.0 / 400.0;
    let g: f64 = 0.5;
    let phase = (1.0 - g * g) / (4.0 * PI * (1.0 + g * g - 2.0 * g * d[2]).powf(1.5));
    let (m, k) = (16, 200);
    let mut out = [0.0f64; BINS];
    for i in 0..m {
        for j in 0..m {
            let x = -0.2 + 0.4 * (i as f64 + 0.5) / m as f64;
            let y = -0.2 + 0.4 * (j as f64 + 0.5) / m as f64;
            let top = [x, y, 0.5];
            for q in 0..k {
                let s = (q as f64 + 0.5) / k as f64;
                let p = [x, y, 0.5 - s];
                let d_cam = field.depth(top, [0.0, 0.0, -1.0], s);
                let d_light = field.depth(p, back, exit_distance(p, back));
                let rho = field.rho(p);
                for (b, o) in out.iter_mut().enumerate() {
                    let st = ss[b] as f64 + 0.2;
                    *o += (-st * (d_cam + d_light)).exp() * ss[b] as f64 * rho * phase * e;
                }
            }
        }
    }
    out.iter().map(|v| v / (m * m * k) as f64).collect()
}

fn check(field: Field, density: &str, cases: &[(&str, &[&str], f64)]) {
    let expected = single_scattering(field);
    for (name, sets, floor) in cases {
        let s = scene(&fog_text(density), sets);
        let (mean, se) = independent_estimates(&s, 5, 2, (0, 8, 0, 8));
        assert_bins(name, &mean, &se, &expected, Z, *floor);
    }
}

/// Gathered spheres and cylinders keep the engine_media test's 1 % kernel allowance (the blur
/// of radius R and volumes cut at the cube's faces); NEE has none. The cylinders integrate
/// the camera's transmittance through the density in closed form (eq. 2, truncated) or by
/// quadrature (eq. 3 long); `estimator::dense`.
const CASES: [(&str, &[&str], f64); 7] = [
    ("spheres q=1", &["integrator.q=1"], 0.01),
    ("spheres q=0.3", &["integrator.q=0.3"], 0.01),
    ("spheres q=0.1", &["integrator.q=0.1"], 0.01),
    (
        "cylinder (eq. 2)",
        &["integrator.volume=\"cylinder\""],
        0.01,
    ),
    (
        "cylinder-truncated",
        &["integrator.volume=\"cylinder-truncated\""],
        0.01,
    ),
    (
        "cylinder-long (eq. 3)",
        &["integrator.volume=\"cylinder-long\""],
        0.01,
    ),
    ("nee", &["integrator.direct=nee"], 0.0),
];

#[test]
fn height_fog_matches_single_scattering() {
    check(Field::Height, HEIGHT, &CASES);
}

#[test]
fn fog_bank_matches_single_scattering() {
    check(Field::Layer, LAYER, &CASES);
}

#[test]
fn grid_matches_single_scattering() {
    let dir = tempfile::tempdir().unwrap();
    check(Field::Grid, &grid_density(dir.path()), &CASES);
}

/// The cylinders in a grey medium (sigma_s = 1.5 /m in every bin), where forward flights are
/// grey and the gather takes the closed forms (eq. 2: `e^{-st D(tau_a)}` and the chord's
/// optical length; truncated: the optical length alone) instead of quadrature, in height fog
/// and in the grid.
#[test]
fn grey_cylinders_match_single_scattering() {
    let dir = tempfile::tempdir().unwrap();
    let cases: [(&str, &str); 3] = [
        ("grey cylinder (eq. 2)", "integrator.volume=\"cylinder\""),
        (
            "grey cylinder-truncated",
            "integrator.volume=\"cylinder-truncated\"",
        ),
        (
            "grey cylinder-long (eq. 3)",
            "integrator.volume=\"cylinder-long\"",
        ),
    ];
    for (field, density) in [
        (Field::Height, HEIGHT.to_string()),
        (Field::Grid, grid_density(dir.path())),
    ] {
        let expected = single_scattering_of(field, &[1.5; BINS]);
        for (name, set) in cases {
            let sets = [set, "media.fog.sigma_s=1.5"];
            let s = scene(&fog_text(&density), &sets);
            let (mean, se) = independent_estimates(&s, 5, 2, (0, 8, 0, 8));
            assert_bins(name, &mean, &se, &expected, Z, 0.01);
        }
    }
}

/// Null-collision transport (`tracking = "delta"`, majorant blocks, and `"delta-global"`) in
/// the grid, made grey (sigma_s = 1.5 /m in every bin) as tracking requires: the camera walk's
/// sub-steps and the forward flights by delta tracking, NEE's shadow rays and camera
/// transmittance by ratio tracking, its distances towards the parallel light by delta
/// tracking. Same bounds as the exact transport.
#[test]
fn tracked_grid_matches_single_scattering() {
    let dir = tempfile::tempdir().unwrap();
    let expected = single_scattering_of(Field::Grid, &[1.5; BINS]);
    let density = grid_density(dir.path());
    let cases: [(&str, &[&str], f64); 5] = [
        (
            "delta spheres q=1",
            &["integrator.q=1", "media.fog.tracking=\"delta\""],
            0.01,
        ),
        (
            "delta spheres q=0.3",
            &["integrator.q=0.3", "media.fog.tracking=\"delta\""],
            0.01,
        ),
        (
            "delta nee",
            &["integrator.direct=nee", "media.fog.tracking=\"delta\""],
            0.0,
        ),
        (
            "global spheres q=0.3",
            &["integrator.q=0.3", "media.fog.tracking=\"delta-global\""],
            0.01,
        ),
        (
            "global nee",
            &[
                "integrator.direct=nee",
                "media.fog.tracking=\"delta-global\"",
            ],
            0.0,
        ),
    ];
    for (name, sets, floor) in cases {
        let mut sets = sets.to_vec();
        sets.push("media.fog.sigma_s=1.5");
        let s = scene(&fog_text(&density), &sets);
        let (mean, se) = independent_estimates(&s, 5, 2, (0, 8, 0, 8));
        assert_bins(name, &mean, &se, &expected, Z, floor);
    }
}

/// Tracking is refused, naming the key, where it cannot work: a chromatic medium, and a
/// density with a closed-form depth.
#[test]
fn tracking_is_refused_where_it_does_not_apply() {
    let dir = tempfile::tempdir().unwrap();
    let scene_dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/test.toml");
    let sets = vec!["media.fog.tracking=\"delta\"".to_string()];
    for (density, why) in [
        (grid_density(dir.path()), "grey"),
        (HEIGHT.to_string(), "grid or noise"),
    ] {
        let loaded = brume::scene::load_str(&fog_text(&density), &scene_dir, &sets);
        let err = match loaded {
            Ok(l) => brume::scene::build(&l).err().map(|e| e.to_string()),
            Err(e) => Some(e.to_string()),
        }
        .expect("refused");
        assert!(
            err.contains("media.fog.tracking") && err.contains(why),
            "{err}"
        );
    }
}

/// Cylinders in a tracked medium are refused before rendering, naming the keys: their
/// weights need the optical depth at every point of the axis.
#[test]
fn cylinders_are_refused_with_tracking() {
    let dir = tempfile::tempdir().unwrap();
    let sets = vec![
        "integrator.volume=\"cylinder\"".to_string(),
        "media.fog.tracking=\"delta\"".to_string(),
        "media.fog.sigma_s=1.5".to_string(),
    ];
    let scene_dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/test.toml");
    let loaded = brume::scene::load_str(&fog_text(&grid_density(dir.path())), &scene_dir, &sets);
    let err = match loaded {
        Ok(l) => brume::scene::build(&l).err().map(|e| e.to_string()),
        Err(e) => Some(e.to_string()),
    }
    .expect("refused");
    assert!(
        err.contains("integrator.volume") && err.contains("media.fog.tracking"),
        "{err}"
    );
}
