//! Sensors from the integrator on a plane under point lights (issue 16): illuminance sensors
//! (next-event estimation at the sensor, or forward rays through the sensor's disc) and
//! luminance sensors (the film's pixels) against closed forms and candela tables. Next-event
//! estimates of a point light are deterministic at a fixed point (no standard error): they are
//! held to a relative bound; the forward-ray estimates to |z| <= 4 at fixed seeds.

use std::f64::consts::PI;
use std::path::Path;

use brume::film::SensorReading;
use brume::integrator::Budget;
use brume::light::{Goniometric, ies};

use crate::common::{Setup, scene};

const Z: f64 = 4.0;
/// Relative bound of a deterministic estimate (f32 sums of a few terms).
const EXACT: f64 = 5e-5;

/// The sensors' readings after `passes` passes at `seed`.
fn readings(s: &Setup, seed: u64, passes: u32) -> Vec<SensorReading> {
    let mut r = s.renderer(seed);
    r.run(Budget::Passes(passes), |_, _| {});
    r.film().sensor_readings()
}

fn z_of(r: &SensorReading, expected: f64) -> f64 {
    let se = r.std_error.expect("several passes");
    (r.value - expected) / se
}

/// Asserts a forward-ray estimate within `Z` standard errors, and that the test could fail: its
/// standard error is below 3 % of the value.
fn assert_z(what: &str, r: &SensorReading, expected: f64) {
    let z = z_of(r, expected);
    let se = r.std_error.unwrap_or(f64::INFINITY);
    eprintln!(
        "{what}: {:.5} {} (se {se:.5}) expected {expected:.5}, z = {z:.2}",
        r.value, r.unit
    );
    assert!(z.abs() <= Z, "{what}: z = {z}");
    assert!(se < 0.03 * expected, "{what}: se {se} too large to test");
}

fn assert_exact(what: &str, r: &SensorReading, expected: f64) {
    let rel = (r.value / expected - 1.0).abs();
    eprintln!(
        "{what}: {:.6} {} expected {expected:.6}, relative error {rel:.2e}",
        r.value, r.unit
    );
    assert!(rel <= EXACT, "{what}: {} vs {expected}", r.value);
}

const I: f64 = 100.0;
const D: f64 = 2.0;
const RHO: f64 = 0.5;

/// A Lambert plane of albedo RHO under a point light of I cd at height D, seen from above by
/// an orthographic camera over the 0.2 x 0.2 m square around the light's foot; a luminance
/// sensor over all pixels and an illuminance sensor at the foot.
fn plane(direct: &str, radius: f64) -> String {
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
direct = "{direct}"
radius = {radius}
forward_rays = 200000
sensor_paths = 64
[materials.floor]
type = "lambert"
albedo = {RHO}
[[shapes]]
type = "quad"
size = [20, 20]
material = "floor"
transform = {{ rotate = [-90, 0, 0] }}
[[lights]]
type = "point"
position = [0, {D}, 0]
intensity = {I}
spectrum = "D65"
[[sensors]]
name = "spot"
type = "luminance"
region = [0, 0, 8, 8]
[[sensors]]
name = "foot"
type = "illuminance"
position = [0, 0, 0]
normal = [0, 1, 0]
"#
    )
}

/// Illuminance (lx) at horizontal distance r from the foot of the point light.
fn e_plane(r2: f64) -> f64 {
    I * D / (D * D + r2).powf(1.5)
}

/// Mean of `f` over a disc of radius `r` centred at (x, z), on a polar grid of area-weighted
/// radii (the point itself for r = 0).
fn disc_mean(x: f64, z: f64, r: f64, f: impl Fn(f64, f64) -> f64) -> f64 {
    if r == 0.0 {
        return f(x, z);
    }
    let k = 24;
    let mut acc = 0.0;
    for a in 0..k {
        for b in 0..k {
            let rr = r * ((a as f64 + 0.5) / k as f64).sqrt();
            let phi = 2.0 * PI * (b as f64 + 0.5) / k as f64;
            acc += f(x + rr * phi.cos(), z + rr * phi.sin());
        }
    }
    acc / (k * k) as f64
}

