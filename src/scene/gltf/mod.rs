//! glTF 2.0 import: each `[[shapes]] type = "gltf"` is expanded, when the scene is loaded, into
//! what the scene file could have said itself: one mesh part per primitive (appended after the
//! scene's own shapes; the glTF shape keeps its index and holds no triangles), the materials
//! its primitives use (named `gltf<shape>:<index>:<name>`), its `KHR_lights_punctual` lights
//! (with `[import] lights = true`, after the scene's own lights) and its first camera (when the
//! scene's `[camera]` gives no `position`). Everything after loading (checks, `info`, building,
//! light layers, film identity) sees ordinary kinds. docs/gltf.md lists what maps to what.
//!
//! A file that cannot be read is refused at the shape's `file` key with the glTF path of the
//! offending object; what brume does not render (skins, morph targets, animations, other
//! extensions) is reported by `info` and warned about once per feature.

mod accessor;
mod file;
mod material;
mod mesh;
mod punctual;

use std::collections::BTreeMap;
use std::sync::Arc;

use super::desc::{CameraDesc, LightDesc, MaterialDesc, ShapeDesc, ShapeKindDesc, SpectrumRef};
use super::error::{SceneError, SceneWarning};
use super::import_report::GltfReport;
use super::loaded::LoadedScene;
use super::shapes::{GltfDesc, Part};
use super::source::Source;
use crate::geometry::ShapeKind;
use file::{Fault, GltfFile};

/// The extensions brume maps to its own kinds; any other is reported and ignored.
const SUPPORTED: [&str; 4] = [
    "KHR_lights_punctual",
    "KHR_materials_transmission",
    "KHR_materials_ior",
    "KHR_materials_emissive_strength",
];

/// What a file has that brume does not render: per feature, the glTF paths that have it.
#[derive(Default)]
pub struct Notes(BTreeMap<String, Vec<String>>);

impl Notes {
    pub fn add(&mut self, what: &str, at: &str) {
        let paths = self.0.entry(what.to_string()).or_default();
        if !paths.iter().any(|p| p == at) {
            paths.push(at.to_string());
        }
    }

    fn lines(&self) -> Vec<String> {
        self.0
            .iter()
            .map(|(what, at)| {
                let shown: Vec<&str> = at.iter().take(4).map(String::as_str).collect();
                let more = match at.len() {
                    n if n > 4 => format!(" and {} more", n - 4),
                    _ => String::new(),
                };
                format!("{what}: {}{more}", shown.join(", "))
            })
            .collect()
    }
}

/// Expands every glTF shape of `loaded` (see the module's description), then checks the
/// scene again as a whole.
pub fn expand(loaded: &mut LoadedScene) -> Result<(), SceneError> {
    let gltf_shapes: Vec<usize> = (0..loaded.desc.shapes.len())
        .filter(
            |&i| matches!(&loaded.desc.shapes[i].kind, ShapeKindDesc::Gltf(g) if g.part.is_none()),
        )
        .collect();
    if gltf_shapes.is_empty() {
        return Ok(());
    }
    let mut camera_given = camera_given(loaded);
    for i in gltf_shapes {
        let imported = import(loaded.source(), &loaded.desc, i, !camera_given)?;
        let d = &mut loaded.desc;
        d.shapes.extend(imported.parts);
        d.materials.extend(imported.materials);
        d.lights.extend(imported.lights);
        if let Some(c) = imported.camera {
            d.camera = c;
            camera_given = true;
        }
        loaded.warnings.extend(imported.warnings);
        loaded.imports.push(imported.report);
    }
    if let Some(problem) = super::validate::validate(loaded).into_iter().next() {
        let (key, part) = in_file(&loaded.desc, &problem.key);
        let message = format!(
            "{}{part} (after importing the scene's glTF files)",
            problem.message
        );
        return Err(loaded.source().invalid(&key, message));
    }
    Ok(())
}

