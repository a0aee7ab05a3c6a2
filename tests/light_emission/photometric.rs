//! Lights given in photometric quantities (lm, cd, lx) emit what they are given, converted with
//! their own spectrum; importance moves forward rays between lights without changing the
//! expected flux. Fixed seeds, |z| <= 4.

use std::f64::consts::PI;
use std::path::Path;

use brume::colour::photometry;
use brume::light::Light;
use brume::scene::{build, load_str};
use brume::spectrum::Spectrum;
use brume::world::Scene;
use glam::Vec3;
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64Mcg;

pub fn scene(text: &str) -> Scene {
    let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/test.toml");
    let loaded = load_str(text, &file, &[]).unwrap_or_else(|e| panic!("{e}"));
    build(&loaded).unwrap_or_else(|e| panic!("{e}"))
}

const HEAD: &str = r#"
[camera]
type = "orthographic"
width = 4
height = 4
position = [0, 0, 20]
view_width = 1.0
view_height = 1.0
[spectra.laser]
file = "laser-532nm.csv"
"#;

/// Luminous value (lm, cd, lx) of a spectral quantity of the scene's grid.
fn lumens(scene: &Scene, s: &Spectrum) -> f64 {
    let w = photometry::luminous_weights(&scene.grid).expect("V");
    photometry::photometric(&w, s.as_slice(scene.grid.n))
}

fn u5(rng: &mut Pcg64Mcg) -> [f32; 5] {
    [
        rng.random(),
        rng.random(),
        rng.random(),
        rng.random(),
        rng.random(),
    ]
}

/// Every light of a scene given in lm: forward rays leave through a closed sphere around all
/// of them carrying each light's luminous flux (per light, |z| <= 4), whatever its kind,
/// spectrum and importance.
#[test]
fn lights_given_in_lumens_emit_that_flux_through_a_closed_sphere() {
    let text = format!(
        "{HEAD}{}",
        r#"
[[lights]]
type = "point"
position = [1, 0, 0]
luminous_flux = 1200.0
spectrum = "A"
[[lights]]
type = "spot"
position = [-1, 0, 0]
direction = [0, -1, 0]
angle = 30.0
soft_edge = 5.0
luminous_flux = 300.0
importance = 4.0
[[lights]]
type = "laser"
position = [0, 1, 0]
direction = [1, 0, 0]
radius = 0.01
luminous_flux = 3.0
spectrum = "laser"
importance = 50.0
[[lights]]
type = "point"
position = [0, -1, 0]
profile = "../tests/data/asymmetric.ies"
luminous_flux = 2000.0
[[shapes]]
type = "sphere"
radius = 0.5
emit = "F11"
luminous_flux = 800.0
transform = { translate = [0, 0, 1] }
"#
    );
    let scene = scene(&text);
    // Area lights come first.
    let want = [800.0, 1200.0, 300.0, 3.0, 2000.0];
    let mut rng = Pcg64Mcg::seed_from_u64(1601);
    let n = 400_000;
    let (mut sum, mut sq) = ([0.0f64; 5], [0.0f64; 5]);
    let (centre, radius) = (Vec3::ZERO, 10.0f32);
    for _ in 0..n {
        let (i, s) = scene
            .lights
            .sample(&scene.geometry, u5(&mut rng))
            .expect("lights emit");
        // The ray leaves the enclosing sphere once, forwards.
        let o = s.ray.o - centre;
        let b = o.dot(s.ray.d);
        let t = -b + (b * b - (o.length_squared() - radius * radius)).sqrt();
        assert!(t > 0.0);
        let v = lumens(&scene, &s.flux);
        sum[i as usize] += v;
        sq[i as usize] += v * v;
    }
    for (i, want) in want.iter().enumerate() {
        let mean = sum[i] / n as f64;
        let se = ((sq[i] / n as f64 - mean * mean) / n as f64).sqrt();
        let z = (mean - want) / se;
        assert!(
            z.abs() <= 4.0,
            "light {i}: {mean} lm vs {want} (z = {z:.2})"
        );
    }
}

