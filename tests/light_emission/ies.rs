//! IES LM-63 profiles: the intensity a profiled light evaluates is the candela table at its
//! angles and bilinear between them; the directions it samples follow the table (chi-square
//! against an independent quadrature); symmetric files equal their full tables; malformed files
//! are refused with their file and line.

use std::f64::consts::{PI, TAU};
use std::path::{Path, PathBuf};

use brume::light::{Goniometric, ies};
use glam::{Vec2, Vec3};
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64Mcg;

use super::photometric::scene;

fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data")
        .join(name)
}

fn table(name: &str) -> Goniometric {
    Goniometric::from_ies(&ies::load(&data(name)).expect("parses")).expect("emits")
}

/// A profiled point light aimed down (-Y) with C = 0 towards +X (so C = 90 is towards -Z,
/// counter-clockwise seen from above).
const LAMP: &str = r#"
[camera]
type = "orthographic"
width = 4
height = 4
position = [0, 0, 20]
view_width = 1.0
view_height = 1.0
[[lights]]
type = "point"
position = [0, 3, 0]
profile = "../tests/data/asymmetric.ies"
profile_c0 = [1, 0, 0]
power = 2.0
"#;

fn world_dir(gamma_deg: f64, c_deg: f64) -> Vec3 {
    let (g, c) = (gamma_deg.to_radians(), c_deg.to_radians());
    // Axis -Y, C = 0 along +X, C = 90 along -Z.
    Vec3::new(
        (g.sin() * c.cos()) as f32,
        -(g.cos() as f32),
        -(g.sin() * c.sin()) as f32,
    )
}

#[test]
fn the_light_evaluates_the_candela_table_at_its_angles() {
    let d = ies::load(&data("asymmetric.ies")).expect("parses");
    let g = table("asymmetric.ies");
    // Flux of the table (lm) by an independent quadrature of the interpolant.
    let total = quadrature(&g, 0.0, PI, 0.0, TAU, 400);
    assert!(
        (total / g.total() - 1.0).abs() < 1e-5,
        "{total} vs {}",
        g.total()
    );
    let s = scene(LAMP);
    let light = &s.lights.lights()[0];
    for (h, c) in d.horizontal.iter().enumerate() {
        for (v, gamma) in d.vertical.iter().enumerate() {
            let cd = d.intensity(h, v);
            assert_eq!(g.eval_angles(gamma.to_radians(), c.to_radians()), cd);
            // Per watt of the light: cd / total lm, in every bin of its spectrum.
            let i = s.grid.integral(&light.intensity(world_dir(*gamma, *c)));
            let want = 2.0 * cd / g.total();
            assert!(
                (i - want).abs() <= 1e-5 * want.max(1e-3),
                "({gamma}, {c}): {i} vs {want}"
            );
        }
    }
    // Halfway between table angles: bilinear.
    let mid = g.eval_angles(45f64.to_radians(), 45f64.to_radians());
    let want =
        0.25 * (d.intensity(0, 1) + d.intensity(0, 2) + d.intensity(1, 1) + d.intensity(1, 2));
    assert!((mid - want).abs() < 1e-9, "{mid} vs {want}");
}

