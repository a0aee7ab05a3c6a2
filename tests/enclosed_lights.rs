//! A light shut inside an opaque closed shape, the camera outside, is warned about when the
//! scene is built (src/scene/enclosed.rs); a lamp behind glass, a lamp in the room the camera is
//! in, and every shipped scene are not.

use std::path::Path;

use brume::scene::load_str;

/// A point light at the centre of a closed 1 m box of material `box`, seen from `camera`.
fn scene(material: &str, camera: [f32; 3]) -> String {
    format!(
        "[camera]\nposition = {camera:?}\nlook_at = [0, 0, 0]\n\n\
         [materials.paint]\ntype = \"lambert\"\nalbedo = 0.5\n\n\
         [materials.glass]\ntype = \"dielectric\"\nior = 1.5\n\n\
         [[shapes]]\ntype = \"box\"\nsize = [1, 1, 1]\nmaterial = \"{material}\"\n\n\
         [[lights]]\ntype = \"point\"\nposition = [0, 0, 0]\npower = 10\n"
    )
}

fn warnings(text: &str) -> Vec<String> {
    let s = load_str(text, Path::new("scenes/test.toml"), &[]).expect("loads");
    let (_, w) = brume::scene::build_with_warnings(&s).expect("builds");
    w.iter().map(|w| w.to_string()).collect()
}

#[test]
fn a_lamp_shut_in_an_opaque_box_is_warned_about_at_its_key() {
    let w = warnings(&scene("paint", [0.0, 0.0, 5.0]));
    assert_eq!(w.len(), 1, "{w:?}");
    // Line 18 is the light's table (`[[lights]]`).
    assert!(w[0].contains("lights.0") && w[0].contains(":18"), "{w:?}");
    assert!(
        w[0].contains("shut inside shapes.0") && w[0].contains("`paint`"),
        "{w:?}"
    );
}

#[test]
fn a_lamp_behind_glass_or_in_the_cameras_room_is_not() {
    assert!(warnings(&scene("glass", [0.0, 0.0, 5.0])).is_empty());
    // The camera inside the box with the lamp: a room.
    assert!(warnings(&scene("paint", [0.2, 0.1, 0.3])).is_empty());
    // An open box (its top face missing) lets the light out.
    let open = scene("paint", [0.0, 0.0, 5.0]).replace(
        "[[shapes]]\ntype = \"box\"\nsize = [1, 1, 1]",
        "[[shapes]]\ntype = \"quad\"\nsize = [1, 1]\ntransform = { translate = [0, 0, -0.5] }",
    );
    assert!(warnings(&open).is_empty());
}

#[test]
fn no_shipped_scene_has_a_shut_in_light() {
    for dir in ["scenes", "tools/compare/scenes", "tools/bench"] {
        for entry in std::fs::read_dir(dir).expect("scene folder") {
            let path = entry.expect("entry").path();
            if path.extension().is_some_and(|e| e == "toml") {
                let s = brume::scene::load(&path, &[]).unwrap_or_else(|e| panic!("{e}"));
                let (_, w) = brume::scene::build_with_warnings(&s).expect("builds");
                let shut: Vec<String> = w
                    .iter()
                    .map(|w| w.to_string())
                    .filter(|w| w.contains("shut inside"))
                    .collect();
                assert!(shut.is_empty(), "{}: {shut:?}", path.display());
            }
        }
    }
}
