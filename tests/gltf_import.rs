//! glTF 2.0 import (issue 29): what a file brings (meshes with node transforms, materials,
//! KHR lights in candela and lux, the camera), and the acceptance test: the same scene written
//! as glTF and as TOML renders the same image, bit for bit, at the same seed.

#[path = "gltf/writer.rs"]
mod writer;

use std::fmt::Write as _;
use std::path::Path;

use brume::integrator::{Budget, Renderer};
use brume::scene::desc::{LightKind, MaterialKind};
use serde_json::json;
use writer::Gltf;

const YFOV: f32 = 0.7;

/// A floor (2 x 2 m, z = 0, facing +z), a small emitting panel above it facing down, a
/// standing plate of rough metal (glTF metallic 1, roughness 0.5: a conductor), a point
/// light moved by its node, a spot and a directional light shining down -z (their nodes'
/// axis), and a camera 3 m above, looking down.
fn street() -> Gltf {
    let mut g = Gltf::new();
    let floor = g.material(json!({
        "name": "Floor",
        "pbrMetallicRoughness": { "baseColorFactor": [0.5, 0.4, 0.3, 1.0], "metallicFactor": 0.0 }
    }));
    g.use_extension("KHR_materials_emissive_strength");
    let lamp = g.material(json!({
        "name": "Lamp",
        "pbrMetallicRoughness": { "baseColorFactor": [0.8, 0.8, 0.8, 1.0], "metallicFactor": 0.0 },
        "emissiveFactor": [1.0, 0.9, 0.8],
        "extensions": { "KHR_materials_emissive_strength": { "emissiveStrength": 200.0 } }
    }));
    let quad = [
        [-1.0, -1.0, 0.0],
        [1.0, -1.0, 0.0],
        [1.0, 1.0, 0.0],
        [-1.0, 1.0, 0.0],
    ];
    let m = g.mesh(&quad, None, &[0, 1, 2, 0, 2, 3], Some(floor));
    g.node(json!({ "name": "Floor", "mesh": m }));
    let panel = [
        [-0.1, -0.1, 0.5],
        [-0.1, 0.1, 0.5],
        [0.1, 0.1, 0.5],
        [0.1, -0.1, 0.5],
    ];
    let m = g.mesh(&panel, None, &[0, 1, 2, 0, 2, 3], Some(lamp));
    g.node(json!({ "name": "Panel", "mesh": m }));
    let steel = g.material(json!({
        "name": "Steel",
        "pbrMetallicRoughness": { "baseColorFactor": [0.6, 0.62, 0.65, 1.0],
            "metallicFactor": 1.0, "roughnessFactor": 0.5 }
    }));
    let plate = [
        [0.4, -0.5, 0.0],
        [0.9, -0.5, 0.0],
        [0.9, -0.5, 0.6],
        [0.4, -0.5, 0.6],
    ];
    let m = g.mesh(&plate, None, &[0, 1, 2, 0, 2, 3], Some(steel));
    g.node(json!({ "name": "Plate", "mesh": m }));
    let point = g.light(json!({ "type": "point", "intensity": 40.0 }));
    let spot = g.light(json!({
        "type": "spot", "intensity": 120.0, "color": [1.0, 0.8, 0.6],
        "spot": { "innerConeAngle": 0.25, "outerConeAngle": 0.5 }
    }));
    let sun = g.light(json!({ "type": "directional", "intensity": 3.0 }));
    let light = |i| json!({ "KHR_lights_punctual": { "light": i } });
    g.node(json!({ "name": "Bulb", "translation": [0.25, 0.5, 1.0], "extensions": light(point) }));
    g.node(json!({ "name": "Spot", "translation": [-0.5, 0.0, 2.0], "extensions": light(spot) }));
    g.node(json!({ "name": "Sun", "extensions": light(sun) }));
    let cam = g.camera(json!({ "type": "perspective",
        "perspective": { "yfov": YFOV, "znear": 0.01, "aspectRatio": 1.0 } }));
    g.node(json!({ "name": "Eye", "camera": cam, "translation": [0.0, 0.0, 3.0] }));
    g
}

const SETTINGS: &str = "[film]\nbins = 8\n\n[integrator]\nforward_rays = 3000\nradius = 0.03\n";

