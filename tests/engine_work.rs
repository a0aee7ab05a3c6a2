//! The work counters the automatic settings weigh into a pass's cost (`auto::COST_WEIGHTS`)
//! count what they say: here the forward segments, against their expected number.

mod common;

use brume::integrator::Budget;
use common::*;

/// A laser straight down through a unit box of grey fog (sigma_t = 1 /m), a forward ray ending
/// at its first real event (`max_depth = 1`). Each ray traces the air above the box, then the
/// fog; a ray that crosses the fog unscattered (probability e^-1) traces the air below it too.
/// So a ray traces 2 + e^-1 segments on average (one geometry intersection each).
#[test]
fn forward_segments_count_the_rays_flights() {
    let text = r#"
[film]
bins = 4
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
camera_samples = 1
q = 1
max_depth = 1
[media.fog]
sigma_s = 0.5
sigma_a = 0.5
[[shapes]]
type = "box"
size = [1, 1, 1]
interior = "fog"
[[lights]]
type = "laser"
position = [0, 2, 0]
direction = [0, -1, 0]
radius = 0.001
power = 1.0
spectrum = 1.0
"#;
    let setup = scene(text, &[]);
    let passes = 4u32;
    let mut r = setup.renderer(5);
    r.run(Budget::Passes(passes), |_, _| {});
    let stats = r.stats();
    let rays = stats.forward_rays as f64;
    assert_eq!(rays, 4e5, "{stats:?}");
    let mean = stats.forward_segments as f64 / rays;
    let p = (-1.0f64).exp();
    let expected = 2.0 + p;
    // Per ray the count is 2 plus a Bernoulli(p): standard deviation sqrt(p (1 - p)).
    let se = (p * (1.0 - p) / rays).sqrt();
    let z = (mean - expected) / se;
    assert!(
        z.abs() < 4.0,
        "segments per ray {mean} vs {expected} (z = {z:.2})"
    );
}
