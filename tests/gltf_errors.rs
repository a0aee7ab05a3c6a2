//! Bad glTF files are refused when the scene loads, before anything renders: each error names
//! the scene file, line and key of the shape, the glTF file and the glTF path of the object at
//! fault. The files are written by the test (tests/gltf/writer.rs) and then broken.

#[path = "gltf/writer.rs"]
mod writer;

use std::path::Path;

use serde_json::json;
use writer::Gltf;

/// A triangle with a material whose base colour is a texture.
fn good() -> Gltf {
    let mut g = Gltf::new();
    let mut png = Vec::new();
    {
        let mut enc = png::Encoder::new(&mut png, 1, 1);
        enc.set_color(png::ColorType::Rgb);
        let mut w = enc.write_header().expect("png header");
        w.write_image_data(&[200, 100, 50]).expect("png data");
    }
    let tex = g.texture(&png, "image/png");
    let m = g.material(json!({ "name": "Paint",
        "pbrMetallicRoughness": { "baseColorTexture": { "index": tex }, "metallicFactor": 0.0 } }));
    let uv = [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]];
    let mesh = g.mesh(
        &[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
        Some(&uv),
        &[0, 1, 2],
        Some(m),
    );
    g.node(json!({ "mesh": mesh }));
    g
}

const SCENE: &str = "[camera]\nposition = [0, 0, 5]\n\n[[lights]]\ntype = \"point\"\n\
                     power = 1\nposition = [0, 0, 1]\n\n[[shapes]]\ntype = \"gltf\"\n";

/// Loads a scene whose shape reads `file` in `dir`; the error's text.
fn refusal(dir: &Path, file: &str) -> String {
    let path = dir.join("scene.toml");
    std::fs::write(&path, format!("{SCENE}file = \"{file}\"\n")).expect("write scene");
    match brume::scene::load(&path, &[]) {
        Ok(_) => panic!("{file} was accepted"),
        Err(e) => e.to_string(),
    }
}

/// The error names the scene's line and key, the glTF file and every one of `parts`.
fn assert_names(e: &str, file: &str, parts: &[&str]) {
    assert!(
        e.contains("scene.toml:11") && e.contains("shapes.0.file"),
        "{e}"
    );
    assert!(e.contains(file), "{e}");
    for p in parts {
        assert!(e.contains(p), "`{p}` missing from: {e}");
    }
}

#[test]
fn the_good_file_loads_and_builds() {
    let dir = tempfile::tempdir().expect("tempdir");
    good().write_gltf(dir.path(), "good");
    let path = dir.path().join("scene.toml");
    std::fs::write(&path, format!("{SCENE}file = \"good.gltf\"\n")).expect("write");
    let loaded = brume::scene::load(&path, &[]).unwrap_or_else(|e| panic!("{e}"));
    brume::scene::build(&loaded).unwrap_or_else(|e| panic!("{e}"));
}

#[test]
fn a_missing_bin_buffer_is_refused() {
    let dir = tempfile::tempdir().expect("tempdir");
    good().write_gltf(dir.path(), "t");
    std::fs::remove_file(dir.path().join("t.bin")).expect("remove");
    let e = refusal(dir.path(), "t.gltf");
    assert_names(&e, "t.gltf", &["buffers[0]", "t.bin"]);
}

#[test]
fn an_accessor_index_beyond_the_accessors_is_refused() {
    let dir = tempfile::tempdir().expect("tempdir");
    let mut g = good();
    g.json["meshes"][0]["primitives"][0]["indices"] = json!(99);
    g.write_glb(&dir.path().join("t.glb"));
    let e = refusal(dir.path(), "t.glb");
    assert_names(&e, "t.glb", &["meshes[0].primitives[0].indices"]);
}