fn gltf_scene(dir: &Path) -> std::path::PathBuf {
    street().write_glb(&dir.join("street.glb"));
    let text = format!(
        "{SETTINGS}\n[import]\nlights = true\n\n[camera]\nwidth = 24\nheight = 24\n\n\
         [[shapes]]\ntype = \"gltf\"\nfile = \"street.glb\"\n"
    );
    let path = dir.join("gltf.toml");
    std::fs::write(&path, text).expect("write scene");
    path
}

/// The same scene in TOML: OBJ meshes of the same triangles, the lights and camera by hand.
fn toml_scene(dir: &Path) -> std::path::PathBuf {
    std::fs::write(
        dir.join("floor.obj"),
        "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nf 1 2 3\nf 1 3 4\n",
    )
    .expect("obj");
    std::fs::write(
        dir.join("panel.obj"),
        "v -0.1 -0.1 0.5\nv -0.1 0.1 0.5\nv 0.1 0.1 0.5\nv 0.1 -0.1 0.5\nf 1 2 3\nf 1 3 4\n",
    )
    .expect("obj");
    let f = |v: f32| v as f64;
    let (c1, c2) = (f(0.9), f(0.8));
    let nits = (0.2126f32 * 1.0 + 0.7152 * 0.9 + 0.0722 * 0.8) * 200.0;
    let mut t = String::from(SETTINGS);
    let _ = write!(
        t,
        "\n[camera]\nwidth = 24\nheight = 24\nposition = [0, 0, 3]\nlook_at = [0, 0, 2]\n\
         up = [0, 1, 0]\nfov = {}\n",
        YFOV.to_degrees()
    );
    let _ = write!(
        t,
        "\n[materials.floor]\ntype = \"lambert\"\nalbedo = [{}, {}, {}]\n\
         \n[materials.lamp]\ntype = \"lambert\"\nalbedo = [{}, {}, {}]\n",
        f(0.5),
        f(0.4),
        f(0.3),
        f(0.8),
        f(0.8),
        f(0.8)
    );
    t.push_str("\n[[shapes]]\ntype = \"mesh\"\nfile = \"floor.obj\"\nmaterial = \"floor\"\n");
    let _ = write!(
        t,
        "\n[[shapes]]\ntype = \"mesh\"\nfile = \"panel.obj\"\nmaterial = \"lamp\"\n\
         emit = [1.0, {c1}, {c2}]\nluminance = {nits}\n"
    );
    let _ = write!(
        t,
        "\n[[lights]]\ntype = \"point\"\nintensity = 40\nposition = [0.25, 0.5, 1]\n\
         \n[[lights]]\ntype = \"spot\"\nintensity = 120\nspectrum = [1.0, {}, {}]\n\
         position = [-0.5, 0, 2]\ndirection = [0, 0, -1]\nangle = {}\nsoft_edge = {}\n\
         \n[[lights]]\ntype = \"directional\"\nilluminance = 3\ndirection = [0, 0, -1]\n",
        f(0.8),
        f(0.6),
        0.5f32.to_degrees(),
        (0.5f32 - 0.25).to_degrees()
    );
    std::fs::write(
        dir.join("plate.obj"),
        "v 0.4 -0.5 0\nv 0.9 -0.5 0\nv 0.9 -0.5 0.6\nv 0.4 -0.5 0.6\nf 1 2 3\nf 1 3 4\n",
    )
    .expect("obj");
    let _ = write!(
        t,
        "\n[materials.steel]\ntype = \"conductor\"\nroughness = 0.25\nf0 = [{}, {}, {}]\n\
         \n[[shapes]]\ntype = \"mesh\"\nfile = \"plate.obj\"\nmaterial = \"steel\"\n",
        f(0.6),
        f(0.62),
        f(0.65)
    );
    let path = dir.join("toml.toml");
    std::fs::write(&path, t).expect("write scene");
    path
}

fn render_bits(scene: &Path) -> Vec<u32> {
    let loaded = brume::scene::load(scene, &[]).unwrap_or_else(|e| panic!("{e}"));
    let built = brume::scene::build(&loaded).unwrap_or_else(|e| panic!("{e}"));
    let integrator =
        brume::scene::build_integrator(&loaded, &built).unwrap_or_else(|e| panic!("{e}"));
    let mut r = Renderer::new(&built, integrator, 7);
    r.run(Budget::Passes(2), |_, _| {});
    let img = r.image();
    assert!(
        img.data.iter().any(|v| *v > 0.0),
        "{}: black image",
        scene.display()
    );
    img.data.iter().map(|v| v.to_bits()).collect()
}

