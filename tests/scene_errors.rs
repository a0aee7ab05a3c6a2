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

/// GOOD with `lines` added to its `[integrator]` table after `q = 0.5` (line 7): the first
/// added line is line 8.
fn with_integrator(lines: &str) -> String {
    GOOD.replace("q = 0.5", &format!("q = 0.5\n{lines}"))
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
    assert_eq!(s.desc.integrator.q.value(), Some(0.5));
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

/// The radius schedule's keys: a schedule named beside a progressive alpha, and a consistent
/// schedule that would never wait.
#[test]
fn conflicting_or_empty_radius_schedules_are_rejected_with_their_line() {
    let e = fails(
        &with_integrator("alpha = 0.8\nradius_schedule = \"fixed\""),
        &[],
    );
    assert_at(&e, 9, "integrator.radius_schedule");
    assert!(e.to_string().contains("alpha = 0.8"), "{e}");
    let e = fails(&GOOD.replace("q = 0.5", "q = 0.5\nshrink_after = 0"), &[]);
    assert_at(&e, 8, "integrator.shrink_after");
    let e = fails(GOOD, &["integrator.radius_schedule=\"sometimes\""]);
    assert!(e.to_string().contains("radius_schedule"), "{e}");
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
    assert_eq!(s.desc.integrator.q.value(), Some(0.1));
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

/// A scene with one kind of each table, for the per-kind rules.
const KINDS: &str = r#"
[camera]
width = 64
height = 48

[materials.wall]
type = "lambert"
albedo = 0.4

[[shapes]]
type = "quad"
size = [1, 1]
material = "wall"
transform = { translate = [0, 0, 1] }

[[lights]]
type = "spot"
position = [0, 0, 3]
direction = [0, 0, -1]
angle = 30
power = 10
"#;

/// The full error text (file:line:column, key, message) for KINDS with `from` replaced by `to`.
fn kinds_error(from: &str, to: &str, sets: &[&str]) -> String {
    assert!(KINDS.contains(from), "{from}");
    fails(&KINDS.replacen(from, to, 1), sets).to_string()
}

/// Errors inside `[[lights]]`, `[[shapes]]` and `[materials.*]` keep the positions they had when
/// those tables were flat serde structs (file:line:column and key, recorded on 420f0de); the
/// messages after the key changed only where the rule did (per-kind keys, exact array lengths).
#[test]
fn kind_table_errors_keep_their_exact_positions() {
    let cases: &[(&str, &str, &str, &str)] = &[
        (
            "power = 10",
            "power = \"x\"",
            "21:9: key `lights.0.power`",
            "invalid type",
        ),
        (
            "size = [1, 1]",
            "size = \"big\"",
            "12:8: key `shapes.0.size`",
            "invalid type",
        ),
        (
            "size = [1, 1]",
            "size = [1, 1]\ncolour = 1",
            "13:1: key `shapes.0.colour`",
            "unknown field `colour` for a quad shape",
        ),
        (
            "albedo = 0.4",
            "albedo = 0.4\nshine = 1",
            "9:1: key `materials.wall.shine`",
            "unknown field `shine` for a lambert material",
        ),
        (
            "type = \"lambert\"",
            "type = \"plastic\"",
            "7:8: key `materials.wall.type`",
            "unknown material type `plastic`",
        ),
        (
            "type = \"spot\"\n",
            "",
            "16:1: key `lights.0`",
            "missing field `type`",
        ),
        (
            "translate = [0, 0, 1]",
            "scale = \"x\"",
            "14:23: key `shapes.0.transform.scale`",
            "invalid type",
        ),
        (
            "translate = [0, 0, 1]",
            "foo = 1",
            "14:15: key `shapes.0.transform.foo`",
            "unknown field `foo`",
        ),
        (
            "position = [0, 0, 3]",
            "position = [0, 2]",
            "18:12: key `lights.0.position`",
            "invalid length 2",
        ),
        (
            "albedo = 0.4",
            "albedo = [1, 2]",
            "8:10: key `materials.wall.albedo`",
            "invalid length 2",
        ),
        (
            "power = 10",
            "power = -1",
            "21:1: key `lights.0.power`",
            "> 0",
        ),
        (
            "position = [0, 0, 3]",
            "position = [0, \"x\", 3]",
            "18:16: key `lights.0.position.1`",
            "invalid type",
        ),
        (
            "angle = 30\n",
            "",
            "16:1: key `lights.0.angle`",
            "a spot needs its cone's half-angle `angle` (or a `profile`)",
        ),
        (
            "albedo = 0.4",
            "albedo = \"nosuch\"",
            "8:1: key `materials.wall.albedo`",
            "`nosuch` is not a spectrum",
        ),
        (
            "type = \"quad\"",
            "type = 3",
            "11:8: key `shapes.0.type`",
            "must be a string",
        ),
        (
            "material = \"wall\"",
            "material = 3",
            "13:12: key `shapes.0.material`",
            "invalid type",
        ),
        // Before, the third number was dropped without a word.
        (
            "size = [1, 1]",
            "size = [1, 1, 1]",
            "12:8: key `shapes.0.size`",
            "invalid length 3, expected an array of 2 numbers",
        ),
    ];
    for (from, to, at, message) in cases {
        let e = kinds_error(from, to, &[]);
        assert!(
            e.starts_with(&format!("scenes/test.toml:{at}: ")),
            "{to}: {e}"
        );
        assert!(e.contains(message), "{to}: {e}");
    }
}

/// A key that belongs to another kind of light, shape or material is refused at its line,
/// from the file and from `--set` (before, a point light's `direction` was silently ignored).
#[test]
fn keys_of_another_kind_are_refused() {
    let e = kinds_error("type = \"spot\"", "type = \"point\"", &[]);
    assert!(
        e.starts_with(
            "scenes/test.toml:20:1: key `lights.0.angle`: unknown field `angle` for a point light"
        ),
        "{e}"
    );
    // A point light's `direction` orients a profile; without one it is refused, not ignored.
    let e2 = fails(
        &KINDS
            .replacen("type = \"spot\"", "type = \"point\"", 1)
            .replacen("angle = 30\n", "", 1),
        &[],
    )
    .to_string();
    assert!(
        e2.starts_with(
            "scenes/test.toml:19:1: key `lights.0.direction`: orients a photometric profile"
        ),
        "{e2}"
    );
    let e = kinds_error("size = [1, 1]", "radius = 1", &[]);
    assert!(
        e.contains("12:1: key `shapes.0.radius`: unknown field `radius` for a quad"),
        "{e}"
    );
    let e = kinds_error("albedo = 0.4", "albedo = 0.4\nroughness = 0.1", &[]);
    assert!(e.contains("9:1: key `materials.wall.roughness`"), "{e}");
    let e = fails(KINDS, &["lights.0.radius=0.01"]).to_string();
    assert!(
        e.starts_with("--set lights.0.radius=0.01: key `lights.0.radius`: unknown field `radius` for a spot light"),
        "{e}"
    );
    // Changing the kind from the command line checks the other keys against the new kind.
    let e = fails(KINDS, &["lights.0.type=laser"]).to_string();
    assert!(
        e.starts_with("--set lights.0.type=laser: key `lights.0"),
        "{e}"
    );
}

/// The documented minimum roughness is accepted although 1e-4 is not exactly an f32.
#[test]
fn roughness_bounds_are_compared_as_stored() {
    let glossy = GOOD.replace("type = \"lambert\"", "type = \"glossy\"");
    let ok = glossy.replace("albedo = 0.4", "albedo = 0.4\nroughness = 0.0001");
    load_str(&ok, Path::new("scenes/test.toml"), &[])
        .expect("roughness 1e-4 is the documented minimum");
    let e = fails(
        &glossy.replace("albedo = 0.4", "albedo = 0.4\nroughness = 0.00009"),
        &[],
    );
    assert_at(&e, 12, "materials.wall.roughness");
    assert!(e.to_string().contains("[1e-4, 1]"), "{e}");
}

/// An albedo above 1 (energy gain) is refused, as a number, an RGB triple, or a named spectrum
/// once resolved, unless the material allows it.
#[test]
fn albedo_above_one_is_refused_unless_allowed() {
    let e = fails(&GOOD.replace("albedo = 0.4", "albedo = 1.5"), &[]);
    assert_at(&e, 11, "materials.wall.albedo");
    assert!(e.to_string().contains("allow_energy_gain"), "{e}");
    let e = fails(
        &GOOD.replace("albedo = 0.4", "albedo = [1.2, 0.5, 0.5]"),
        &[],
    );
    assert_at(&e, 11, "materials.wall.albedo");

    let allowed = GOOD.replace("albedo = 0.4", "albedo = 1.5\nallow_energy_gain = true");
    let s = load_str(&allowed, Path::new("scenes/test.toml"), &[]).expect("allowed gain");
    brume::scene::build(&s).expect("builds");
    let rgb = GOOD.replace(
        "albedo = 0.4",
        "albedo = [1.2, 0.6, 0.6]\nallow_energy_gain = true",
    );
    let s = load_str(&rgb, Path::new("scenes/test.toml"), &[]).expect("allowed gain");
    let built = brume::scene::build(&s).expect("builds");
    let brume::material::Material::Lambert { albedo } = &built.materials[0] else {
        panic!("lambert")
    };
    let max = albedo.at(glam::Vec2::ZERO).max_value();
    assert!(max > 1.1, "an allowed RGB above 1 keeps its scale: {max}");

    // A named spectrum is only known once resolved: refused when the scene is built, at the
    // material's albedo key and line.
    let named = format!(
        "{}\n[spectra.hot]\nvalue = 1.5\n",
        GOOD.replace("albedo = 0.4", "albedo = \"hot\"")
    );
    let s = load_str(&named, Path::new("scenes/test.toml"), &[]).expect("loads");
    let e = brume::scene::build(&s).err().expect("refused when built");
    assert_at(&e, 11, "materials.wall.albedo");
    let e = fails(GOOD, &["materials.wall.albedo=2"]);
    assert!(
        e.to_string().starts_with("--set materials.wall.albedo=2: "),
        "{e}"
    );
}

#[test]
fn camera_up_along_the_view_is_refused() {
    let text = GOOD.replace(
        "height = 48",
        "height = 48\nposition = [0, 0, 5]\nup = [0, 0, 2]",
    );
    let e = fails(&text, &[]);
    assert_at(&e, 6, "camera.up");
    assert!(
        e.to_string().contains("parallel to the view direction"),
        "{e}"
    );
    let e = fails(GOOD, &["camera.up=[0, 0, -1]"]);
    assert_eq!(e.key(), Some("camera.up"), "{e}");
    // A perspective camera has no viewed rectangle, an orthographic one no field of view.
    let e = fails(GOOD, &["camera.view_width=2"]);
    assert_eq!(e.key(), Some("camera.view_width"), "{e}");
    let e = fails(GOOD, &["camera.type=orthographic", "camera.fov=30"]);
    assert_eq!(e.key(), Some("camera.fov"), "{e}");
}

/// Lights far beyond any real source are refused with the bound (a 1e30 W lamp rendered black:
/// its splats overflow the film; see tests/reliability_limits.rs for the render).
#[test]
fn absurd_light_power_is_refused() {
    let e = kinds_error("power = 10", "power = 1e30", &[]);
    assert!(
        e.starts_with("scenes/test.toml:21:1: key `lights.0.power`: "),
        "{e}"
    );
    assert!(e.contains("1e9 W"), "{e}");
    let directional = KINDS.replace(
        "type = \"spot\"\nposition = [0, 0, 3]\ndirection = [0, 0, -1]\nangle = 30\npower = 10",
        "type = \"directional\"\ndirection = [0, 0, -1]\nirradiance = 1e7",
    );
    let e = fails(&directional, &[]).to_string();
    assert!(
        e.contains("key `lights.0.irradiance`") && e.contains("1e6"),
        "{e}"
    );
    let emitter = KINDS.replace("material = \"wall\"", "emit = 1e5\nemit_scale = 1e4");
    let s = load_str(&emitter, Path::new("scenes/test.toml"), &[]).expect("loads");
    let e = brume::scene::build(&s)
        .err()
        .expect("too bright")
        .to_string();
    assert!(
        e.contains("13:1: key `shapes.0.emit`") && e.contains("1e8"),
        "{e}"
    );
}

fn warnings_of(text: &str, sets: &[&str]) -> Vec<String> {
    let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
    let s = load_str(text, Path::new("scenes/test.toml"), &sets).expect("loads");
    let (_, warnings) = brume::scene::build_with_warnings(&s).expect("builds");
    warnings.iter().map(|w| w.to_string()).collect()
}

#[test]
fn a_scene_without_light_or_with_a_huge_radius_is_warned() {
    assert!(
        warnings_of(KINDS, &[]).is_empty(),
        "a sane scene has no warnings"
    );
    let w = warnings_of(GOOD, &[]);
    assert_eq!(w.len(), 1, "{w:?}");
    assert!(w[0].contains("no light that emits"), "{w:?}");
    // A radius of 10 m on a 1.4 m scene (the audit's image was 250x too dark).
    let w = warnings_of(
        &KINDS.replace("[camera]", "[integrator]\nradius = 10\n\n[camera]"),
        &[],
    );
    assert_eq!(w.len(), 1, "{w:?}");
    assert!(
        w[0].starts_with("scenes/test.toml:3:1: key `integrator.radius`: 10 m is"),
        "{w:?}"
    );
    let w = warnings_of(KINDS, &["integrator.radius=0.5"]);
    assert!(w[0].starts_with("--set integrator.radius=0.5: "), "{w:?}");
    // 5 % of the diagonal is the bound.
    assert!(warnings_of(KINDS, &["integrator.radius=0.07"]).is_empty());
}

/// The documentation's `--set` example runs on the scene it names.
#[test]
fn the_documented_set_example_works() {
    let scene = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/fog-room-laser.toml");
    let s = load(&scene, &["shapes.1.material=wall".into()]).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(s.desc.shapes[1].common.material.as_deref(), Some("wall"));
}

#[test]
fn blends_name_existing_materials_without_containing_themselves() {
    let blend = |first: &str, second: &str, weight: &str| {
        format!(
            "{GOOD}\n[materials.coat]\ntype = \"glossy\"\nalbedo = 0.3\n\n\
             [materials.mix]\ntype = \"blend\"\nfirst = \"{first}\"\nsecond = \"{second}\"\nweight = {weight}\n"
        )
    };
    let s = load_str(
        &blend("wall", "coat", "0.25"),
        Path::new("scenes/test.toml"),
        &[],
    )
    .expect("a blend of two materials");
    let built = brume::scene::build(&s).expect("builds");
    assert!(matches!(
        built.materials[1],
        brume::material::Material::Blend(_)
    ));
    let e = fails(&blend("wall", "stone", "0.25"), &[]);
    assert_at(&e, 25, "materials.mix.second");
    let e = fails(&blend("wall", "coat", "1.5"), &[]);
    assert_at(&e, 26, "materials.mix.weight");
    let e = fails(&blend("wall", "mix", "0.5"), &[]);
    assert_eq!(e.key(), Some("materials.mix"), "{e}");
    assert!(e.to_string().contains("mix -> mix"), "{e}");
}

/// `direct` (hybrid transport): a laser cannot take next-event estimation, and only emitting
/// shapes have direct light; the other choices load.
#[test]
fn direct_choices_are_checked_per_light() {
    let laser = KINDS.replacen(
        "type = \"spot\"\nposition = [0, 0, 3]\ndirection = [0, 0, -1]\nangle = 30\npower = 10",
        "type = \"laser\"\nposition = [0, 0, 3]\ndirection = [0, 0, -1]\nradius = 0.001\npower = 10\ndirect = \"nee\"",
        1,
    );
    let e = fails(&laser, &[]).to_string();
    assert!(
        e.contains("key `lights.0.direct`: a laser's direct light cannot be reached"),
        "{e}"
    );
    let e = kinds_error(
        "material = \"wall\"",
        "material = \"wall\"\ndirect = \"nee\"",
        &[],
    );
    assert!(
        e.contains("key `shapes.0.direct`: only an emitting shape"),
        "{e}"
    );
    for ok in ["auto", "nee", "photons"] {
        let set = format!("lights.0.direct=\"{ok}\"");
        load_str(KINDS, Path::new("scenes/test.toml"), &[set]).expect("loads");
    }
    let e = fails(KINDS, &["lights.0.direct=\"sometimes\""]).to_string();
    assert!(e.contains("lights.0.direct"), "{e}");
}

/// Spectral lines (issue 17): a wavelength that is not one, a negative power, a line outside
/// the film's range, a scene whose lines need more than 64 bins, and lines where a reflectance
/// belongs are refused when the scene loads, at the file, line and key that give them.
#[test]
fn bad_spectral_lines_name_file_line_and_key() {
    let light = |spectrum: &str, sets: &[&str]| {
        kinds_error(
            "power = 10",
            &format!("power = 10\nspectrum = {spectrum}"),
            sets,
        )
    };
    let at = |e: &str, key: &str, what: &str| {
        assert!(
            e.starts_with("scenes/test.toml:22:") && e.contains(&format!("key `{key}`: ")),
            "{e}"
        );
        assert!(e.contains(what), "{e}");
    };
    let e = light("{ line = -532.0 }", &[]);
    at(&e, "lights.0.spectrum.line", "finite and > 0 nm");
    let e = light("{ lines = [[532.0, 1.0], [1064.0, 0.1]] }", &[]);
    at(
        &e,
        "lights.0.spectrum.lines.1.0",
        "outside the film's range 380-780 nm",
    );
    let e = light("{ lines = [[532.0, -1.0]] }", &[]);
    at(&e, "lights.0.spectrum.lines.0.1", ">= 0");
    let e = light("{ line = 532.0, lines = [[633.0, 1.0]] }", &[]);
    at(&e, "lights.0.spectrum", "either `line");
    // 60 equal bins; each line inside one splits it: 62, 64, then 66 bins at the third line.
    let three = "{ lines = [[450.0, 1.0], [532.0, 1.0], [633.0, 1.0]] }";
    let e = light(three, &["film.bins=60"]);
    at(&e, "lights.0.spectrum.lines.2.0", "would need 66 bins");
    assert!(e.contains("film.bins = 60"), "{e}");
    // 58 equal bins and the same lines fill the 64 exactly.
    let text = KINDS.replacen("power = 10", &format!("power = 10\nspectrum = {three}"), 1);
    let s = load_str(
        &text,
        Path::new("scenes/test.toml"),
        &["film.bins=58".into()],
    )
    .unwrap();
    let grid = brume::scene::build(&s).expect("builds").grid;
    assert_eq!((grid.n, grid.lines()), (64, &[450.0, 532.0, 633.0][..]));
    // A shape's `emit` takes lines too; an albedo does not.
    let e = kinds_error("material = \"wall\"", "emit = { line = 800.0 }", &[]);
    assert!(
        e.starts_with("scenes/test.toml:13:") && e.contains("key `shapes.0.emit.line`: "),
        "{e}"
    );
    let e = kinds_error("albedo = 0.4", "albedo = { line = 532.0 }", &[]);
    assert!(
        e.starts_with("scenes/test.toml:8:") && e.contains("key `materials.wall.albedo`: "),
        "{e}"
    );
    assert!(e.contains("spectral lines"), "{e}");
}

/// `radius_indirect = "auto"` asks the pilots for the radius for scattered light; they run only
/// beside an automatic radius and automatic budgets, so asked for otherwise it is refused at
/// its line rather than silently rendered at the radius. Other strings are refused too.
#[test]
fn an_automatic_radius_for_scattered_light_without_its_pilots_is_rejected() {
    let auto = with_integrator("radius_indirect = \"auto\"");
    assert!(load_str(&auto, Path::new("scenes/test.toml"), &[]).is_ok());
    let e = fails(
        &with_integrator("radius = 0.01\nradius_indirect = \"auto\""),
        &[],
    );
    assert_at(&e, 9, "integrator.radius_indirect");
    assert!(e.to_string().contains("needs radius = \"auto\""), "{e}");
    let pinned = "radius_indirect = \"auto\"\nforward_rays = 1000\ncamera_samples = 1";
    let e = fails(&with_integrator(pinned), &[]);
    assert_at(&e, 8, "integrator.radius_indirect");
    let e = fails(GOOD, &["integrator.radius_indirect=\"twice\""]);
    assert!(e.to_string().contains("radius_indirect"), "{e}");
}