/// A profiled light given in candela (`intensity`, the table's peak): a point and a spot send
/// that many cd towards the table's brightest entry (gamma 60, C 90 of asymmetric.ies: 400 cd
/// times its multiplier 2) and the table's proportion of it elsewhere (straight down: 100 of
/// 400), with their own spectra.
#[test]
fn a_profile_given_in_candela_has_that_intensity_at_its_peak() {
    let g = table("asymmetric.ies");
    assert_eq!(g.peak(), 800.0);
    let text = format!(
        "{LAMP}{}",
        r#"
[[lights]]
type = "point"
position = [0, 3, 0]
profile = "../tests/data/asymmetric.ies"
profile_c0 = [1, 0, 0]
intensity = 750.0
spectrum = "A"
[[lights]]
type = "spot"
position = [0, 3, 0]
direction = [0, -1, 0]
profile = "../tests/data/asymmetric.ies"
profile_c0 = [1, 0, 0]
intensity = 40.0
spectrum = "F11"
"#
    );
    let s = scene(&text);
    let v = brume::colour::photometry::luminous_weights(&s.grid).expect("V");
    let cd = |light: &brume::light::Light, d: Vec3| {
        brume::colour::photometry::photometric(&v, light.intensity(d).as_slice(s.grid.n))
    };
    for (light, want) in s.lights.lights()[1..].iter().zip([750.0, 40.0]) {
        let (peak, down) = (cd(light, world_dir(60.0, 90.0)), cd(light, Vec3::NEG_Y));
        assert!((peak / want - 1.0).abs() < 1e-5, "{peak} cd vs {want}");
        assert!(
            (down / (want / 4.0) - 1.0).abs() < 1e-5,
            "{down} cd vs {want} / 4"
        );
    }
}

/// `integral of eval sin(gamma)` over a patch of angles, midpoint rule on `k` x `k` points.
fn quadrature(g: &Goniometric, g0: f64, g1: f64, c0: f64, c1: f64, k: usize) -> f64 {
    let (dg, dc) = ((g1 - g0) / k as f64, (c1 - c0) / k as f64);
    let mut sum = 0.0;
    for i in 0..k {
        let gamma = g0 + (i as f64 + 0.5) * dg;
        for j in 0..k {
            let c = c0 + (j as f64 + 0.5) * dc;
            sum += g.eval_angles(gamma, c) * gamma.sin() * dg * dc;
        }
    }
    sum
}

/// Forward rays of the profiled light, binned in (gamma, C) cells of 15 x 30 degrees: a
/// chi-square against the table's flux per cell (independent quadrature) within |z| <= 4.
#[test]
fn sampled_directions_follow_the_table() {
    let g = table("asymmetric.ies");
    let s = scene(LAMP);
    let light = &s.lights.lights()[0];
    let (ng, nc) = (12usize, 12usize);
    let mut expected = vec![0.0f64; ng * nc];
    for i in 0..ng {
        for j in 0..nc {
            let (a, b) = (i as f64 * PI / ng as f64, (i + 1) as f64 * PI / ng as f64);
            let (c, d) = (j as f64 * TAU / nc as f64, (j + 1) as f64 * TAU / nc as f64);
            expected[i * nc + j] = quadrature(&g, a, b, c, d, 24) / g.total();
        }
    }
    let mut rng = Pcg64Mcg::seed_from_u64(1604);
    let n = 300_000;
    let mut counts = vec![0usize; ng * nc];
    for _ in 0..n {
        let u = [rng.random(), rng.random(), rng.random(), rng.random()];
        let e = light.sample_emission(&s.geometry, u);
        // Every ray carries the light's whole power: equal flux.
        assert_eq!(e.flux, light.power(&s.geometry));
        let d = e.ray.d;
        let gamma = (-d.y as f64).clamp(-1.0, 1.0).acos();
        let c = (-d.z as f64).atan2(d.x as f64).rem_euclid(TAU);
        let i = ((gamma / PI * ng as f64) as usize).min(ng - 1);
        let j = ((c / TAU * nc as f64) as usize).min(nc - 1);
        counts[i * nc + j] += 1;
    }
    let (mut chi2, mut dof) = (0.0, 0usize);
    for (k, &p) in expected.iter().enumerate() {
        let e = p * n as f64;
        if e < 5.0 {
            assert!(
                (counts[k] as f64) < 5.0 + 6.0 * e.sqrt().max(1.0),
                "cell {k}"
            );
            continue;
        }
        chi2 += (counts[k] as f64 - e).powi(2) / e;
        dof += 1;
    }
    let dof = (dof - 1) as f64;
    let z = (chi2 - dof) / (2.0 * dof).sqrt();
    eprintln!("IES sampling: chi2 = {chi2:.1} for {dof} dof (z = {z:.2})");
    assert!(z <= 4.0, "chi2 = {chi2:.1} for {dof} dof (z = {z:.2})");
    assert!(dof > 60.0, "most cells are tested");
}