#[test]
fn gltf_and_toml_of_one_scene_render_the_same_bits() {
    let dir = tempfile::tempdir().expect("tempdir");
    let a = render_bits(&gltf_scene(dir.path()));
    let b = render_bits(&toml_scene(dir.path()));
    assert_eq!(a.len(), b.len());
    let differ = a.iter().zip(&b).filter(|(x, y)| x != y).count();
    assert_eq!(differ, 0, "{differ} of {} values differ", a.len());
}

#[test]
fn a_glb_brings_its_meshes_materials_lights_and_camera() {
    let dir = tempfile::tempdir().expect("tempdir");
    let loaded = brume::scene::load(&gltf_scene(dir.path()), &[]).unwrap_or_else(|e| panic!("{e}"));
    let d = &loaded.desc;
    // The glTF shape itself, then one part per primitive.
    assert_eq!(d.shapes.len(), 4);
    assert_eq!(
        d.shapes[1].common.material.as_deref(),
        Some("gltf0:0:Floor")
    );
    assert!(d.shapes[2].common.emit.is_some());
    let expected = (0.2126f32 + 0.7152 * 0.9 + 0.0722 * 0.8) * 200.0;
    assert_eq!(d.shapes[2].common.luminance, Some(expected));
    assert!(matches!(
        d.materials["gltf0:0:Floor"].kind,
        MaterialKind::Lambert(_)
    ));
    let kinds: Vec<&str> = d.lights.iter().map(|l| l.kind_name()).collect();
    assert_eq!(kinds, ["point", "spot", "directional"]);
    let LightKind::Point(p) = &d.lights[0].kind else {
        panic!()
    };
    assert_eq!((p.intensity, p.position), (Some(40.0), [0.25, 0.5, 1.0]));
    let LightKind::Spot(s) = &d.lights[1].kind else {
        panic!()
    };
    assert_eq!(s.angle, Some(0.5f32.to_degrees()));
    assert_eq!(s.direction, [0.0, 0.0, -1.0]);
    let LightKind::Directional(l) = &d.lights[2].kind else {
        panic!()
    };
    assert_eq!(l.illuminance, Some(3.0));
    assert_eq!(d.camera.position, [0.0, 0.0, 3.0]);
    assert_eq!(d.camera.fov, Some(YFOV.to_degrees()));
    assert_eq!((d.camera.width, d.camera.height), (24, 24));
    let info = brume::scene::summary::summarise(&loaded).to_string();
    assert!(info.contains("street.glb: 3 meshes (3 primitives), 6 triangles, 3 materials (1 emitting), 3 of 3 lights imported"), "{info}");
    assert!(info.contains("camera: cameras[0] at nodes[6]"), "{info}");
    assert!(loaded.warnings.is_empty(), "{:?}", loaded.warnings);
}

