//! What a scene file or a mistyped path must not be able to do (issue 31): write outside the
//! scene's folder, have a file's text printed, overwrite one output with another (a
//! false-colour map, a symbolic link), render an empty file; and what `info` and `--set` tell.

use std::path::Path;
use std::process::Output;

use super::{SCENE, brume, write_scene};

fn run(dir: &Path, args: &[&str]) -> Output {
    brume()
        .current_dir(dir)
        .args(args)
        .output()
        .expect("run brume")
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

fn listing(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .expect("dir")
        .map(|e| e.expect("entry").file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

/// `--set 'lights.0.spectrum="/etc/shadow"'` printed the file's first line; a data row that
/// is not a number printed the row.
#[test]
fn a_file_named_as_a_spectrum_is_never_echoed() {
    let dir = tempfile::tempdir().expect("tempdir");
    let d = dir.path();
    write_scene(d, SCENE);
    std::fs::write(d.join("shadow"), "root:SECRET-HASH:20228:0:99999:7:::\n").expect("write");
    std::fs::write(
        d.join("table.csv"),
        "wavelength_nm,power\n400,1\n500,SECRET-VALUE\n",
    )
    .expect("write");
    for file in ["shadow", "table.csv"] {
        let shadow = d.join(file);
        let set = format!("lights.0.spectrum={:?}", shadow.to_str().expect("utf-8"));
        for cmd in ["info", "render"] {
            let out = run(
                d,
                &[cmd, "scene.toml", "--set", &set, "-q"][..if cmd == "info" { 4 } else { 5 }],
            );
            let err = stderr(&out);
            assert!(!out.status.success(), "{cmd} {file}: {err}");
            assert!(err.contains(file), "{cmd} {file}: the file is named: {err}");
            assert!(!err.contains("SECRET"), "{cmd} {file}: echoed: {err}");
        }
    }
}

/// Relative `film.outputs` are written in the scene file's folder (as documented), not the
/// working folder; a scene cannot write above its folder or to an absolute path, but the
/// command line can.
#[test]
fn scene_outputs_stay_in_the_scene_folder() {
    let dir = tempfile::tempdir().expect("tempdir");
    let d = dir.path();
    let sub = d.join("scenes");
    std::fs::create_dir(&sub).expect("mkdir");
    let with_outputs = |outputs: &str| {
        let text = SCENE.replacen(
            "[camera]",
            &format!("[film]\noutputs = {outputs}\n[camera]"),
            1,
        );
        write_scene(&sub, &text);
    };
    with_outputs(r#"["out.png"]"#);
    let out = run(d, &["render", "scenes/scene.toml", "-q"]);
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(sub.join("out.png").is_file(), "{:?}", listing(&sub));
    assert!(!d.join("out.png").exists(), "written in the working folder");

    let outside = d.join("abs.png");
    let absolute = format!("[{:?}]", outside.to_str().expect("utf-8"));
    for (outputs, name) in [
        (r#"["../up.png"]"#, "up.png"),
        (r#"["x/../../up.png"]"#, "up.png"),
        (absolute.as_str(), "abs.png"),
    ] {
        with_outputs(outputs);
        let before = (listing(d), listing(&sub));
        let out = run(d, &["render", "scenes/scene.toml", "-q"]);
        let err = stderr(&out);
        assert!(!out.status.success(), "{outputs} accepted");
        assert!(
            err.contains("film.outputs.0") && err.contains("outside the scene file's folder"),
            "{err}"
        );
        assert_eq!((listing(d), listing(&sub)), before, "{outputs} wrote files");
        // On the command line the same path is the user's choice.
        let out = run(d, &["render", "scenes/scene.toml", "-q", "-o", name]);
        assert!(out.status.success(), "{}", stderr(&out));
        assert!(d.join(name).is_file());
    }
}

/// `-o b.png -o b-luminance.png` with `film.false_colour`: the map of b.png and the image
/// b-luminance.png are one file; the second write silently replaced the first.
#[test]
fn an_output_named_like_a_false_colour_map_is_refused() {
    let dir = tempfile::tempdir().expect("tempdir");
    let d = dir.path();
    write_scene(d, SCENE);
    let args = [
        "render",
        "scene.toml",
        "-q",
        "--set",
        "film.false_colour=true",
        "-o",
        "b.png",
        "-o",
        "b-luminance.png",
    ];
    let out = run(d, &args);
    let err = stderr(&out);
    assert!(!out.status.success(), "accepted");
    assert!(
        err.contains("same file") && err.contains("false-colour map of b.png"),
        "{err}"
    );
    assert_eq!(listing(d), ["scene.toml"]);
}

/// A symbolic link to another output of the same render, before either exists.
#[cfg(unix)]
#[test]
fn a_link_to_another_output_is_refused() {
    let dir = tempfile::tempdir().expect("tempdir");
    let d = dir.path();
    write_scene(d, SCENE);
    std::os::unix::fs::symlink("a.exr", d.join("b.exr")).expect("symlink");
    let out = run(
        d,
        &["render", "scene.toml", "-q", "-o", "a.exr", "-o", "b.exr"],
    );
    let err = stderr(&out);
    assert!(!out.status.success() && err.contains("same file"), "{err}");
    assert!(!d.join("a.exr").exists());
}

/// An empty scene rendered a black image and exited 0; a folder or /dev/zero as a scene said
/// "Is a directory (os error 21)" or filled the memory; a folder named as a mesh said
/// "file not found".
#[test]
fn empty_and_non_file_scenes_are_refused_with_what_they_are() {
    let dir = tempfile::tempdir().expect("tempdir");
    let d = dir.path();
    std::fs::write(d.join("empty.toml"), "# nothing yet\n\n").expect("write");
    std::fs::create_dir(d.join("folder")).expect("mkdir");
    let mut cases = vec![
        ("empty.toml", "the scene file is empty"),
        ("folder", "is a folder, not a scene file"),
    ];
    if Path::new("/dev/zero").exists() {
        cases.push(("/dev/zero", "not a scene file"));
    }
    for (scene, words) in cases {
        for cmd in ["info", "render"] {
            let out = run(d, &[cmd, scene, "-q"][..if cmd == "info" { 2 } else { 3 }]);
            let err = stderr(&out);
            assert!(!out.status.success(), "{cmd} {scene}: accepted");
            assert!(err.contains(words), "{cmd} {scene}: {err}");
        }
    }
    assert_eq!(listing(d), ["empty.toml", "folder"]);
    let mesh =
        format!("{SCENE}\n[[shapes]]\ntype = \"mesh\"\nfile = \"folder\"\nmaterial = \"wall\"\n");
    write_scene(d, &mesh);
    let out = run(d, &["info", "scene.toml"]);
    let err = stderr(&out);
    assert!(
        !out.status.success() && err.contains("folder: is a folder, not a file"),
        "{err}"
    );
}

/// `brume info` lists each light and sensor with its keys.
#[test]
fn info_lists_lights_and_sensors() {
    let dir = tempfile::tempdir().expect("tempdir");
    let d = dir.path();
    let text = format!(
        "{SCENE}\n[[lights]]\ntype = \"point\"\nposition = [0, 0, 1]\npower = 2.0\n\
         spectrum = {{ line = 532.0 }}\n\n[[sensors]]\ntype = \"luminance\"\nname = \"patch\"\n\
         region = [0, 0, 4, 4]\n"
    );
    write_scene(d, &text);
    let out = run(d, &["info", "scene.toml"]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(text.contains("lights:       2"), "{text}");
    assert!(
        text.contains("lights.0: directional") && text.contains("irradiance = 100.0"),
        "{text}"
    );
    assert!(
        text.contains("lights.1: point") && text.contains("spectrum = { line = 532.0 }"),
        "{text}"
    );
    assert!(
        text.contains("sensors.0 (patch): luminance") && text.contains("region = [0, 0, 4, 4]"),
        "{text}"
    );
}

/// `--set media=none` switches the fog off (the shapes that only bounded it stay, empty):
/// the fog-cube's wall renders as without the fog box; `media.NAME=none` removes one medium
/// and an unknown name is refused.
#[test]
fn media_none_switches_the_fog_off() {
    let scene = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/fog-cube.toml");
    let off = brume::scene::load(&scene, &["media=none".into()]).unwrap_or_else(|e| panic!("{e}"));
    assert!(off.desc.media.is_empty());
    assert!(off.desc.shapes.iter().all(|s| s.common.interior.is_none()));
    let one =
        brume::scene::load(&scene, &["media.fog=none".into()]).unwrap_or_else(|e| panic!("{e}"));
    assert!(one.desc.media.is_empty());
    let e = brume::scene::load(&scene, &["media.smoke=none".into()]).unwrap_err();
    assert!(
        e.to_string().contains("no medium `smoke` (its media: fog)"),
        "{e}"
    );
    let built = brume::scene::build(&off).unwrap_or_else(|e| panic!("{e}"));
    assert!(built.media.is_empty());
}