/// Mean luminance (cd/m²) over the viewed square, each point's illuminance averaged over a
/// disc of radius `blur` (the surface spheres' kernel; 0: exact).
fn luminance_of_square(blur: f64) -> f64 {
    let m = 48;
    let mut acc = 0.0;
    for i in 0..m {
        for j in 0..m {
            let x = -0.1 + 0.2 * (i as f64 + 0.5) / m as f64;
            let z = -0.1 + 0.2 * (j as f64 + 0.5) / m as f64;
            acc += disc_mean(x, z, blur, |x, z| e_plane(x * x + z * z));
        }
    }
    RHO / PI * acc / (m * m) as f64
}

/// Acceptance (issue 16): under a point light of I cd at height d, an illuminance sensor at
/// the foot reads I/d² lx and a luminance sensor over the spot rho I/(pi d²) cd/m² (over the
/// 0.2 m square: its exact mean, 0.25 % below the value at the foot).
#[test]
fn point_light_over_a_lambert_plane() {
    let at_foot = RHO * I / (PI * D * D);
    let square = luminance_of_square(0.0);
    eprintln!("rho I/(pi d²) = {at_foot:.5}, mean over the square {square:.5}");
    assert!((square / at_foot - 1.0).abs() < 0.003);

    // Next-event estimation: exact at the sensor, pixel positions the only noise in the image.
    let r = readings(&scene(&plane("nee", 0.1), &[]), 1, 8);
    assert_exact("nee: illuminance at the foot", &r[1], I / (D * D));
    let z = z_of(&r[0], square);
    eprintln!(
        "nee: luminance {:.6} vs {square:.6}, z = {z:.2}",
        r[0].value
    );
    assert!(z.abs() <= Z, "nee luminance: z = {z}");

    // Forward rays: the sensor's disc of radius R = 0.15 m reads the mean irradiance over it,
    // 2 I (1 - d / sqrt(d² + R²)) / R² (0.42 % below I/d²); surface spheres blur as much.
    let radius = 0.15;
    let disc = 2.0 * I * (1.0 - D / (D * D + radius * radius).sqrt()) / (radius * radius);
    let r = readings(&scene(&plane("photons", radius), &[]), 2, 32);
    assert_z("photons: illuminance at the foot", &r[1], disc);
    assert_z("photons: luminance", &r[0], luminance_of_square(radius));
}

fn data(name: &str) -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data")
        .join(name)
}

/// The asymmetric full-sphere table at height 1 m, aimed down, C = 0 towards +X (C = 90
/// towards -Z); illuminance sensors at the nadir and at gamma = 30 degrees in the four table
/// planes C = 0, 90, 180, 270.
fn lamp(direct: &str) -> String {
    let r = 30f64.to_radians().tan();
    let mut text = format!(
        r#"
[film]
bins = 4
[camera]
type = "orthographic"
width = 2
height = 2
position = [0, 3, 0]
look_at = [0, 0, 0]
up = [0, 0, -1]
[integrator]
direct = "{direct}"
radius = 0.07
forward_rays = 200000
sensor_paths = 16
[materials.floor]
type = "lambert"
albedo = 0.3
[[shapes]]
type = "quad"
size = [20, 20]
material = "floor"
transform = {{ rotate = [-90, 0, 0] }}
[[lights]]
type = "point"
position = [0, 1, 0]
profile = "../tests/data/asymmetric.ies"
profile_c0 = [1, 0, 0]
"#
    );
    for (x, z) in [(0.0, 0.0), (r, 0.0), (0.0, -r), (-r, 0.0), (0.0, r)] {
        text += &format!(
            "[[sensors]]\ntype = \"illuminance\"\nposition = [{x}, 0, {z}]\nnormal = [0, 1, 0]\n"
        );
    }
    text
}

