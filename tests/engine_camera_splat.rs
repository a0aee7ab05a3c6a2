//! `integrator.splat_to_camera` (light tracing to the camera, `integrator::camera_splat`):
//! forward rays' first surface hits splatted into the pixel that sees them must estimate what
//! next-event estimation computes independently, per pixel, through vacuum and through fog,
//! for a perspective and an orthographic camera, on surfaces and in the fog (single
//! scattering); and a camera path's first surface spheres must leave that light to the splat
//! (no double counting: the splat image does not depend on the gather radius at all when
//! every surface light is direct).

mod common;

use brume::film::SpectralImage;

use common::*;

/// A Lambert floor under a point light, seen by `camera`; a fog slab over the floor when
/// `fog` (its scattered light reaches the floor and the camera as gathered light in both
/// renders). The slab stops 0.1 m above the floor: a floor coplanar with the fog's boundary has
/// no medium on its side (the floor declares none), for shadow rays and splats alike.
fn text(camera: &str, fog: bool, direct: &str, radius: f64) -> String {
    let mut t = format!(
        r#"
[film]
bins = 4
[camera]
{camera}
[integrator]
direct = "{direct}"
splat_to_camera = {splat}
radius = {radius}
forward_rays = 100000
camera_samples = 4
[materials.floor]
type = "lambert"
albedo = 0.6
[[shapes]]
type = "quad"
size = [8, 8]
material = "floor"
transform = {{ rotate = [-90, 0, 0] }}
[[lights]]
type = "point"
position = [0.3, 1.5, -0.2]
power = 100.0
"#,
        splat = direct == "photons",
    );
    if fog {
        t += r#"
[media.fog]
sigma_s = 0.25
sigma_a = 0.15
g = 0.4
[[shapes]]
type = "box"
size = [8, 0.7, 8]
interior = "fog"
transform = { translate = [0, 0.45, 0] }
"#;
    }
    t
}

const PERSPECTIVE: &str = r#"type = "perspective"
width = 12
height = 8
position = [0, 1.6, 2.2]
look_at = [0, 0, 0]
fov = 45"#;

const ORTHOGRAPHIC: &str = r#"type = "orthographic"
width = 10
height = 10
position = [0.1, 3, 0.2]
look_at = [0.1, 0, 0]
up = [0, 0, -1]
view_width = 1.6
view_height = 1.6"#;

/// Layer `layer` ("" for the image) of `runs` independent one-pass renders (independent seeds,
/// so that standard errors come from many samples and the z-scores below are close to normal).
fn runs_of(s: &Setup, first_seed: u64, runs: u64, layer: &str) -> Vec<Vec<f64>> {
    let pick = |img: &SpectralImage| -> Vec<f64> {
        let data = match img.layers.iter().find(|(n, _)| n == layer) {
            Some((_, d)) => d,
            None => &img.data,
        };
        data.iter().map(|&v| v as f64).collect()
    };
    (0..runs)
        .map(|k| pick(&render(s, first_seed + k, 1)))
        .collect()
}

/// Per run, the layer's mean over all pixels in each of `n` bins.
fn image_means(runs: &[Vec<f64>], n: usize) -> Vec<Vec<f64>> {
    runs.iter()
        .map(|r| {
            let pixels = r.len() / n;
            (0..n)
                .map(|b| (0..pixels).map(|p| r[p * n + b]).sum::<f64>() / pixels as f64)
                .collect()
        })
        .collect()
}

/// The splat render's `layer` agrees with next-event estimation's (48 runs each): see
/// [`same_expectation`].
fn agree(camera: &str, fog: bool, layer: &str, max_rel: f64) {
    let nee = scene(&text(camera, fog, "nee", 0.05), &[]);
    let splat = scene(&text(camera, fog, "photons", 0.05), &[]);
    let what = format!("{camera:.20} fog {fog} {layer}");
    same_expectation(&what, (&nee, 500), (&splat, 700), layer, max_rel);
}

/// Layer `layer` of two renders (48 runs each from the given first seeds) has the same
/// expectation: every pixel and bin within |z| <= 4.5 (a few hundred comparisons, so a false
/// alarm has odds of a few percent at worst, and the seeds are fixed), with a mean relative
/// standard error below `max_rel`; and the image mean per bin within |z| <= 4 with a relative
/// standard error below 1 %, which a bias of a few percent anywhere would fail.
fn same_expectation(what: &str, a: (&Setup, u64), b: (&Setup, u64), layer: &str, max_rel: f64) {
    let runs = 48;
    let a = runs_of(a.0, a.1, runs, layer);
    let b = runs_of(b.0, b.1, runs, layer);
    let compare = |a: &[Vec<f64>], b: &[Vec<f64>], part: &str, max_z: f64, max_rel: f64| {
        let (a, b) = (mean_and_se(a, a[0].len()), mean_and_se(b, b[0].len()));
        let (mut worst, mut rel) = (0.0f64, 0.0);
        for i in 0..a.0.len() {
            let se = (a.1[i].powi(2) + b.1[i].powi(2)).sqrt();
            worst = worst.max(((b.0[i] - a.0[i]) / se.max(1e-30)).abs());
            rel += se / a.0[i].abs().max(1e-30);
        }
        rel /= a.0.len() as f64;
        eprintln!("{what} {part}: worst |z| {worst:.2}, mean rel. se {rel:.4}");
        assert!(worst <= max_z, "{what} {part}: worst |z| = {worst}");
        assert!(rel < max_rel, "{what} {part}: too noisy to tell: {rel}");
    };
    compare(&a, &b, "pixels", 4.5, max_rel);
    compare(
        &image_means(&a, 4),
        &image_means(&b, 4),
        "image mean",
        4.0,
        0.01,
    );
}