/// Where a problem of the expanded scene is in the scene file: an imported part's keys
/// (`shapes.<n>...`, with `n` past the file's shapes) are the glTF shape's it came from, and the
/// part is named in the message's `" in <part> of <file>"`.
pub(crate) fn in_file(d: &super::desc::SceneDesc, key: &str) -> (String, String) {
    let Some(rest) = key.strip_prefix("shapes.") else {
        return (key.to_string(), String::new());
    };
    let (n, tail) = rest.split_once('.').unwrap_or((rest, ""));
    let part = n.parse::<usize>().ok().and_then(|n| {
        let ShapeKindDesc::Gltf(g) = &d.shapes.get(n)?.kind else {
            return None;
        };
        Some((g.part.as_ref()?, g.file.as_str()))
    });
    let Some((part, file)) = part else {
        return (key.to_string(), String::new());
    };
    let key = match tail {
        "" => format!("shapes.{}", part.shape),
        t => format!("shapes.{}.{t}", part.shape),
    };
    (key, format!(" in {} of {file}", part.path))
}

/// Does the scene file (or a `--set`) place the camera?
fn camera_given(loaded: &LoadedScene) -> bool {
    let in_file = loaded
        .text
        .parse::<toml::Table>()
        .ok()
        .and_then(|t| t.get("camera")?.get("position").cloned())
        .is_some();
    in_file
        || loaded
            .sets
            .iter()
            .any(|(_, k)| k == "camera" || k == "camera.position")
}

struct Imported {
    parts: Vec<ShapeDesc>,
    materials: BTreeMap<String, MaterialDesc>,
    lights: Vec<LightDesc>,
    camera: Option<CameraDesc>,
    warnings: Vec<SceneWarning>,
    report: GltfReport,
}

/// Where a glTF shape is and how its errors are placed.
struct Ctx<'a> {
    source: Source<'a>,
    shape: &'a ShapeDesc,
    g: &'a GltfDesc,
    /// Its index in `shapes`, and `shapes.<i>`.
    i: usize,
    key: String,
    /// The glTF file's path as shown in messages.
    shown: String,
}

impl Ctx<'_> {
    /// A fault of the file, at the shape's `file` key.
    fn refuse(&self, f: Fault) -> SceneError {
        let at = if f.path.is_empty() {
            String::new()
        } else {
            format!(": {}", f.path)
        };
        let message = format!("{}{at}: {}", self.shown, f.message);
        self.source.invalid(&format!("{}.file", self.key), message)
    }
}

/// Imports shape `i` (a glTF shape) of `d`.
fn import(
    source: Source,
    d: &super::desc::SceneDesc,
    i: usize,
    want_camera: bool,
) -> Result<Imported, SceneError> {
    let shape = &d.shapes[i];
    let ShapeKindDesc::Gltf(g) = &shape.kind else {
        unreachable!("expand passes glTF shapes only")
    };
    let path = source.resolve(&g.file);
    let cx = Ctx {
        source,
        shape,
        g,
        i,
        key: format!("shapes.{i}"),
        shown: path.display().to_string(),
    };
    let f = file::open(&path).map_err(|e| cx.refuse(e))?;
    let mut notes = Notes::default();
    check_extensions(&f, &mut notes).map_err(|e| cx.refuse(e))?;
    let nodes = mesh::nodes(&f, g.scene.as_ref(), &g.nodes).map_err(|e| match e.path.as_str() {
        "nodes" | "scenes" => {
            let k = if e.path == "nodes" { "nodes" } else { "scene" };
            let message = format!("{}: {}", cx.shown, e.message);
            source.invalid(&format!("{}.{k}", cx.key), message)
        }
        _ => cx.refuse(e),
    })?;
    let mut out = Imported::new(&cx);
    let mut mats = material::Materials::new(&f, i, cx.shown.clone());
    let mut used = vec![false; g.materials.len()];
    let mut meshes = std::collections::BTreeSet::new();
    for (node, world) in &nodes {
        if node.skin().is_some() {
            let at = format!("nodes[{}]", node.index());
            notes.add("skins (meshes drawn in their rest pose)", &at);
        }
        if let Some(m) = node.mesh() {
            meshes.insert(m.index());
            for p in m.primitives() {
                let part = Primitive {
                    f: &f,
                    p,
                    mesh: m.index(),
                    world: *world,
                };
                primitive(&cx, part, &mut mats, &mut used, &mut notes, &mut out)?;
            }
        }
        node_extras(&cx, d, node, *world, want_camera, &mut notes, &mut out)?;
    }
    unused_overrides(&cx, &f, &used)?;
    out.report.meshes = meshes.len();
    out.materials = mats.made;
    out.report.ignored = notes.lines();
    out.warnings = out
        .report
        .ignored
        .iter()
        .map(|l| {
            let message = format!("{}: ignored: {l}", cx.shown);
            source.warning(&format!("{}.file", cx.key), message)
        })
        .collect();
    Ok(out)
}

