//! Input limits: values outside physical or practical ranges are refused with a clear error
//! before any heavy allocation, and a render too large for the machine needs `--force`.

use std::path::Path;

use brume::scene::load_str;

const BASE: &str = r#"
[camera]
width = 8
height = 8

[media.fog]
sigma_s = 0.5
sigma_a = 0.1
g = 0.2

[materials.wall]
type = "lambert"
albedo = 0.4

[[shapes]]
type = "box"
size = [1, 1, 1]
interior = "fog"

[[lights]]
type = "directional"
direction = [0, 0, -1]
irradiance = 1.0
"#;

fn error(text: &str, dir: &Path, sets: &[&str]) -> String {
    let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
    match load_str(text, &dir.join("scene.toml"), &sets) {
        Ok(_) => panic!("accepted: {sets:?}"),
        Err(e) => e.to_string(),
    }
}

#[test]
fn out_of_range_values_are_refused_with_their_key() {
    let d = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes");
    let cases: &[(&str, &str)] = &[
        ("media.fog.sigma_s=-1", "media.fog.sigma_s"),
        ("media.fog.sigma_a=-0.1", "media.fog.sigma_a"),
        ("media.fog.g=1.0", "media.fog.g"),
        ("media.fog.g=-1.0", "media.fog.g"),
        ("media.fog.g=nan", "media.fog.g"),
        ("integrator.q=0", "integrator.q"),
        ("integrator.q=1.5", "integrator.q"),
        ("camera.width=0", "camera.width"),
        ("camera.height=100000", "camera.height"),
        ("film.bins=65", "film.bins"),
        ("film.bins=0", "film.bins"),
        ("integrator.radius=0", "integrator.radius"),
        ("integrator.radius=inf", "integrator.radius"),
    ];
    for (set, key) in cases {
        let e = error(BASE, &d, &[set]);
        assert!(e.contains(key), "{set}: {e}");
    }
    load_str(BASE, &d.join("scene.toml"), &[]).expect("the base scene is valid");
}

/// A PNG whose header claims 100000 x 100000 pixels (no pixel data follows).
fn forged_png(path: &Path) {
    let mut ihdr = Vec::new();
    ihdr.extend_from_slice(b"IHDR");
    ihdr.extend_from_slice(&100_000u32.to_be_bytes());
    ihdr.extend_from_slice(&100_000u32.to_be_bytes());
    ihdr.extend_from_slice(&[8, 2, 0, 0, 0]);
    let mut file = b"\x89PNG\r\n\x1a\n".to_vec();
    file.extend_from_slice(&13u32.to_be_bytes());
    file.extend_from_slice(&ihdr);
    file.extend_from_slice(&crc32(&ihdr).to_be_bytes());
    for tag in [b"IDAT", b"IEND"] {
        file.extend_from_slice(&0u32.to_be_bytes());
        file.extend_from_slice(tag);
        file.extend_from_slice(&crc32(tag).to_be_bytes());
    }
    std::fs::write(path, file).unwrap();
}

fn crc32(bytes: &[u8]) -> u32 {
    let mut c = 0xffff_ffffu32;
    for b in bytes {
        c ^= *b as u32;
        for _ in 0..8 {
            c = if c & 1 != 0 {
                0xedb8_8320 ^ (c >> 1)
            } else {
                c >> 1
            };
        }
    }
    !c
}

#[test]
fn an_absurd_texture_is_refused_from_its_header() {
    let t = tempfile::tempdir().unwrap();
    forged_png(&t.path().join("huge.png"));
    std::fs::write(t.path().join("junk.png"), b"not an image").unwrap();
    let text = format!("{BASE}\n[materials.tex]\ntype = \"lambert\"\ntexture = \"huge.png\"\n");
    let e = error(&text, t.path(), &[]);
    assert!(e.contains("100000x100000"), "{e}");
    let text = text.replace("huge.png", "junk.png");
    let e = error(&text, t.path(), &[]);
    assert!(e.contains("not a readable image"), "{e}");
}

#[test]
fn a_render_larger_than_memory_needs_force() {
    let t = tempfile::tempdir().unwrap();
    let scene = t.path().join("big.toml");
    std::fs::write(&scene, BASE).unwrap();
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_brume"))
        .current_dir(t.path())
        .args(["render", scene.to_str().unwrap(), "--passes", "1"])
        .args(["--set", "camera.width=32768", "--set", "camera.height=4096"])
        .args(["--set", "film.bins=64", "-o", "x.exr"])
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success());
    assert!(err.contains("--force") && err.contains("GiB"), "{err}");
    assert!(!t.path().join("x.exr").exists());
}

