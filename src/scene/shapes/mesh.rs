//! `type = "mesh"`: a triangle mesh from a Wavefront OBJ file.

use serde::{Deserialize, Serialize};

use crate::geometry::{self, ShapeKind};
use crate::scene::builder::Builder;
use crate::scene::check::Checker;
use crate::scene::error::SceneError;

#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MeshDesc {
    /// OBJ file, relative to the scene file.
    pub file: String,
}

impl MeshDesc {
    pub(super) fn check(&self, c: &mut Checker, key: &str) {
        c.file(&format!("{key}.file"), &self.file);
    }

    /// The mesh, its vertices within what the geometry holds (an OBJ with vertices at 1e10 m
    /// rendered black: its normals overflowed).
    pub(super) fn build(&self, b: &Builder, key: &str) -> Result<ShapeKind, SceneError> {
        let key = format!("{key}.file");
        let path = b.source.resolve(&self.file);
        let kind = geometry::load_obj(&path).map_err(|e| b.source.invalid(&key, e.to_string()))?;
        if let ShapeKind::Mesh { positions, .. } = &kind
            && let Some((i, why)) = positions
                .iter()
                .enumerate()
                .find_map(|(i, &p)| geometry::out_of_range(p).map(|w| (i, w)))
        {
            let message = format!("{}: vertex {}: {why}", path.display(), i + 1);
            return Err(b.source.invalid(&key, message));
        }
        Ok(kind)
    }
}