impl Imported {
    fn new(cx: &Ctx) -> Imported {
        Imported {
            parts: Vec::new(),
            materials: BTreeMap::new(),
            lights: Vec::new(),
            camera: None,
            warnings: Vec::new(),
            report: GltfReport {
                key: cx.key.clone(),
                file: cx.g.file.clone(),
                ..GltfReport::default()
            },
        }
    }
}

/// A primitive to import: its file, itself and its node's world matrix.
struct Primitive<'f> {
    f: &'f GltfFile,
    p: gltf::Primitive<'f>,
    mesh: usize,
    world: glam::Mat4,
}

/// One primitive as a part: its triangles, its material (an override by the glTF material's
/// name, the shape's `material`, or the imported material) and its emission.
fn primitive(
    cx: &Ctx,
    prim: Primitive,
    mats: &mut material::Materials,
    used: &mut [bool],
    notes: &mut Notes,
    out: &mut Imported,
) -> Result<(), SceneError> {
    let Primitive { f, p, mesh, world } = prim;
    let at = format!("meshes[{mesh}].primitives[{}]", p.index());
    note_primitive(&p, &at, notes);
    let tris = mesh::triangles(f, &p, world, &at).map_err(|e| cx.refuse(e))?;
    let m = p.material();
    let over = m
        .name()
        .and_then(|n| cx.g.materials.keys().position(|k| k == n));
    if let Some(k) = over {
        used[k] = true;
    }
    let over =
        over.and_then(|k| cx.g.materials.values().nth(k))
            .or(cx.shape.common.material.as_ref());
    let mat_at = m
        .index()
        .map_or("the default material".into(), |k| format!("materials[{k}]"));
    let (material, emit) = match over {
        Some(name) => {
            let emit = material::emission(&m, &mat_at).map_err(|e| cx.refuse(e))?;
            (name.clone(), emit)
        }
        None => {
            let s = mats.surface(m.clone(), notes).map_err(|e| cx.refuse(e))?;
            (s.material, s.emit)
        }
    };
    let r = &mut out.report;
    let gltf_name = m.name().map_or(mat_at.clone(), str::to_string);
    if !r.materials.iter().any(|(n, _)| *n == gltf_name) {
        r.materials.push((gltf_name, material.clone()));
        r.emitting += emit.is_some() as usize;
    }
    r.primitives += 1;
    if let ShapeKind::Mesh { indices, .. } = &tris {
        r.triangles += indices.len();
    }
    out.parts.push(part(cx, tris, at, material, emit));
    Ok(())
}