/// The bound on light power is where the film's fixed-point sums stop holding a render: a lamp
/// of `MAX_POWER` renders with nothing dropped, while one 1e21 times brighter (1e30 W, which the
/// audit found rendering black with rc 0) loses its samples. The scene refuses it beforehand.
#[test]
fn the_largest_accepted_light_power_renders_and_a_larger_one_would_not() {
    use brume::integrator::{Budget, Renderer};
    use brume::light::{Light, LightSet};
    let text = format!(
        r#"
[camera]
type = "orthographic"
width = 16
height = 16
position = [0, 0, 2]
[integrator]
forward_rays = 20000
[materials.wall]
type = "lambert"
albedo = 0.5
[[shapes]]
type = "quad"
size = [1, 1]
material = "wall"
[[lights]]
type = "point"
position = [0, 0, 1]
power = {}
"#,
        brume::scene::MAX_POWER
    );
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes");
    let loaded = load_str(&text, &dir.join("scene.toml"), &[]).expect("the bound is accepted");
    let mut scene = brume::scene::build(&loaded).expect("builds");
    let render = |scene: &brume::scene::Scene| {
        let integrator = brume::scene::build_integrator(&loaded, scene).expect("integrator");
        let mut r = Renderer::new(scene, integrator, 5);
        r.run(Budget::Passes(2), |_, _| {});
        let mean = r.image().data.iter().map(|v| *v as f64).sum::<f64>();
        (r.film().dropped, mean)
    };
    let (dropped, sum) = render(&scene);
    assert_eq!(dropped, 0, "nothing dropped at the bound");
    assert!(sum.is_finite() && sum > 0.0);

    let Light::Point { position, power } = scene.lights.lights()[0].clone() else {
        panic!("a point light")
    };
    let brighter = Light::point(position, power * 1e21);
    scene.lights = LightSet::new(vec![brighter], &scene.geometry, &scene.grid);
    let (dropped, _) = render(&scene);
    assert!(dropped > 0, "1e30 W overflows the film");

    let e = error(
        &text.replace("power = 1000000000", "power = 1e30"),
        &dir,
        &[],
    );
    assert!(e.contains("key `lights.0.power`"), "{e}");
}

/// Issue 31: `integrator.q = 1e-9` on a 32 x 32 fog-cube grew about 160 MB/s until memory ran
/// out, and q = 1e-5 with `max_gather_bytes = 1e8` reached 2.6 GB. A budget that cannot hold
/// one camera path's expected records is refused before anything is built, by render and info
/// alike, with the estimate; a row of camera paths over the budget (32 x 2 paths of ~63 000
/// volumes, 1.1 GiB, against 95 MiB) stops the render at once with an error. Run under
/// `ulimit -v` and a timeout, so that a regression fails instead of exhausting the machine.
#[test]
fn gather_memory_over_the_budget_is_refused_or_stopped() {
    let t = tempfile::tempdir().unwrap();
    let scene = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/fog-cube.toml");
    let size = "--set camera.width=32 --set camera.height=32";
    let refused = "one camera path may leave 264.5 GiB of gather records, more than the gather \
                   budget of 4.0 GiB";
    for (command, sets, message) in [
        ("render", "--set integrator.q=1e-9", refused),
        ("info", "--set integrator.q=1e-9", refused),
        (
            "render",
            "--set integrator.q=1e-5 --set integrator.max_gather_bytes=100000000",
            "over the gather budget of 95.4 MiB",
        ),
    ] {
        let output = if command == "render" { "-o x.exr" } else { "" };
        let script = format!(
            "ulimit -v 2000000; exec timeout 60 '{}' {command} '{}' {size} {sets} {output}",
            env!("CARGO_BIN_EXE_brume"),
            scene.display()
        );
        let t0 = std::time::Instant::now();
        let out = std::process::Command::new("sh")
            .current_dir(t.path())
            .args(["-c", &script])
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{command} {sets}: {err}");
        assert!(
            err.contains(message)
                && err.contains("integrator.q")
                && err.contains("integrator.max_gather_bytes"),
            "{err}"
        );
        assert!(
            t0.elapsed().as_secs() < 20,
            "{command} {sets}: not stopped at once"
        );
        assert!(!t.path().join("x.exr").exists());
    }
}
