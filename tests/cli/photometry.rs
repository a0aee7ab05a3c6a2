//! The photometric commands and outputs: sensors printed and written beside the image (and
//! by `merge`, bit-identical to a single run), the false-colour map, `probe`, luminous
//! efficacy in `spectrum`, the meteorological optical range in `info` and fog given by its
//! visibility.

use std::path::Path;

use super::{brume, write_scene};

const SCENE: &str = r#"
[film]
units = "photometric"
noise_layer = true
false_colour = true
light_layers = true
[camera]
type = "orthographic"
width = 8
height = 8
position = [0, 0, 2]
view_width = 1.0
view_height = 1.0
[integrator]
forward_rays = 2000
passes = 3
[materials.wall]
type = "lambert"
albedo = 0.5
[[shapes]]
type = "quad"
size = [1, 1]
material = "wall"
[[lights]]
type = "directional"
direction = [0, 0, -1]
illuminance = 1000.0
[[sensors]]
name = "wall"
type = "luminance"
region = [2, 2, 6, 6]
[[sensors]]
type = "illuminance"
position = [0, 0, 0]
normal = [0, 0, 1]
"#;

fn run(args: &[&str]) -> (String, String) {
    let out = brume().args(args).output().expect("run brume");
    let (o, e) = (
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    );
    assert!(out.status.success(), "brume {args:?}: {e}");
    (o, e)
}

fn s(p: &Path) -> &str {
    p.to_str().expect("utf-8")
}

#[test]
fn sensors_false_colour_and_probe() {
    let dir = tempfile::tempdir().expect("tempdir");
    let scene = write_scene(dir.path(), SCENE);
    let exr = dir.path().join("a.exr");
    let (out, _) = run(&["render", s(&scene), "-o", s(&exr), "--seed", "5"]);
    assert!(
        out.contains("wall") && out.contains("cd/m2") && out.contains("sensor1"),
        "{out}"
    );
    for f in ["a.sensors.csv", "a.sensors.json", "a-luminance.png"] {
        assert!(dir.path().join(f).is_file(), "{f} written");
    }
    let csv = std::fs::read_to_string(dir.path().join("a.sensors.csv")).expect("csv");
    let row = csv.lines().nth(1).expect("a row");
    assert!(row.starts_with("wall,luminance,"), "{csv}");
    let json: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(dir.path().join("a.sensors.json")).expect("json"),
    )
    .expect("parses");
    let wall = &json["sensors"][0];
    assert_eq!(wall["passes"], 3);
    let value = wall["value"].as_f64().expect("value");
    // A Lambertian wall of albedo 0.5 under 1000 lx: 500 / pi cd/m².
    // A sanity bound at 3 passes; the statistical test of the luminance sensor is the
    // integrator's (lead's) end-to-end test.
    assert!(
        (value / (500.0 / std::f64::consts::PI) - 1.0).abs() < 0.25,
        "{value}"
    );
    // probe reads the same luminance back from the EXR (cd/m², photometric).
    let (probe, _) = run(&["probe", s(&exr), "--region", "2,2,6,6", "--json"]);
    let p: serde_json::Value = serde_json::from_str(&probe).expect("probe json");
    let mean = p["luminance_cd_m2"].as_f64().expect("cd");
    assert!((mean / value - 1.0).abs() < 1e-3, "{mean} vs {value}");
    assert!(p["std_error"].as_f64().expect("noise") > 0.0);
    // Pixels taken as independent: the region's error is only a lower bound (issue 31), and
    // says so.
    assert_eq!(p["std_error_is_lower_bound"], true, "{p}");
    let (text, _) = run(&["probe", s(&exr), "--region", "2,2,6,6"]);
    assert!(text.contains("LOWER BOUND"), "{text}");
    let (text, _) = run(&["probe", s(&exr), "--px", "3,3"]);
    assert!(text.contains("cd/m2 (photometric EXR)"), "{text}");
    let out = brume()
        .args(["probe", s(&exr), "--px", "9,0"])
        .output()
        .expect("run");
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("outside the 8x8 image"));
}

/// Parts rendered with `--pass-range` merge into the sensors and light layers of one run.
#[test]
fn merged_parts_give_the_single_run_sensors() {
    let dir = tempfile::tempdir().expect("tempdir");
    let scene = write_scene(dir.path(), SCENE);
    let d = |f: &str| dir.path().join(f);
    run(&[
        "render",
        s(&scene),
        "-o",
        s(&d("one.exr")),
        "-o",
        s(&d("one.brume")),
    ]);
    for (range, part) in [("0..1", "p0.brume"), ("1..3", "p1.brume")] {
        run(&[
            "render",
            s(&scene),
            "--pass-range",
            range,
            "-o",
            s(&d(part)),
        ]);
    }
    let (out, _) = run(&[
        "merge",
        s(&d("p1.brume")),
        s(&d("p0.brume")),
        "-o",
        s(&d("two.exr")),
        "-o",
        s(&d("two.brume")),
    ]);
    assert!(out.contains("wall"), "{out}");
    let one = std::fs::read_to_string(d("one.sensors.json")).expect("one");
    let two = std::fs::read_to_string(d("two.sensors.json")).expect("two");
    assert_eq!(one, two, "bit for bit");
    // The films (sums of pixels, light layers and sensors) are the same bytes.
    assert_eq!(
        std::fs::read(d("one.brume")).ok(),
        std::fs::read(d("two.brume")).ok()
    );
}

