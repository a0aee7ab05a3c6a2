//! Integration spheres at the surfaces that bound their camera segment
//! (`integrator::boundary`): a ball that reaches through the floor under the fog holds no
//! forward rays below it, so the plain sphere estimator reads the fog near the floor low (by up
//! to half at the floor). The camera segment's bounding planes clip both the ball and the
//! forward chords, and the weight divides by the clipped ball's volume.
//!
//! Scene: a fog box (index-matched, so its bottom face 1 mm above the floor is looked through
//! to the floor) lit by a parallel light travelling along +X, parallel to a black floor; an
//! orthographic camera inside the fog looks 30 degrees down at the floor; single scattering
//! only (`direct = "photons"`, `max_depth = 1`). The fluence `E e^{-st (x + 1.5)}` does not
//! depend on the height, so averaging it over a ball clipped by the floor's plane is exact up to
//! the ball's O((st R)^2) blur along X (4e-4 here): the radiance has a closed form, and a radius
//! of 0.15 m makes the floor's bias (about -4 % of the viewed square) ten standard errors.
//! Fixed seeds; per bin, |z| <= 4 with no kernel allowance.

mod common;

use std::f64::consts::PI;

use common::*;

const Z: f64 = 4.0;
const BINS: usize = 2;
const SIGMA_S: f64 = 0.3;
const SIGMA_T: f64 = 0.4;
const E: f64 = 2.0;
/// Camera: orthographic, its centre at (0, 0.6, 0), looking along (0, -sin 30°, -cos 30°),
/// viewing 0.3 x 0.3 m.
const CAM_Y: f64 = 0.6;
const VIEW: f64 = 0.3;
/// The fog's bottom face, 1 mm above the floor.
const BOTTOM: f64 = 0.001;
const CAM_Z: f64 = 0.5;
/// The light travels along (1, -TILT, 0): the floor shadows the space below it (a light
/// parallel to the floor would light it, and open media gather light there).
const TILT: f64 = 0.2;

fn fog_text() -> String {
    let (s, c) = (30f64.to_radians().sin(), 30f64.to_radians().cos());
    format!(
        r#"
[film]
bins = {BINS}
[camera]
type = "orthographic"
width = 8
height = 8
position = [0, {CAM_Y}, {CAM_Z}]
look_at = [0, {}, {}]
view_width = {VIEW}
view_height = {VIEW}
[integrator]
radius = 0.15
forward_rays = 200000
camera_samples = 32
direct = "photons"
max_depth = 1
[media.fog]
sigma_s = {SIGMA_S}
sigma_a = {}
[materials.black]
type = "lambert"
albedo = 0.0
[[shapes]]
type = "box"
size = [1, 1, 2]
interior = "fog"
transform = {{ translate = [0, {}, 0] }}
[[shapes]]
type = "quad"
size = [2, 3]
material = "black"
transform = {{ rotate = [-90, 0, 0] }}
[[lights]]
type = "directional"
direction = [1, {}, 0]
irradiance = {E}
spectrum = 1.0
"#,
        CAM_Y - s,
        CAM_Z - c,
        SIGMA_T - SIGMA_S,
        0.5 + BOTTOM,
        -TILT,
    )
}

/// Single scattering averaged over the viewed square: at a ray from `o` (down 30°),
/// per bin `L = ss/(4 pi) (E / 400 nm) e^{-st (o_x + 1.5)} (1 - e^{-st T}) / st`,
/// `T = (o_y - BOTTOM) / sin 30°` the distance to the fog's bottom face, averaged over a fine
/// lattice of ray origins (the camera's right is +X, its up (0, cos 30°, -sin 30°)).
fn expected() -> f64 {
    let (s, c) = (30f64.to_radians().sin(), 30f64.to_radians().cos());
    // Radiance is per nm: a flat spectrum spreads the irradiance over 380-780 nm.
    let e_nm = E / 400.0;
    let m = 256;
    let mut sum = 0.0;
    for i in 0..m {
        for j in 0..m {
            let a = VIEW * ((i as f64 + 0.5) / m as f64 - 0.5);
            let b = VIEW * ((j as f64 + 0.5) / m as f64 - 0.5);
            let (ox, oy) = (a, CAM_Y + b * c);
            let t = (oy - BOTTOM) / s;
            sum += SIGMA_S / (4.0 * PI)
                * e_nm
                * (-SIGMA_T * (ox + 0.5) * (1.0 + TILT * TILT).sqrt()).exp()
                * (1.0 - (-SIGMA_T * t).exp())
                / SIGMA_T;
        }
    }
    sum / (m * m) as f64
}

#[test]
fn spheres_clipped_at_the_floor_match_single_scattering() {
    let want = expected();
    let expected = vec![want; BINS];
    for (name, q) in [
        ("spheres q=1", "integrator.q=1"),
        ("spheres q=0.3", "integrator.q=0.3"),
    ] {
        let s = scene(&fog_text(), &[q]);
        let (mean, se) = independent_estimates(&s, 8, 2, (0, 8, 0, 8));
        assert_bins(name, &mean, &se, &expected, Z, 0.0);
    }
}