/// A node's light (with `[import] lights`) and camera (the first, when wanted).
fn node_extras(
    cx: &Ctx,
    d: &super::desc::SceneDesc,
    node: &gltf::Node,
    world: glam::Mat4,
    want_camera: bool,
    notes: &mut Notes,
    out: &mut Imported,
) -> Result<(), SceneError> {
    let node_at = format!("nodes[{}]", node.index());
    if let Some(l) = node.light() {
        out.report.lights.1 += 1;
        if !d.import.lights {
            let what = "KHR_lights_punctual lights (import them with [import] lights = true)";
            notes.add(what, &node_at);
        } else if let Some(light) = punctual::light(&l, world, notes).map_err(|e| cx.refuse(e))? {
            out.lights.push(light);
            out.report.lights.0 += 1;
        }
    }
    if let Some(c) = node.camera()
        && want_camera
        && out.camera.is_none()
    {
        out.camera = Some(punctual::camera(&c, world, &d.camera));
        let name = c.name().map(|n| format!(" ({n})")).unwrap_or_default();
        out.report.camera = Some(format!("cameras[{}]{name} at {node_at}", c.index()));
    }
    Ok(())
}

/// A `materials` override naming a material no primitive read uses is a mistake.
fn unused_overrides(cx: &Ctx, f: &GltfFile, used: &[bool]) -> Result<(), SceneError> {
    let Some(k) = used.iter().position(|u| !u) else {
        return Ok(());
    };
    let name = cx.g.materials.keys().nth(k).cloned().unwrap_or_default();
    let names: Vec<&str> = f.doc.materials().filter_map(|m| m.name()).collect();
    let known = if names.is_empty() {
        "none named".to_string()
    } else {
        names.join(", ")
    };
    Err(cx.source.invalid(
        &format!("{}.materials.{name}", cx.key),
        format!(
            "{}: no primitive read uses a material named `{name}` (its materials: {known})",
            cx.shown
        ),
    ))
}

/// The scene shape of one primitive: the glTF shape's keys, its material and emission.
fn part(
    cx: &Ctx,
    mesh: ShapeKind,
    path: String,
    material: String,
    emit: Option<([f64; 3], f32)>,
) -> ShapeDesc {
    let mut common = cx.shape.common.clone();
    common.material = Some(material);
    if let Some((colour, nits)) = emit {
        common.emit = Some(SpectrumRef::Rgb(colour));
        common.luminance = Some(nits);
    }
    ShapeDesc {
        common,
        kind: ShapeKindDesc::Gltf(GltfDesc {
            part: Some(Part {
                mesh: Arc::new(mesh),
                path,
                shape: cx.i,
            }),
            ..cx.g.clone()
        }),
    }
}

/// Extensions the file requires that brume cannot honour are refused; others used are noted.
fn check_extensions(f: &GltfFile, notes: &mut Notes) -> Result<(), Fault> {
    if let Some(e) = f.doc.extensions_required().find(|e| !SUPPORTED.contains(e)) {
        return Err(Fault::at(
            "extensionsRequired",
            format!("the file requires {e}, which brume does not read"),
        ));
    }
    for e in f.doc.extensions_used().filter(|e| !SUPPORTED.contains(e)) {
        notes.add(&format!("extension {e}"), "extensionsUsed");
    }
    let (skins, animations) = (f.doc.skins().len(), f.doc.animations().len());
    if animations > 0 {
        notes.add(
            "animations (the file's static pose used)",
            &format!("{animations} animations"),
        );
    }
    if skins > 0 {
        notes.add(
            "skins (meshes drawn in their rest pose)",
            &format!("{skins} skins"),
        );
    }
    Ok(())
}

/// Attributes of a primitive brume does not use.
fn note_primitive(p: &gltf::Primitive, at: &str, notes: &mut Notes) {
    if p.morph_targets().len() > 0 {
        notes.add("morph targets (the base mesh used)", at);
    }
    for (semantic, _) in p.attributes() {
        let what = match semantic {
            gltf::Semantic::Colors(_) => "vertex colours COLOR_n",
            gltf::Semantic::Tangents => "tangents",
            gltf::Semantic::TexCoords(n) if n > 0 => "texture coordinates past TEXCOORD_0",
            gltf::Semantic::Positions
            | gltf::Semantic::Normals
            | gltf::Semantic::TexCoords(_)
            // Joints and weights come with skins, noted at their nodes.
            | gltf::Semantic::Joints(_)
            | gltf::Semantic::Weights(_) => continue,
        };
        notes.add(what, at);
    }
}
