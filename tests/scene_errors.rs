//! A malformed scene fails with a message naming the file, line and key, and never panics.

use std::path::Path;

use brume::scene::{Origin, SceneError, load, load_str};

const GOOD: &str = r#"
[camera]
width = 64
height = 48

[integrator]
q = 0.5

[materials.wall]
type = "lambert"
albedo = 0.4

[[shapes]]
type = "quad"
size = [1, 1]
material = "wall"
"#;

fn fails(text: &str, sets: &[&str]) -> SceneError {
    let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
    match load_str(text, Path::new("scenes/test.toml"), &sets) {
        Ok(_) => panic!("scene unexpectedly accepted"),
        Err(e) => e,
    }
}

/// The error points into the file at `line` and names `key`.
fn assert_at(e: &SceneError, line: usize, key: &str) {
    let text = e.to_string();
    assert!(
        text.starts_with(&format!("scenes/test.toml:{line}:")),
        "{text}"
    );
    assert_eq!(e.key(), Some(key), "{text}");
}

#[test]
fn the_good_scene_loads() {
    let s = load_str(GOOD, Path::new("scenes/test.toml"), &[]).expect("good scene");
    assert_eq!(s.desc.camera.width, 64);
    assert_eq!(s.desc.integrator.q, 0.5);
    assert_eq!(s.desc.film.bins, 32, "default bins");
}

#[test]
fn bad_toml_names_file_and_line() {
    let e = fails(&GOOD.replace("[integrator]", "[integrator"), &[]);
    let text = e.to_string();
    assert!(text.starts_with("scenes/test.toml:6:"), "{text}");
}

#[test]
fn unknown_key_is_an_error() {
    let e = fails(&GOOD.replace("q = 0.5", "qq = 0.5"), &[]);
    assert_at(&e, 7, "integrator.qq");
    assert!(e.to_string().contains("unknown field"));
}

#[test]
fn wrong_type_names_key() {
    let e = fails(&GOOD.replace("width = 64", "width = \"wide\""), &[]);
    assert_at(&e, 3, "camera.width");
}

#[test]
fn negative_width_is_rejected() {
    let e = fails(&GOOD.replace("width = 64", "width = -64"), &[]);
    assert_at(&e, 3, "camera.width");
}

#[test]
fn out_of_range_q_is_rejected_with_its_line() {
    let e = fails(&GOOD.replace("q = 0.5", "q = 1.5"), &[]);
    assert_at(&e, 7, "integrator.q");
    assert!(e.to_string().contains("(0, 1]"));
}

#[test]
fn missing_texture_names_key() {
    let e = fails(
        &GOOD.replace("albedo = 0.4", "texture = \"no-such-file.png\""),
        &[],
    );
    assert_at(&e, 11, "materials.wall.texture");
    assert!(e.to_string().contains("no-such-file.png"));
}

#[test]
fn dangling_material_reference() {
    let e = fails(
        &GOOD.replace("material = \"wall\"", "material = \"stone\""),
        &[],
    );
    assert_at(&e, 16, "shapes.0.material");
}

#[test]
fn set_overrides_and_validates() {
    let s = load_str(
        GOOD,
        Path::new("scenes/test.toml"),
        &[
            "integrator.q=0.1".into(),
            "camera.width=32".into(),
            "integrator.volume=\"cylinder\"".into(),
        ],
    )
    .expect("valid overrides");
    assert_eq!(s.desc.integrator.q, 0.1);
    assert_eq!(s.desc.camera.width, 32);
    assert_eq!(
        s.desc.integrator.volume,
        brume::scene::desc::VolumeKind::Cylinder
    );
    // Bare strings work too.
    let s = load_str(
        GOOD,
        Path::new("scenes/test.toml"),
        &["integrator.mode=see-through".into()],
    )
    .expect("bare string");
    assert_eq!(
        s.desc.integrator.mode,
        brume::scene::desc::GatherMode::SeeThrough
    );
}

#[test]
fn set_with_unknown_path_fails_naming_the_assignment() {
    for (set, key) in [
        ("integrator.foo=1", "integrator.foo"),
        ("integrator.q=2", "integrator.q"),
        ("camera.width=-3", "camera.width"),
        ("shapes.0.material=metal", "shapes.0.material"),
    ] {
        let e = fails(GOOD, &[set]);
        match &e {
            SceneError::Invalid {
                origin: Origin::Set(a),
                ..
            } => assert_eq!(a, set),
            other => panic!("{set}: wrong error {other:?}"),
        }
        assert_eq!(e.key(), Some(key), "{e}");
    }
    assert!(matches!(
        fails(GOOD, &["novalue"]),
        SceneError::BadAssignment { .. }
    ));
    assert!(matches!(
        fails(GOOD, &["shapes.7.size=[1,1]"]),
        SceneError::BadAssignment { .. }
    ));
}

#[test]
fn unreadable_file_is_reported() {
    let e = load(Path::new("/nonexistent/scene.toml"), &[]).expect_err("missing file");
    assert!(e.to_string().contains("/nonexistent/scene.toml"));
}

#[test]
fn every_shipped_scene_loads() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes");
    let mut count = 0;
    for entry in std::fs::read_dir(&dir).expect("scenes/") {
        let path = entry.expect("entry").path();
        if path.extension().is_some_and(|e| e == "toml") {
            load(&path, &[]).unwrap_or_else(|e| panic!("{e}"));
            count += 1;
        }
    }
    assert!(count >= 1, "no scenes found");
}