#[test]
fn a_vertex_index_beyond_the_vertices_is_refused() {
    let dir = tempfile::tempdir().expect("tempdir");
    let mut g = Gltf::new();
    let mesh = g.mesh(
        &[[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
        None,
        &[0, 1, 7],
        None,
    );
    g.node(json!({ "mesh": mesh }));
    g.write_glb(&dir.path().join("t.glb"));
    let e = refusal(dir.path(), "t.glb");
    assert_names(&e, "t.glb", &["meshes[0].primitives[0].indices", "index 7"]);
}

#[test]
fn a_primitive_of_lines_is_refused() {
    let dir = tempfile::tempdir().expect("tempdir");
    let mut g = good();
    g.json["meshes"][0]["primitives"][0]["mode"] = json!(1);
    g.write_glb(&dir.path().join("t.glb"));
    let e = refusal(dir.path(), "t.glb");
    assert_names(&e, "t.glb", &["meshes[0].primitives[0].mode", "Lines"]);
}

#[test]
fn a_texture_that_cannot_be_decoded_is_refused() {
    let dir = tempfile::tempdir().expect("tempdir");
    let mut g = good();
    // The image's view (the first one) overwritten with bytes that are no PNG.
    let len = g.json["bufferViews"][0]["byteLength"]
        .as_u64()
        .expect("length") as usize;
    g.bin[..len].fill(0x5a);
    g.write_glb(&dir.path().join("t.glb"));
    let e = refusal(dir.path(), "t.glb");
    assert_names(&e, "t.glb", &["images[0]", "cannot decode"]);
}

#[test]
fn a_huge_index_count_is_refused_before_it_is_allocated() {
    let dir = tempfile::tempdir().expect("tempdir");
    let mut g = good();
    let idx = g.json["meshes"][0]["primitives"][0]["indices"]
        .as_u64()
        .expect("index");
    g.json["accessors"][idx as usize]["count"] = json!(3u64 << 40);
    g.write_glb(&dir.path().join("t.glb"));
    let e = refusal(dir.path(), "t.glb");
    assert_names(
        &e,
        "t.glb",
        &[
            "meshes[0].primitives[0].indices",
            &format!("accessors[{idx}]"),
            "3298534883328 elements",
        ],
    );
}

#[test]
fn a_buffer_view_beyond_its_buffer_is_refused() {
    let dir = tempfile::tempdir().expect("tempdir");
    let mut g = good();
    g.json["bufferViews"][1]["byteLength"] = json!(1u64 << 33);
    g.write_glb(&dir.path().join("t.glb"));
    let e = refusal(dir.path(), "t.glb");
    assert_names(&e, "t.glb", &["bufferViews[1]"]);
}

#[test]
fn a_node_that_is_its_own_ancestor_is_refused() {
    let dir = tempfile::tempdir().expect("tempdir");
    let mut g = good();
    g.json["nodes"][0]["children"] = json!([0]);
    g.write_glb(&dir.path().join("t.glb"));
    let e = refusal(dir.path(), "t.glb");
    assert_names(&e, "t.glb", &["nodes[0]"]);
}

#[test]
fn an_extension_the_file_requires_and_brume_lacks_is_refused() {
    let dir = tempfile::tempdir().expect("tempdir");
    let mut g = good();
    g.use_extension("KHR_draco_mesh_compression");
    g.json["extensionsRequired"] = json!(["KHR_draco_mesh_compression"]);
    g.write_glb(&dir.path().join("t.glb"));
    let e = refusal(dir.path(), "t.glb");
    assert_names(
        &e,
        "t.glb",
        &["extensionsRequired", "KHR_draco_mesh_compression"],
    );
}

#[test]
fn a_file_that_is_not_gltf_and_an_absent_node_name_are_refused() {
    let dir = tempfile::tempdir().expect("tempdir");
    std::fs::write(dir.path().join("t.glb"), b"glTF\x02\0\0\0garbage").expect("write");
    let e = refusal(dir.path(), "t.glb");
    assert_names(&e, "t.glb", &[]);
    good().write_glb(&dir.path().join("g.glb"));
    let path = dir.path().join("scene.toml");
    let text = format!("{SCENE}file = \"g.glb\"\nnodes = [\"Pole\"]\n");
    std::fs::write(&path, text).expect("write");
    let e = brume::scene::load(&path, &[])
        .expect_err("no such node")
        .to_string();
    assert!(
        e.contains("scene.toml:12") && e.contains("shapes.0.nodes") && e.contains("`Pole`"),
        "{e}"
    );
}

#[test]
fn a_scene_is_picked_by_index_or_name_and_an_absent_one_is_refused() {
    let dir = tempfile::tempdir().expect("tempdir");
    let mut g = good();
    g.json["scenes"][0]["name"] = json!("Street");
    g.json["scenes"]
        .as_array_mut()
        .expect("scenes")
        .push(json!({ "name": "Empty", "nodes": [] }));
    g.write_glb(&dir.path().join("g.glb"));
    let path = dir.path().join("scene.toml");
    let shapes = |scene: &str| {
        std::fs::write(&path, format!("{SCENE}file = \"g.glb\"\nscene = {scene}\n"))
            .expect("write");
        brume::scene::load(&path, &[]).map(|l| l.desc.shapes.len())
    };
    assert_eq!(shapes("\"Street\"").expect("by name"), 2);
    assert_eq!(shapes("1").expect("by index"), 1);
    let e = shapes("2").expect_err("no third scene").to_string();
    assert!(
        e.contains("scene.toml:12") && e.contains("shapes.0.scene") && e.contains("2 scenes"),
        "{e}"
    );
    let e = shapes("\"Park\"").expect_err("no such name").to_string();
    assert!(e.contains("shapes.0.scene") && e.contains("`Park`"), "{e}");
}

/// A problem only the imported parts have (here the shape's `emit_scale` beside the luminance an
/// emissive glTF material gives its part) is placed at the glTF shape's own keys, with the
/// part named, not at a `shapes.<n>` the scene file does not have.
#[test]
fn a_problem_of_an_imported_part_names_the_gltf_shape_and_the_part() {
    let dir = tempfile::tempdir().expect("tempdir");
    let mut g = Gltf::new();
    let m = g.material(json!({ "name": "Lens", "emissiveFactor": [1.0, 0.9, 0.8] }));
    let mesh = g.mesh(
        &[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
        None,
        &[0, 1, 2],
        Some(m),
    );
    g.node(json!({ "mesh": mesh }));
    g.write_gltf(dir.path(), "lens");
    let path = dir.path().join("scene.toml");
    std::fs::write(
        &path,
        format!("{SCENE}file = \"lens.gltf\"\nemit_scale = 2.0\n"),
    )
    .expect("write scene");
    let e = match brume::scene::load(&path, &[]) {
        Ok(_) => panic!("emit_scale beside a glTF emitter was accepted"),
        Err(e) => e.to_string(),
    };
    assert!(e.contains("shapes.0.") && !e.contains("shapes.1"), "{e}");
    // Line 9 is the glTF shape's table (`luminance` is the part's, not written in the file).
    assert!(
        e.contains("scene.toml:9:1: key `shapes.0.luminance`"),
        "{e}"
    );
    assert!(e.contains("meshes[0].primitives[0] of lens.gltf"), "{e}");
}