#[test]
fn spectrum_prints_luminous_efficacy() {
    let (out, _) = run(&["spectrum", "D65", "--json"]);
    let v: serde_json::Value = serde_json::from_str(&out).expect("json");
    let e = v["luminous_efficacy_lm_per_w"].as_f64().expect("efficacy");
    // D65 over 380-780 nm: about 250 lm/W (CIE 1931 V, K_m = 683).
    assert!((200.0..300.0).contains(&e), "{e}");
    let (text, _) = run(&["spectrum", "A"]);
    assert!(
        text.contains("luminous efficacy") && text.contains("lm/W"),
        "{text}"
    );
}

/// Grey fog given by its visibility V: sigma_t = ln(20) / V, and `info` prints V back as its
/// meteorological optical range.
#[test]
fn fog_given_by_visibility_has_that_optical_range() {
    let dir = tempfile::tempdir().expect("tempdir");
    let fog = "[media.fog]\nvisibility = 37.5\nalbedo = 0.9\n[[shapes]]\ntype = \"box\"\n\
               size = [1, 1, 1]\ninterior = \"fog\"\n";
    let scene = write_scene(dir.path(), &format!("{SCENE}{fog}"));
    let (out, _) = run(&["info", s(&scene)]);
    let line = out
        .lines()
        .find(|l| l.contains("meteorological optical range"))
        .expect("MOR line");
    let mor: f64 = line
        .split(':')
        .nth(1)
        .and_then(|v| v.trim().trim_end_matches(" m").parse().ok())
        .expect("a number");
    assert!((mor / 37.5 - 1.0).abs() < 1e-5, "{line}");
    let sigma = 20f64.ln() / 37.5;
    assert!(out.contains(&format!("{sigma:.6}")), "{out}");
    assert!(out.contains("0.900000"), "albedo: {out}");
    let bad = fog.replace("albedo = 0.9\n", "albedo = 0.9\nsigma_s = 0.1\n");
    let scene = write_scene(dir.path(), &format!("{SCENE}{bad}"));
    let out = brume().arg("info").arg(&scene).output().expect("run");
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        !out.status.success() && err.contains("media.fog.sigma_s"),
        "{err}"
    );
}

/// Issue 31 item 14: `probe` over NaN or infinite pixels printed NaN with exit 0. Now they are
/// counted and left out with a warning, and a region with no finite pixel is refused.
#[test]
fn probe_reports_non_finite_pixels() {
    let dir = tempfile::tempdir().expect("tempdir");
    let path = dir.path().join("nan.exr");
    // Row 0: NaN, +inf, then 1.0; row 1: all 1.0 (grey, so Y = 1).
    exr::prelude::write_rgb_file(&path, 4, 2, |x, y| {
        let v = match (x, y) {
            (0, 0) => f32::NAN,
            (1, 0) => f32::INFINITY,
            _ => 1.0,
        };
        (v, v, v)
    })
    .expect("write exr");
    let out = brume()
        .args(["probe", s(&path), "--region", "0,0,4,2", "--json"])
        .output()
        .expect("run");
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{err}");
    assert!(
        err.contains("2 of the region's 8 pixels are NaN or infinite"),
        "{err}"
    );
    let p: serde_json::Value = serde_json::from_slice(&out.stdout).expect("probe json");
    assert_eq!(p["pixels"], 6);
    assert_eq!(p["non_finite_pixels"], 2);
    assert!(
        (p["mean"].as_f64().expect("a number") - 1.0).abs() < 1e-6,
        "{p}"
    );
    for at in [["--px", "0,0"], ["--region", "0,0,2,1"]] {
        let out = brume()
            .args(["probe", s(&path), at[0], at[1]])
            .output()
            .expect("run");
        assert!(!out.status.success(), "{at:?}: meaningless, yet exit 0");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains("NaN or infinite: no statistics"), "{err}");
        assert!(!String::from_utf8_lossy(&out.stdout).contains("NaN"));
    }
}

/// Issue 31: with `film.units = "photometric"` and no exposure, the 159 cd/m² wall (albedo 0.5
/// under 1000 lx) came out as PNG (7, 7, 7). A photometric film meters by default: the wall,
/// the whole image, lands on middle grey (sRGB code 118).
#[test]
fn a_photometric_film_is_exposed_by_default() {
    let dir = tempfile::tempdir().expect("tempdir");
    let scene = write_scene(dir.path(), SCENE);
    let png = dir.path().join("wall.png");
    run(&["render", s(&scene), "-o", s(&png), "--seed", "5", "-q"]);
    let img = image::open(&png).expect("png").to_rgb8();
    let c = img.get_pixel(4, 4).0;
    for v in c {
        assert!((100..=140).contains(&v), "{c:?}");
    }
    // An explicit exposure still rules: 0 stops shows the film's own values (dark).
    let png0 = dir.path().join("wall0.png");
    let set = "film.exposure=0";
    run(&["render", s(&scene), "--set", set, "-o", s(&png0), "-q"]);
    let c = image::open(&png0).expect("png").to_rgb8().get_pixel(4, 4).0;
    assert!(c.iter().all(|v| *v < 20), "{c:?}");
}
