//! `type = "gltf"`: the triangle meshes of a glTF 2.0 file (`.gltf` or `.glb`). Loading expands
//! such a shape into one part per mesh primitive (`scene::gltf`); this file holds its keys,
//! their checks and the runtime mesh of a part.

use std::collections::BTreeMap;
use std::fmt;
use std::sync::Arc;

use serde::{Deserialize, Serialize};

use crate::geometry::ShapeKind;
use crate::scene::check::Checker;

/// Which glTF scene to read: its index or its name.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(untagged)]
pub enum SceneRef {
    Index(usize),
    Name(String),
}

#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GltfDesc {
    /// `.gltf` or `.glb` file, relative to the scene file.
    pub file: String,
    /// The glTF scene to read (default: the file's `scene`, else its first).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub scene: Option<SceneRef>,
    /// Only these nodes (by name) and their children, with their full transforms.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub nodes: Vec<String>,
    /// glTF material name -> scene material name: replaces the imported material.
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub materials: BTreeMap<String, String>,
    /// Set on the parts loading makes (never read from a scene file).
    #[serde(skip)]
    pub part: Option<Part>,
}

/// One imported primitive: its triangles (in the glTF file's frame, node transforms applied)
/// and where it came from (`meshes[m].primitives[p]` under `nodes[n]`).
#[derive(Clone)]
pub struct Part {
    pub mesh: Arc<ShapeKind>,
    pub path: String,
    /// The `[[shapes]]` index of the glTF shape it came from.
    pub shape: usize,
}

impl fmt::Debug for Part {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        // The vertices would flood any debug output.
        write!(f, "Part({} of shapes.{})", self.path, self.shape)
    }
}

impl GltfDesc {
    pub(super) fn check(&self, c: &mut Checker, key: &str) {
        if self.part.is_none() {
            c.file(&format!("{key}.file"), &self.file);
        }
        for (name, m) in &self.materials {
            c.material(&format!("{key}.materials.{name}"), m);
        }
    }

    /// A part's mesh; the shape as written in the scene file holds no triangles itself (its
    /// parts follow the scene's own shapes).
    pub(super) fn build(&self) -> ShapeKind {
        match &self.part {
            Some(p) => (*p.mesh).clone(),
            None => ShapeKind::Mesh {
                positions: Vec::new(),
                normals: None,
                uvs: None,
                indices: Vec::new(),
            },
        }
    }
}