/// Acceptance (issue 16): illuminance on a plane under an IES-profiled light follows the
/// candela table: I(gamma, C) cos³(gamma) / h² at table angles (next-event estimation: to
/// rounding; forward rays through the sensors' discs of 7 cm: |z| <= 4 against the table's
/// interpolant averaged over each disc, which the table's kinks at its own angles move from
/// the table's value by -6 % to +33 %).
#[test]
fn illuminance_under_an_ies_profile_follows_the_candela_table() {
    let d = ies::load(&data("asymmetric.ies")).expect("parses");
    let g = Goniometric::from_ies(&d).expect("emits");
    let cos30 = 30f64.to_radians().cos();
    // (horizontal, vertical) table indices of each sensor: the nadir, then gamma = 30.
    let cells = [(0, 0), (0, 1), (1, 1), (2, 1), (3, 1)];
    let table: Vec<f64> = cells
        .iter()
        .enumerate()
        .map(|(k, &(h, v))| d.intensity(h, v) * if k == 0 { 1.0 } else { cos30.powi(3) })
        .collect();
    eprintln!("table: {table:?}");
    let r = readings(&scene(&lamp("nee"), &[]), 1, 2);
    for (k, want) in table.iter().enumerate() {
        assert_exact(&format!("nee: sensor {k}"), &r[k], *want);
    }

    let s = scene(&lamp("photons"), &[]);
    let r = readings(&s, 3, 40);
    let t = 30f64.to_radians().tan();
    for (k, (x, z)) in [(0.0, 0.0), (t, 0.0), (0.0, -t), (-t, 0.0), (0.0, t)]
        .into_iter()
        .enumerate()
    {
        // The light's intensity towards (x, 0, z) from (0, 1, 0), times cos / distance².
        let e = |x: f64, z: f64| {
            let dist = (x * x + z * z + 1.0).sqrt();
            let gamma = (1.0 / dist).acos();
            let c = (-z).atan2(x).rem_euclid(2.0 * PI);
            g.eval_angles(gamma, c) / (dist * dist * dist)
        };
        let want = disc_mean(x, z, 0.07, e);
        eprintln!("sensor {k}: table {:.3}, disc mean {want:.3}", table[k]);
        assert_z(&format!("photons: sensor {k}"), &r[k], want);
    }
}

/// A Lambertian disc of radius A emitting PHI lm downwards from height H over a floor, and
/// illuminance sensors on the floor below its centre and R_OFF off its axis.
const A: f64 = 0.5;
const H: f64 = 1.0;
const PHI: f64 = 1000.0;
const R_OFF: f64 = 0.8;

fn disc_lamp(direct: &str) -> String {
    format!(
        r#"
[film]
bins = 4
[camera]
type = "orthographic"
width = 2
height = 2
position = [0, 3, 0]
look_at = [0, 0, 0]
up = [0, 0, -1]
[integrator]
direct = "{direct}"
radius = 0.05
forward_rays = 20000
sensor_paths = 2048
[materials.floor]
type = "lambert"
albedo = 0.3
[[shapes]]
type = "quad"
size = [20, 20]
material = "floor"
transform = {{ rotate = [-90, 0, 0] }}
[[shapes]]
type = "disc"
radius = {A}
emit = "D65"
luminous_flux = {PHI}
transform = {{ rotate = [90, 0, 0], translate = [0, {H}, 0] }}
[[sensors]]
type = "illuminance"
position = [0, 0, 0]
normal = [0, 1, 0]
[[sensors]]
type = "illuminance"
position = [{R_OFF}, 0, 0]
normal = [0, 1, 0]
"#
    )
}

/// Illuminance at horizontal distance r below a parallel coaxial Lambertian disc of luminance
/// L: (pi L / 2) (1 - (h² + r² - a²) / sqrt((h² + r² + a²)² - 4 a² r²)).
fn e_disc(r: f64) -> f64 {
    let l = PHI / (PI * PI * A * A);
    let (h2, r2, a2) = (H * H, r * r, A * A);
    PI * l / 2.0 * (1.0 - (h2 + r2 - a2) / ((h2 + r2 + a2).powi(2) - 4.0 * a2 * r2).sqrt())
}

/// An area light over illuminance sensors: next-event samples at the sensor and the sensor
/// paths that hit the emitter share its light by the power heuristic (`nee`); without
/// next-event estimation the sensor paths see it alone (`photons`). Both read the closed form
/// within |z| <= 4.
#[test]
fn illuminance_under_an_area_light() {
    let want = [e_disc(0.0), e_disc(R_OFF)];
    assert!((want[0] - PHI / (PI * (H * H + A * A))).abs() < 1e-9 * want[0]);
    for (mode, seed) in [("nee", 5), ("photons", 6)] {
        let r = readings(&scene(&disc_lamp(mode), &[]), seed, 12);
        for k in 0..2 {
            assert_z(&format!("{mode}: sensor {k}"), &r[k], want[k]);
        }
    }
}
