use std::path::Path;

use glam::{Vec2, Vec3};

use super::{GeometryError, ShapeKind};

/// Loads every object of a Wavefront OBJ file into one triangle mesh (polygons are triangulated;
/// normals and uvs are kept only when every vertex has them).
pub fn load_obj(path: &Path) -> Result<ShapeKind, GeometryError> {
    let err = |message: String| GeometryError::Obj {
        path: path.to_path_buf(),
        message,
    };
    let opts = tobj::LoadOptions {
        triangulate: true,
        single_index: true,
        ..Default::default()
    };
    let (models, _materials) = tobj::load_obj(path, &opts).map_err(|e| err(e.to_string()))?;
    let mut positions = Vec::new();
    let mut normals = Vec::new();
    let mut uvs = Vec::new();
    let mut indices = Vec::new();
    let (mut all_normals, mut all_uvs) = (true, true);
    for (k, m) in models.iter().enumerate() {
        let mesh = &m.mesh;
        let base = positions.len() as u32;
        let nv = mesh.positions.len() / 3;
        positions.extend(
            mesh.positions
                .chunks_exact(3)
                .map(|c| Vec3::new(c[0], c[1], c[2])),
        );
        all_normals &= mesh.normals.len() == nv * 3;
        all_uvs &= mesh.texcoords.len() == nv * 2;
        normals.extend(
            mesh.normals
                .chunks_exact(3)
                .map(|c| Vec3::new(c[0], c[1], c[2])),
        );
        uvs.extend(
            mesh.texcoords
                .chunks_exact(2)
                .map(|c| Vec2::new(c[0], c[1])),
        );
        for tri in mesh.indices.chunks_exact(3) {
            let t = [tri[0] + base, tri[1] + base, tri[2] + base];
            if t.iter().any(|&i| i as usize >= positions.len()) {
                // The object is counted, not named: a file's text is never echoed.
                return Err(err(format!(
                    "face index out of range in object {} of the file",
                    k + 1
                )));
            }
            indices.push(t);
        }
    }
    if indices.is_empty() {
        return Err(err("no triangles".into()));
    }
    Ok(ShapeKind::Mesh {
        positions,
        normals: all_normals.then_some(normals),
        uvs: all_uvs.then_some(uvs),
        indices,
    })
}