/// Quadrant symmetry (0-90) equals the file written out over 0-360; a single horizontal
/// angle is the same in every direction about the axis.
#[test]
fn symmetric_files_expand_to_their_full_tables() {
    let (q, full) = (table("quadrant.ies"), table("quadrant-full.ies"));
    let mut rng = Pcg64Mcg::seed_from_u64(1605);
    for _ in 0..2000 {
        let d = Vec3::new(
            rng.random::<f32>() - 0.5,
            rng.random::<f32>() - 0.5,
            rng.random::<f32>() - 0.5,
        )
        .normalize();
        let (a, b) = (q.eval(d), full.eval(d));
        assert!((a - b).abs() <= 1e-9 * a.max(1.0), "{d}: {a} vs {b}");
        let v = q.sample(Vec2::new(rng.random(), rng.random()));
        assert!((v.length() - 1.0).abs() < 1e-5);
    }
    assert!((q.total() / full.total() - 1.0).abs() < 1e-12);
    let text = std::fs::read_to_string(data("quadrant.ies")).expect("read");
    let round = text
        .replace("1 500 1 4 3", "1 500 1 4 1")
        .replace("0 45 90\n", "0\n")
        .replace("200 250 40 0\n200 90 120 30\n", "");
    let r = Goniometric::from_ies(&ies::parse(&round, Path::new("round.ies")).expect("parses"))
        .expect("emits");
    for c in [0.0f64, 1.0, 2.5, 4.0, 6.0] {
        assert_eq!(r.eval_angles(0.7, c), r.eval_angles(0.7, 0.0));
    }
    // Top-hemisphere-free table: a hard cut-off at 90 degrees.
    assert!(q.cone_cos().expect("cut-off").abs() < 1e-6);
    assert_eq!(table("asymmetric.ies").cone_cos(), None);
}

/// A malformed file named by a scene fails the build with the file and line of the fault.
#[test]
fn malformed_files_are_refused_with_their_line() {
    let dir = tempfile::tempdir().expect("tempdir");
    let good = std::fs::read_to_string(data("asymmetric.ies")).expect("read");
    let cases = [
        (
            good.replace("0 90 180 270 360", "0 90 80 270 360"),
            8,
            "must increase",
        ),
        (
            good.replace("1 1000 2.0 7 5 1 2", "1 1000 2.0 7 5 2 2"),
            5,
            "type 2 (B)",
        ),
        (
            good.replace("TILT=NONE", "TILT=INCLUDE"),
            4,
            "TILT is not NONE",
        ),
        (good.replace("100 120 400", "100 120 -400"), 10, "negative"),
        (format!("{good}5\n"), 14, "after the last"),
    ];
    for (text, line, what) in cases {
        let path = dir.path().join("bad.ies");
        std::fs::write(&path, text).expect("write");
        let err = match ies::load(&path) {
            Ok(_) => panic!("{what}: accepted"),
            Err(e) => e,
        };
        assert_eq!(err.line, line, "{err}");
        assert!(err.to_string().contains(what), "{err}");
        let lamp = LAMP.replace(
            "../tests/data/asymmetric.ies",
            path.to_str().expect("utf-8"),
        );
        let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/test.toml");
        let loaded = brume::scene::load_str(&lamp, &file, &[]).expect("valid scene");
        let err = brume::scene::build(&loaded)
            .err()
            .expect("refused")
            .to_string();
        assert!(
            err.contains(&format!("bad.ies:{line}:")) && err.contains("lights.0.profile"),
            "{err}"
        );
    }
}
