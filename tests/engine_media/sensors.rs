//! An illuminance sensor inside fog (issue 16): a slab of grey fog under a parallel light,
//! the sensor facing the light at optical depth 1. Paths are cut after one scattering
//! (`max_depth = 1`), so the reading is the transmitted direct light plus the singly
//! scattered light, both in closed form (the second by a one-dimensional quadrature). Both
//! ways of estimating direct light: next-event estimation at the sensor and along its paths,
//! and forward rays through the sensor's disc and into its paths' integration volumes.

use std::f64::consts::PI;

use brume::film::SensorReading;
use brume::integrator::Budget;

use crate::common::scene;

const E0: f64 = 1000.0;
const SIGMA_S: f64 = 1.6;
const SIGMA_T: f64 = 2.0;
const G: f64 = 0.5;
/// Depth of the sensor below the slab's lit face.
const DEPTH: f64 = 0.5;

/// The slab y in [0, 1], 10 m wide (the light scattered from beyond its edges, at least 5 m
/// and 10 optical depths away, is below 1e-4 of the reading), lit from above by E0 lx; the
/// sensor at its middle facing up.
fn slab(direct: &str) -> String {
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
radius = 0.1
max_depth = 1
forward_rays = 200000
sensor_paths = 512
[media.fog]
sigma_s = {SIGMA_S}
sigma_a = {}
g = {G}
[[shapes]]
type = "box"
size = [10, 1, 10]
interior = "fog"
transform = {{ translate = [0, 0.5, 0] }}
[[lights]]
type = "directional"
direction = [0, -1, 0]
illuminance = {E0}
[[sensors]]
name = "in-fog"
type = "illuminance"
position = [0, {}, 0]
normal = [0, 1, 0]
"#,
        SIGMA_T - SIGMA_S,
        1.0 - DEPTH
    )
}

fn hg(cos: f64) -> f64 {
    (1.0 - G * G) / (4.0 * PI * (1.0 + G * G - 2.0 * G * cos).powf(1.5))
}

/// Singly scattered illuminance at depth z facing the light: light scattered at distance s
/// along a direction of cosine mu with the normal, from depth z - s mu, turned by an angle of
/// cosine mu, `2 pi E0 ss ∫ mu p(mu) ∫_0^{z/mu} e^{-st (z - s mu)} e^{-st s} ds dmu`; the inner
/// integral is `e^{-st z} (1 - e^{-st z (1 - mu) / mu}) / (st (1 - mu))`.
fn single_scattered(z: f64) -> f64 {
    let k = 200_000;
    let mut acc = 0.0;
    for i in 0..k {
        let mu = (i as f64 + 0.5) / k as f64;
        let a = SIGMA_T * z * (1.0 - mu) / mu;
        let inner = (-SIGMA_T * z).exp() * -(-a).exp_m1() / (SIGMA_T * (1.0 - mu));
        acc += mu * hg(mu) * inner / k as f64;
    }
    2.0 * PI * E0 * SIGMA_S * acc
}

fn reading(direct: &str, seed: u64, passes: u32) -> SensorReading {
    let s = scene(&slab(direct), &[]);
    let mut r = s.renderer(seed);
    r.run(Budget::Passes(passes), |_, _| {});
    r.film().sensor_readings().remove(0)
}

/// Acceptance (issue 16): the sensor reads E0 e^{-st z} (direct, transmitted) plus the
/// singly scattered light, |z| <= 4 with either way of estimating direct light; the direct
/// part alone is far outside the interval (the scattered light is measured, not just
/// bounded).
#[test]
fn illuminance_inside_fog_is_direct_plus_scattered_light() {
    let direct = E0 * (-SIGMA_T * DEPTH).exp();
    let scattered = single_scattered(DEPTH);
    let want = direct + scattered;
    eprintln!("direct {direct:.3} lx + scattered {scattered:.3} lx = {want:.3} lx");
    for (mode, passes) in [("nee", 16), ("photons", 48)] {
        let r = reading(mode, 7, passes);
        let se = r.std_error.expect("passes");
        let z = (r.value - want) / se;
        let z_direct = (r.value - direct) / se;
        eprintln!(
            "{mode}: {:.3} lx (se {se:.3}), z = {z:.2}; against the direct part alone z = \
             {z_direct:.1}",
            r.value
        );
        assert!(z.abs() <= 4.0, "{mode}: z = {z}");
        assert!(
            z_direct > 10.0,
            "{mode}: the scattered part must be resolved"
        );
    }
}