/// Intensities in cd: isotropic and on a spot's axis; a directional light's illuminance in lx.
#[test]
fn intensity_and_illuminance_are_exact() {
    let text = format!(
        "{HEAD}{}",
        r#"
[[lights]]
type = "point"
position = [1, 0, 0]
intensity = 95.0
spectrum = "LED-B1"
[[lights]]
type = "spot"
position = [-1, 0, 0]
direction = [0, -1, 0]
angle = 25.0
soft_edge = 10.0
intensity = 5000.0
[[lights]]
type = "directional"
direction = [0, 0, -1]
illuminance = 20000.0
spectrum = "D50"
"#
    );
    let scene = scene(&text);
    let l = scene.lights.lights();
    let cd = |light: &Light, d: Vec3| lumens(&scene, &light.intensity(d));
    let close = |a: f64, b: f64| (a / b - 1.0).abs() < 1e-5;
    assert!(close(cd(&l[0], Vec3::new(0.3, 0.4, 0.5)), 95.0));
    assert!(close(
        lumens(&scene, &l[0].power(&scene.geometry)),
        4.0 * PI * 95.0
    ));
    assert!(close(cd(&l[1], Vec3::NEG_Y), 5000.0));
    assert!(cd(&l[1], Vec3::Y) == 0.0);
    let Light::Directional { irradiance, .. } = &l[2] else {
        panic!("directional")
    };
    assert!(close(lumens(&scene, irradiance), 20000.0));
}

/// Importance k on a weak light: its share of forward rays grows by k relative to the other
/// light, and the expected flux it sends into a cone is unchanged (|z| <= 4).
#[test]
fn importance_moves_rays_not_flux() {
    let at = |importance: f32| {
        scene(&format!(
            "{HEAD}
[[lights]]
type = \"point\"
position = [0, 0, 0]
power = 10.0
[[lights]]
type = \"point\"
position = [5, 0, 0]
power = 0.01
importance = {importance}
"
        ))
    };
    let axis = Vec3::new(0.0, 0.6, 0.8);
    let cos_cone = 20f32.to_radians().cos();
    let frac = (1.0 - cos_cone as f64) / 2.0;
    let mut shares = Vec::new();
    for (k, seed) in [(1.0f32, 1602u64), (40.0, 1603)] {
        let s = at(k);
        let p = s.lights.pick_probability(1) as f64;
        let expect_p = 0.01 * k as f64 / (10.0 + 0.01 * k as f64);
        assert!((p / expect_p - 1.0).abs() < 1e-5);
        let mut rng = Pcg64Mcg::seed_from_u64(seed);
        let n = 400_000;
        let (mut picked, mut flux) = (0usize, 0.0f64);
        for _ in 0..n {
            let (i, e) = s.lights.sample(&s.geometry, u5(&mut rng)).expect("emits");
            if i == 1 {
                picked += 1;
                if e.ray.d.dot(axis) > cos_cone {
                    flux += s.grid.integral(&e.flux);
                }
            }
        }
        // Flux of light 1 into the cone: power x solid-angle fraction.
        let want = 0.01 * frac;
        let mean = flux / n as f64;
        let q = p * frac;
        let se = 0.01 / p * (q * (1.0 - q) / n as f64).sqrt();
        assert!(
            ((mean - want) / se).abs() <= 4.0,
            "k = {k}: {mean} vs {want}"
        );
        let share = picked as f64 / n as f64;
        assert!(((share - p) / (p * (1.0 - p) / n as f64).sqrt()).abs() <= 4.0);
        shares.push(share / (1.0 - share));
    }
    // The odds of picking the weak light rise by the importance factor.
    let ratio = shares[1] / shares[0];
    assert!((ratio / 40.0 - 1.0).abs() < 0.1, "odds ratio {ratio}");
}

/// Exactly one amount per light, and none that its kind does not have.
#[test]
fn amounts_are_refused_unless_exactly_one() {
    let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/test.toml");
    let cases = [
        ("power = 1.0\nluminous_flux = 5.0", "give one of"),
        ("", "give one of `power`, `luminous_flux`, `intensity`"),
        ("intensity = -3.0", "must be a finite number > 0"),
        ("illuminance = 3.0", "unknown field `illuminance`"),
        ("power = 1.0\nimportance = 0.0", "importance"),
    ];
    for (keys, message) in cases {
        let text = format!("{HEAD}[[lights]]\ntype = \"point\"\nposition = [0, 0, 0]\n{keys}\n");
        let err = match load_str(&text, &file, &[]).and_then(|l| build(&l).map(|_| ())) {
            Ok(()) => panic!("{keys}: accepted"),
            Err(e) => e.to_string(),
        };
        assert!(err.contains(message), "{keys}: {err}");
    }
}