/// Node transforms compose down the hierarchy; a mirroring one keeps faces outward.
#[test]
fn nodes_carry_their_parents_transforms_and_can_be_picked_by_name() {
    let dir = tempfile::tempdir().expect("tempdir");
    let mut g = Gltf::new();
    let tri = g.mesh(
        &[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
        None,
        &[0, 1, 2],
        None,
    );
    let child = g.json["nodes"].as_array().map_or(0, |a| a.len());
    g.json["nodes"]
        .as_array_mut()
        .unwrap()
        .push(json!({ "name": "Child", "mesh": tri,
        "translation": [0.0, 0.0, 1.0], "scale": [1.0, 1.0, -1.0] }));
    g.node(
        json!({ "name": "Parent", "children": [child], "translation": [10.0, 0.0, 0.0],
        "mesh": tri }),
    );
    g.write_glb(&dir.path().join("t.glb"));
    let scene = "[camera]\nposition = [0, 0, 9]\n[[lights]]\ntype = \"point\"\npower = 1\n\
                 position = [0, 0, 1]\n[[shapes]]\ntype = \"gltf\"\nfile = \"t.glb\"\n\
                 nodes = [\"Child\"]\n";
    let path = dir.path().join("s.toml");
    std::fs::write(&path, scene).unwrap();
    let loaded = brume::scene::load(&path, &[]).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(loaded.desc.shapes.len(), 2, "only the child's triangle");
    let brume::scene::desc::ShapeKindDesc::Gltf(g) = &loaded.desc.shapes[1].kind else {
        panic!()
    };
    let part = g.part.as_ref().expect("a part");
    let brume::geometry::ShapeKind::Mesh {
        positions, indices, ..
    } = &*part.mesh
    else {
        panic!()
    };
    assert_eq!(positions[1].to_array(), [11.0, 0.0, 1.0]);
    // Mirrored by z -> -z: the winding is swapped, so that the face turns the way it did.
    assert_eq!(indices[0], [0, 2, 1]);
    assert_eq!(part.path, "meshes[0].primitives[0]");
}

#[test]
fn materials_are_overridden_by_name_and_a_wrong_name_is_refused() {
    let dir = tempfile::tempdir().expect("tempdir");
    street().write_glb(&dir.path().join("street.glb"));
    let base = "[camera]\nposition = [0, 0, 9]\n[materials.steel]\ntype = \"mirror\"\n\
                [[lights]]\ntype = \"point\"\npower = 1\nposition = [0, 0, 1]\n\
                [[shapes]]\ntype = \"gltf\"\nfile = \"street.glb\"\n[shapes.materials]\n";
    let path = dir.path().join("s.toml");
    std::fs::write(&path, format!("{base}Floor = \"steel\"\n")).unwrap();
    let loaded = brume::scene::load(&path, &[]).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(
        loaded.desc.shapes[1].common.material.as_deref(),
        Some("steel")
    );
    // The panel keeps its own material and its emission.
    assert_eq!(
        loaded.desc.shapes[2].common.material.as_deref(),
        Some("gltf0:1:Lamp")
    );
    std::fs::write(&path, format!("{base}Flor = \"steel\"\n")).unwrap();
    let e = brume::scene::load(&path, &[])
        .expect_err("a name the file lacks")
        .to_string();
    assert!(
        e.contains("shapes.0.materials.Flor") && e.contains("Floor, Lamp"),
        "{e}"
    );
    assert!(e.contains("s.toml:"), "{e}");
}

#[test]
fn metallic_transmissive_and_textured_materials_map_to_brume_kinds() {
    let dir = tempfile::tempdir().expect("tempdir");
    let mut g = Gltf::new();
    let mut png = Vec::new();
    {
        let mut enc = png::Encoder::new(&mut png, 2, 1);
        enc.set_color(png::ColorType::Rgb);
        enc.set_depth(png::BitDepth::Eight);
        let mut w = enc.write_header().unwrap();
        w.write_image_data(&[255, 0, 0, 0, 0, 255]).unwrap();
    }
    let tex = g.texture(&png, "image/png");
    g.use_extension("KHR_materials_transmission");
    g.use_extension("KHR_materials_ior");
    let mats = [
        json!({ "name": "Metal", "pbrMetallicRoughness": { "baseColorFactor": [0.9, 0.6, 0.3, 1.0],
            "metallicFactor": 1.0, "roughnessFactor": 0.5 } }),
        json!({ "name": "Half", "pbrMetallicRoughness": { "metallicFactor": 0.5 } }),
        json!({ "name": "Glass", "extensions": {
            "KHR_materials_transmission": { "transmissionFactor": 1.0 },
            "KHR_materials_ior": { "ior": 1.33 } } }),
        json!({ "name": "Paint", "pbrMetallicRoughness": { "metallicFactor": 0.0,
            "baseColorTexture": { "index": tex } } }),
    ];
    for (k, m) in mats.into_iter().enumerate() {
        let m = g.material(m);
        let x = k as f32 * 2.0;
        let mesh = g.mesh(
            &[[x, 0.0, 0.0], [x + 1.0, 0.0, 0.0], [x, 1.0, 0.0]],
            Some(&[[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]),
            &[0, 1, 2],
            Some(m),
        );
        g.node(json!({ "mesh": mesh }));
    }
    g.write_gltf(dir.path(), "m");
    let path = dir.path().join("s.toml");
    std::fs::write(
        &path,
        "[camera]\nposition = [0, 0, 9]\n[[lights]]\ntype = \"point\"\npower = 1\n\
         position = [0, 0, 1]\n[[shapes]]\ntype = \"gltf\"\nfile = \"m.gltf\"\n",
    )
    .unwrap();
    let loaded = brume::scene::load(&path, &[]).unwrap_or_else(|e| panic!("{e}"));
    let m = &loaded.desc.materials;
    let MaterialKind::Conductor(c) = &m["gltf0:0:Metal"].kind else {
        panic!()
    };
    assert_eq!(c.roughness.alphas(), [0.25, 0.25]);
    let f0 = [0.9f32, 0.6, 0.3].map(|v| v as f64);
    assert_eq!(
        format!("{:?}", c.f0),
        format!("{:?}", Some(brume::scene::desc::SpectrumRef::Rgb(f0)))
    );
    assert!(matches!(m["gltf0:1:Half"].kind, MaterialKind::Blend(_)));
    assert!(m.contains_key("gltf0:1:Half:diffuse") && m.contains_key("gltf0:1:Half:metal"));
    let MaterialKind::Dielectric(d) = &m["gltf0:2:Glass"].kind else {
        panic!()
    };
    assert_eq!(
        format!("{:?}", d.ior),
        format!(
            "{:?}",
            brume::scene::desc::SpectrumRef::Constant(1.33f32 as f64)
        )
    );
    let MaterialKind::Lambert(p) = &m["gltf0:3:Paint"].kind else {
        panic!()
    };
    assert!(p.texture.as_ref().is_some_and(|t| t.decoded.is_some()));
    brume::scene::build(&loaded).unwrap_or_else(|e| panic!("{e}"));
}

#[test]
fn unsupported_features_are_warned_once_each_and_listed_by_info() {
    let dir = tempfile::tempdir().expect("tempdir");
    let mut g = street();
    g.use_extension("KHR_materials_clearcoat");
    g.json["materials"][0]["alphaMode"] = json!("BLEND");
    g.json["materials"][1]["alphaMode"] = json!("MASK");
    g.write_glb(&dir.path().join("street.glb"));
    let path = dir.path().join("s.toml");
    std::fs::write(
        &path,
        "[camera]\nposition = [0, 0, 9]\n[[shapes]]\ntype = \"gltf\"\nfile = \"street.glb\"\n",
    )
    .unwrap();
    let loaded = brume::scene::load(&path, &[]).unwrap_or_else(|e| panic!("{e}"));
    let w: Vec<String> = loaded.warnings.iter().map(|w| w.to_string()).collect();
    assert_eq!(w.len(), 3, "{w:#?}");
    assert!(
        w.iter()
            .any(|w| w.contains("extension KHR_materials_clearcoat")),
        "{w:#?}"
    );
    assert!(
        w.iter()
            .any(|w| w.contains("alphaMode") && w.contains("materials[0], materials[1]")),
        "{w:#?}"
    );
    assert!(
        w.iter().any(|w| w.contains("[import] lights = true")),
        "{w:#?}"
    );
    assert!(
        w.iter()
            .all(|w| w.contains("s.toml:5") && w.contains("shapes.0.file")),
        "{w:#?}"
    );
    let info = brume::scene::summary::summarise(&loaded).to_string();
    assert!(
        info.contains("ignored: extension KHR_materials_clearcoat"),
        "{info}"
    );
    assert!(info.contains("0 of 3 lights imported"), "{info}");
}

/// `luminance` (the key glTF emitters come in by) sets what the camera sees of the emitter: a
/// panel of 250 cd/m² filling the view reads 250 cd/m² in every pixel (direct emission is
/// exact: no sampling noise), whatever its colour.
#[test]
fn an_emitter_given_by_its_luminance_is_seen_at_that_luminance() {
    let dir = tempfile::tempdir().expect("tempdir");
    let path = dir.path().join("s.toml");
    std::fs::write(
        &path,
        "[film]\nbins = 16\n[camera]\nwidth = 8\nheight = 8\nposition = [0, 0, 1]\n\
         look_at = [0, 0, 0]\nfov = 20\n[[shapes]]\ntype = \"quad\"\nsize = [4, 4]\n\
         emit = [1.0, 0.5, 0.2]\nluminance = 250\n",
    )
    .expect("write");
    let loaded = brume::scene::load(&path, &[]).unwrap_or_else(|e| panic!("{e}"));
    let built = brume::scene::build(&loaded).unwrap_or_else(|e| panic!("{e}"));
    let integrator =
        brume::scene::build_integrator(&loaded, &built).unwrap_or_else(|e| panic!("{e}"));
    let mut r = Renderer::new(&built, integrator, 1);
    r.run(Budget::Passes(1), |_, _| {});
    let img = r.image();
    let w = brume::colour::photometry::luminous_weights(&img.grid).expect("weights");
    for px in img.data.chunks_exact(img.grid.n) {
        let l = brume::colour::photometry::photometric(&w, px);
        assert!((l - 250.0).abs() < 250.0 * 1e-4, "{l} cd/m²");
    }
}
