//! Next-event estimation's light pick (`integrator.light_pick`, `integrator::direct::pick`):
//! picking each light in proportion to an estimate of what it sends to the receiver (`local`,
//! the default) instead of its total power (`power`) changes only the variance. An illuminance
//! sensor under four lights reads their closed-form sum with either pick (|z| <= 4), and the
//! local pick's standard error is far smaller there; in a fog box lit by a point light, a spot,
//! a parallel light and an emitting quad reflected by a glossy floor (the MIS weights of
//! emitters hit after a glossy bounce recompute the pick's probability), both picks agree per
//! light layer and per bin (unit tests in `direct::pick` check the picks' frequencies against
//! their probabilities by chi-square).

mod common;

use brume::integrator::Budget;

use common::*;

const Z: f64 = 4.0;

/// A plane in vacuum, an illuminance sensor at the origin facing up, and four lights: a point
/// light of 100 cd 2 m above it (25 lx), a spot of 400 cd on its axis from (1.5, 2, 0) aimed at
/// it (400 x 0.8 / 6.25 = 51.2 lx), a parallel light of 10 lx at cos 0.6 to the normal (6 lx),
/// and a spot aimed up that sends it nothing. 82.2 lx in all.
const SENSOR: &str = r#"
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
radius = 0.05
forward_rays = 1000
sensor_paths = 1024
[materials.floor]
type = "lambert"
albedo = 0.5
[[shapes]]
type = "quad"
size = [20, 20]
material = "floor"
transform = { rotate = [-90, 0, 0] }
[[lights]]
type = "point"
position = [0, 2, 0]
intensity = 100.0
[[lights]]
type = "spot"
position = [1.5, 2, 0]
direction = [-1.5, -2, 0]
angle = 20.0
intensity = 400.0
[[lights]]
type = "directional"
direction = [0.8, -0.6, 0]
illuminance = 10.0
[[lights]]
type = "spot"
position = [0, 2, -1]
direction = [0, 1, 0]
angle = 10.0
intensity = 1000.0
[[sensors]]
name = "origin"
type = "illuminance"
position = [0, 0, 0]
normal = [0, 1, 0]
"#;

#[test]
fn a_sensor_under_four_lights_reads_their_sum_with_either_pick() {
    let expected = 25.0 + 51.2 + 6.0;
    let mut se = Vec::new();
    for pick in ["local", "power"] {
        let set = format!("integrator.light_pick=\"{pick}\"");
        let s = scene(SENSOR, &[&set]);
        let mut r = s.renderer(5);
        r.run(Budget::Passes(32), |_, _| {});
        let reading = &r.film().sensor_readings()[0];
        let e = reading.std_error.expect("several passes");
        let z = (reading.value - expected) / e;
        eprintln!(
            "{pick}: {:.4} lx (se {e:.4}) vs {expected}, z = {z:.2}",
            reading.value
        );
        assert!(z.abs() <= Z, "{pick}: z = {z}");
        assert!(e < 0.03 * expected, "{pick}: se {e} too large to test");
        se.push(e);
    }
    // At the sensor the estimate is nearly proportional to each light's share, so the local
    // pick's only noise is its floor's: here 12x lower (measured), asserted at 4x.
    assert!(
        se[0] < se[1] / 4.0,
        "local se {} vs power se {}",
        se[0],
        se[1]
    );
}

/// A fog box over a glossy floor under every kind of light next-event estimation handles, one
/// film layer per light (so that a wrong probability of one light is not lost in the others').
const FOG: &str = r#"
[film]
bins = 4
light_layers = true
[camera]
type = "perspective"
width = 16
height = 12
position = [0, 1.2, 4]
look_at = [0, 0.8, 0]
fov = 50.0
[integrator]
radius = 0.05
forward_rays = 20000
camera_samples = 16
q = 0.5
[media.fog]
sigma_s = 0.3
sigma_a = 0.05
[materials.floor]
type = "glossy"
albedo = 0.3
ior = 1.5
roughness = 0.1
[[shapes]]
type = "quad"
size = [6, 6]
material = "floor"
transform = { rotate = [-90, 0, 0] }
[[shapes]]
type = "box"
size = [3, 2, 3]
interior = "fog"
transform = { translate = [0, 1.001, 0] }
[[shapes]]
type = "quad"
size = [0.6, 0.6]
emit = 1.0
transform = { rotate = [120, 0, 0], translate = [0.8, 2.4, -0.5] }
[[lights]]
type = "point"
position = [-0.8, 1.6, 0.3]
power = 30.0
[[lights]]
type = "spot"
position = [1.4, 1.8, 1.0]
direction = [-1.4, -1.8, -1.0]
angle = 25.0
power = 40.0
[[lights]]
type = "directional"
direction = [0.4, -1, -0.3]
irradiance = 0.5
"#;

#[test]
fn both_picks_agree_in_a_fog_box_under_every_light_kind() {
    let mut by = Vec::new();
    // Other seeds for each pick: the z's assume independent renders.
    for (pick, seed0) in [("local", 300), ("power", 900)] {
        let set = format!("integrator.light_pick=\"{pick}\"");
        by.push(layer_means(&scene(FOG, &[&set]), 32, seed0));
    }
    let worst = assert_layers_agree("fog box", ("local", "power"), &by[0], &by[1], Z);
    eprintln!("largest |z| {worst:.2}");
}
