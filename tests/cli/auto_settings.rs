//! Automatic settings (`"auto"` q, forward rays and camera paths): the choice comes from pilot
//! passes of the seed alone, so a render in one go, in parts merged out of order, resumed from
//! a checkpoint and on any thread count give the same bytes; the choice is printed by `-v` and
//! written into the EXR's metadata.

use std::path::Path;

use super::{brume, write_scene};

/// A small fog box under a lamp, every sampling budget automatic (the default).
const SCENE: &str = r#"
[camera]
position = [0, 0, 3]
look_at = [0, 0, 0]
fov = 40
width = 20
height = 16
[integrator]
radius = 0.05
q = "auto"
forward_rays = "auto"
camera_samples = "auto"
[media.fog]
sigma_s = 1.5
sigma_a = 0.1
g = 0.3
[materials.wall]
type = "lambert"
albedo = 0.6
[[shapes]]
type = "quad"
size = [3, 3]
material = "wall"
[[shapes]]
type = "box"
size = [1.5, 1.5, 1.5]
interior = "fog"
transform = { translate = [0, 0, 0.8] }
[[lights]]
type = "point"
position = [0.4, 0.6, 2.0]
power = 20.0
"#;

fn run(dir: &Path, args: &[&str]) -> String {
    let scene = dir.join("scene.toml");
    let mut all = vec!["render", scene.to_str().unwrap_or_default()];
    all.extend_from_slice(args);
    let out = brume()
        .current_dir(dir)
        .args(&all)
        .output()
        .expect("brume runs");
    assert!(
        out.status.success(),
        "brume {all:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8_lossy(&out.stdout).into_owned()
}

fn same(dir: &Path, a: &str, b: &str) {
    let read = |n: &str| std::fs::read(dir.join(n)).unwrap_or_else(|e| panic!("{n}: {e}"));
    assert!(read(a) == read(b), "{a} and {b} differ");
}

#[test]
fn automatic_settings_are_chosen_the_same_way_by_every_path_to_an_image() {
    // 4 pilot passes (the four budget pilots nested in one pass, and the fog at q = 0.25),
    // rendered first and left out of the film, then 11 film passes.
    check_every_path(
        SCENE,
        "4 pilot passes rendered before the film's first pass and NOT in the film",
        true,
    );
}

#[test]
fn automatic_q_alone_is_chosen_the_same_way_by_every_path_to_an_image() {
    // Fixed budgets: 4 pilot passes (base, the fog at q = 0.25), the film's first 4.
    let scene = SCENE
        .replace(r#"forward_rays = "auto""#, "forward_rays = 3000")
        .replace(r#"camera_samples = "auto""#, "camera_samples = 2");
    check_every_path(&scene, "4 pilot passes, the film's passes 0..4", false);
}

/// Renders `scene` in one go on 2 and 1 threads, in parts merged out of order and resumed
/// from a checkpoint, and checks the images are the same bytes; `pilots` is what the choice
/// says the pilot passes are, and `left_out` whether the pilots stay out of the film.
fn check_every_path(scene: &str, pilots: &str, left_out: bool) {
    let t = tempfile::tempdir().expect("tempdir");
    let d = t.path();
    write_scene(d, scene);
    let out = run(
        d,
        &["--passes", "11", "--threads", "2", "-v", "-o", "one.exr"],
    );
    let chosen_line = format!("auto: chosen from {pilots}");
    let chosen = out
        .lines()
        .find(|l| l.starts_with(&chosen_line))
        .unwrap_or_else(|| panic!("no choice printed: {out}"));
    let exr = std::fs::read(d.join("one.exr")).expect("one.exr");
    let text = String::from_utf8_lossy(&exr);
    assert!(text.contains("brumeAutoSettings"), "no metadata");
    assert!(
        text.contains(chosen.trim_start_matches("auto: ")),
        "{chosen}"
    );
    run(
        d,
        &["--passes", "11", "--threads", "1", "-q", "-o", "t1.exr"],
    );
    same(d, "one.exr", "t1.exr");
    // Every part renders the pilot passes first, to choose as the single run did.
    run(d, &["--pass-range", "9..11", "-q", "-o", "c.brume"]);
    run(d, &["--pass-range", "0..3", "-q", "-o", "a.brume"]);
    run(d, &["--pass-range", "3..9", "-q", "-o", "b.brume"]);
    let parts = [
        "merge", "c.brume", "a.brume", "b.brume", "-o", "m.exr", "-q",
    ];
    let out = brume().current_dir(d).args(parts).output().expect("merge");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    // The merged film's image equals the single run's (merge knows no choice to record, so
    // compare the films' images through a film file of the single run).
    run(d, &["--passes", "11", "-q", "-o", "one.brume"]);
    let m = brume()
        .current_dir(d)
        .args(["merge", "one.brume", "-o", "one-m.exr", "-q"])
        .output()
        .expect("merge");
    assert!(m.status.success());
    same(d, "one-m.exr", "m.exr");
    // A checkpoint after 5 passes, resumed to 11 (the resumed process renders the pilots again).
    run(
        d,
        &[
            "--passes",
            "5",
            "--checkpoint",
            "k.brume",
            "-q",
            "-o",
            "k.exr",
        ],
    );
    run(
        d,
        &["--passes", "11", "--resume", "k.brume", "-q", "-o", "r.exr"],
    );
    same(d, "one.exr", "r.exr");
    // A render of one film pass: pilots left out of the film are rendered first all the same
    // and the pass samples with the choice; pilots in the film make that pass the first pilot.
    let out = run(d, &["--passes", "1", "-v", "-o", "p1.exr"]);
    let chose = out.lines().any(|l| l.starts_with(&chosen_line));
    assert_eq!(chose, left_out, "{out}");
}
