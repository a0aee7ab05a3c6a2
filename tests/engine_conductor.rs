//! The conductor in the engine: a rough gold floor under an area light (an emitting quad), seen
//! where the light's reflection is. With `direct = "photons"` only the camera paths' lobe
//! samples that hit the emitter carry the reflection; with `nee` light samples weighted against
//! the lobe's samples by the power heuristic carry it too, the samples that hit the emitter
//! taking the complementary weight. Both agree per bin (|z| <= 4) for a rough, a sharp and a
//! smooth (delta) metal, so the conductor's eval, pdf and sampling are one lobe to both sides
//! of the multiple importance sampling.

mod common;

use common::*;

const Z: f64 = 4.0;

#[test]
fn conductor_reflection_of_an_area_light_agrees_between_direct_modes() {
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
forward_rays = 20000
camera_samples = 16
[materials.floor]
type = "conductor"
eta = "gold"
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
    for roughness in ["0.2", "0.05", "0"] {
        let mut by_mode = Vec::new();
        for direct in ["nee", "photons"] {
            let s = scene(
                text,
                &[
                    &format!("integrator.direct=\"{direct}\""),
                    &format!("materials.floor.roughness={roughness}"),
                ],
            );
            // The rows below the emitter (rows 0-1 hold it, whose edges' pixel coverage would
            // be the noise): its reflection and the dark floor.
            by_mode.push(independent_estimates(&s, 12, 2, (0, 12, 3, 12)));
        }
        let ((a, sa), (b, sb)) = (&by_mode[0], &by_mode[1]);
        for bin in 0..a.len() {
            let se = (sa[bin].powi(2) + sb[bin].powi(2)).sqrt();
            let z = (a[bin] - b[bin]) / se;
            eprintln!(
                "roughness {roughness} bin {bin}: nee {:.5e} +- {:.1e}, photons {:.5e} +- {:.1e} (z {z:.2})",
                a[bin], sa[bin], b[bin], sb[bin]
            );
            assert!(
                a[bin] > 0.0,
                "roughness {roughness} bin {bin}: no reflection seen"
            );
            if z.abs() > Z {
                wrong.push(format!("roughness {roughness} bin {bin}: z = {z:.2}"));
            }
        }
    }
    assert!(wrong.is_empty(), "{}", wrong.join("\n"));
}
