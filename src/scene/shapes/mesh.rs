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

    pub(super) fn build(&self, b: &Builder, key: &str) -> Result<ShapeKind, SceneError> {
        let key = format!("{key}.file");
        geometry::load_obj(&b.source.resolve(&self.file))
            .map_err(|e| b.source.invalid(&key, e.to_string()))
    }
}