#[test]
fn splat_matches_next_event_estimation_perspective() {
    agree(PERSPECTIVE, false, "", 0.03);
}

/// The fog's single scattering splatted from one point of each first flight (the medium layer;
/// gathered multiple scattering in both renders).
#[test]
fn splat_matches_next_event_estimation_in_the_fog() {
    agree(PERSPECTIVE, true, "medium", 0.1);
}

#[test]
fn splat_matches_next_event_estimation_orthographic_through_fog() {
    // The surface layer: the splat changes only it (the fog's gathered layer is the same
    // estimator in both renders, and its noise would hide the comparison).
    agree(ORTHOGRAPHIC, true, "surface", 0.06);
}

/// In vacuum all the floor's light is direct: with the splat on, the camera's surface spheres
/// gather nothing, so the image is the same bits at any radius (the forward rays do not depend
/// on it for a point light), whereas with the splat off the radius changes it.
#[test]
fn first_surface_spheres_leave_direct_light_to_the_splat() {
    let img = |radius: f64, splat: bool| {
        let t = text(PERSPECTIVE, false, "photons", radius);
        let t = t.replace(
            "splat_to_camera = true",
            &format!("splat_to_camera = {splat}"),
        );
        render(&scene(&t, &[]), 3, 2).data
    };
    assert_eq!(img(0.02, true), img(0.2, true));
    assert_ne!(img(0.02, false), img(0.2, false));
}

/// A mirror standing beside the floor, which reflects the point light onto it (a caustic).
const MIRROR: &str = r#"
[materials.mirror]
type = "mirror"
albedo = 0.9
[[shapes]]
type = "quad"
size = [8, 3]
material = "mirror"
transform = { rotate = [0, -90, 0], translate = [1.0, 1.5, 0] }
"#;

/// Caustic light: a point light's reflection in a mirror lights the floor (a smooth caustic,
/// the light of a mirrored point light). Splatted (the forward rays' chain light -> mirror ->
/// floor is specular) it has the expectation of the surface spheres' estimate at a small
/// radius (whose blur of this smooth light is far below the noise).
#[test]
fn caustic_splat_matches_the_gathered_caustic() {
    let t = |splat: bool| {
        text(ORTHOGRAPHIC, false, "photons", 0.01).replace(
            "splat_to_camera = true",
            &format!("splat_to_camera = {splat}"),
        ) + MIRROR
    };
    let (on, off) = (scene(&t(true), &[]), scene(&t(false), &[]));
    same_expectation("mirror caustic", (&on, 900), (&off, 1100), "", 0.1);
}

/// `splat_to_camera` absent: on where next-event estimation leaves a light's direct light to
/// forward rays (here a laser's spot on the floor), off with `direct = "photons"` and where
/// next-event estimation handles every light (here with a mirror, whose caustic the splat
/// would otherwise take: so each default is told apart from the other value).
#[test]
fn the_splat_is_on_by_default_where_next_event_estimation_leaves_a_light_to_forward_rays() {
    const LASER: &str = r#"
[[lights]]
type = "laser"
position = [-0.8, 1.0, 0.1]
direction = [0.8, -1.0, -0.1]
radius = 0.01
power = 20.0
"#;
    let img = |direct: &str, extra: &str, splat: Option<bool>| {
        let t = text(PERSPECTIVE, false, direct, 0.05) + extra;
        let key = match splat {
            Some(on) => format!("splat_to_camera = {on}"),
            None => String::new(),
        };
        let t = t
            .replace("splat_to_camera = true", &key)
            .replace("splat_to_camera = false", &key);
        render(&scene(&t, &[]), 3, 2).data
    };
    for (direct, extra, on) in [
        ("nee", LASER, true),
        ("photons", LASER, false),
        ("nee", MIRROR, false),
    ] {
        let default = img(direct, extra, None);
        assert_eq!(default, img(direct, extra, Some(on)), "{direct}: default");
        assert_ne!(
            default,
            img(direct, extra, Some(!on)),
            "{direct}: other value"
        );
    }
}
