//! The command line: exit codes, one-line errors naming file, line and key, and no output left
//! behind by a failed render.

use std::path::Path;
use std::process::Command;

fn brume() -> Command {
    Command::new(env!("CARGO_BIN_EXE_brume"))
}

const SCENE: &str = r#"
[camera]
type = "orthographic"
width = 8
height = 8
position = [0, 0, 2]
view_width = 1.0
view_height = 1.0
[integrator]
forward_rays = 2000
passes = 1
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
irradiance = 100.0
"#;

fn write_scene(dir: &Path, text: &str) -> std::path::PathBuf {
    let p = dir.join("scene.toml");
    std::fs::write(&p, text).expect("write scene");
    p
}

#[test]
fn renders_exr_and_png() {
    let dir = tempfile::tempdir().expect("tempdir");
    let scene = write_scene(dir.path(), SCENE);
    let (exr, png) = (dir.path().join("a.exr"), dir.path().join("a.png"));
    let out = brume()
        .arg("render")
        .arg(&scene)
        .args([
            "-o",
            exr.to_str().unwrap(),
            "-o",
            png.to_str().unwrap(),
            "--passes",
            "2",
            "--seed",
            "3",
        ])
        .output()
        .expect("run brume");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(std::fs::metadata(&exr).expect("exr").len() > 0);
    assert!(std::fs::metadata(&png).expect("png").len() > 0);
}

#[test]
fn malformed_scene_fails_with_position_and_writes_nothing() {
    let dir = tempfile::tempdir().expect("tempdir");
    for (bad, key, line) in [
        (SCENE.replace("width = 8", "width = -8"), "camera.width", 4),
        (
            SCENE.replace("passes = 1", "passes = 1\nbogus = 3"),
            "integrator.bogus",
            12,
        ),
        (
            SCENE.replace("albedo = 0.5", "texture = \"missing.png\""),
            "materials.wall.texture",
            14,
        ),
    ] {
        let scene = write_scene(dir.path(), &bad);
        let exr = dir.path().join("bad.exr");
        let out = brume()
            .arg("render")
            .arg(&scene)
            .args(["-o", exr.to_str().unwrap()])
            .output()
            .expect("run brume");
        assert!(!out.status.success());
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(err.trim_end().lines().count(), 1, "one line: {err}");
        assert!(err.contains(&format!("scene.toml:{line}:")), "{err}");
        assert!(err.contains(key), "{err}");
        assert!(!exr.exists(), "no output after a failure");
        let leftovers: Vec<_> = std::fs::read_dir(dir.path())
            .expect("dir")
            .filter_map(|e| e.ok())
            .filter(|e| e.file_name().to_string_lossy().contains(".tmp"))
            .collect();
        assert!(leftovers.is_empty(), "temporary files left: {leftovers:?}");
    }
}

#[test]
fn unknown_set_path_fails() {
    let dir = tempfile::tempdir().expect("tempdir");
    let scene = write_scene(dir.path(), SCENE);
    let out = brume()
        .args(["info"])
        .arg(&scene)
        .args(["--set", "integrator.nope=1"])
        .output()
        .expect("run brume");
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("--set integrator.nope=1") && err.contains("integrator.nope"),
        "{err}"
    );
}

#[test]
fn info_succeeds_on_every_shipped_scene() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes");
    for entry in std::fs::read_dir(dir).expect("scenes/") {
        let path = entry.expect("entry").path();
        if path.extension().is_some_and(|e| e == "toml") {
            let out = brume().arg("info").arg(&path).output().expect("run brume");
            assert!(
                out.status.success(),
                "{}: {}",
                path.display(),
                String::from_utf8_lossy(&out.stderr)
            );
            assert!(String::from_utf8_lossy(&out.stdout).contains("integration volumes"));
            assert!(out.stderr.is_empty(), "no warnings on shipped scenes");
        }
    }
}

/// `brume info` shows the scene file's spellings, and prints the scene's warnings (here: no
/// light) on stderr without failing.
#[test]
fn info_speaks_the_file_format_and_prints_warnings() {
    let dir = tempfile::tempdir().expect("tempdir");
    let scene = write_scene(dir.path(), SCENE);
    let out = brume()
        .arg("info")
        .arg(&scene)
        .args(["--set", "integrator.volume=cylinder-truncated"])
        .args(["--set", "integrator.mode=see-through"])
        .output()
        .expect("run brume");
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        stdout.contains("volume cylinder-truncated, mode see-through"),
        "{stdout}"
    );
    let dark = SCENE.replace("[[lights]]", "[[ignored]]");
    let dark = dark
        .split("[[ignored]]")
        .next()
        .expect("scene before the light");
    let scene = write_scene(dir.path(), dark);
    let out = brume().arg("info").arg(&scene).output().expect("run brume");
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{err}");
    assert!(
        err.starts_with("brume: warning: ") && err.contains("no light that emits"),
        "{err}"
    );
}

#[test]
fn help_documents_every_flag() {
    let out = brume()
        .args(["render", "--help"])
        .output()
        .expect("run brume");
    let text = String::from_utf8_lossy(&out.stdout);
    for flag in [
        "--output",
        "--passes",
        "--time",
        "--seed",
        "--threads",
        "--set",
    ] {
        assert!(text.contains(flag), "render --help lacks {flag}");
    }
}

#[path = "cli/docs_examples.rs"]
mod docs_examples;

#[path = "cli/photometry.rs"]
mod photometry;

#[path = "cli/auto_settings.rs"]
mod auto_settings;

#[path = "cli/trust.rs"]
mod trust;
