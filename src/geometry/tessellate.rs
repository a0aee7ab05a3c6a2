//! Turns quads and meshes into world-space triangles with shading attributes (spheres, discs
//! and boxes are analytic primitives).

use glam::{Vec2, Vec3, vec2, vec3};

use super::{GeometryError, ShapeDesc, ShapeKind};

/// A world-space triangle of some shape, with per-vertex shading normals (if the shape has them)
/// and uvs. Vertex order is such that `(v1 - v0) x (v2 - v0)` points out of the shape.
#[derive(Clone, Copy, Debug)]
pub(crate) struct WorldTri {
    pub v: [Vec3; 3],
    pub n: Option<[Vec3; 3]>,
    pub uv: [Vec2; 3],
}

/// Appends the triangles of `desc` (none for analytic shapes) to `out`.
pub(crate) fn tessellate(
    index: usize,
    desc: &ShapeDesc,
    out: &mut Vec<WorldTri>,
) -> Result<(), GeometryError> {
    let bad = |message: String| GeometryError::InvalidShape {
        shape: index,
        message,
    };
    let mut local: Vec<WorldTri> = Vec::new();
    match &desc.kind {
        ShapeKind::Sphere { .. } | ShapeKind::Disc { .. } | ShapeKind::Box { .. } => return Ok(()),
        ShapeKind::Quad { size } => {
            let h = *size * 0.5;
            let q = [
                vec3(-h.x, -h.y, 0.0),
                vec3(h.x, -h.y, 0.0),
                vec3(h.x, h.y, 0.0),
                vec3(-h.x, h.y, 0.0),
            ];
            push_quad(&mut local, q);
        }
        ShapeKind::Mesh {
            positions,
            normals,
            uvs,
            indices,
        } => mesh_triangles(positions, normals, uvs, indices, &mut local).map_err(bad)?,
    }
    let t = &desc.transform;
    let flip = t.flips();
    for mut tri in local {
        tri.v = tri.v.map(|p| t.point(p));
        tri.n = tri.n.map(|n| n.map(|n| t.normal(n)));
        if flip {
            // Mirroring reverses winding: restore outward orientation.
            tri.v.swap(1, 2);
            tri.uv.swap(1, 2);
            if let Some(n) = tri.n.as_mut() {
                n.swap(1, 2);
            }
        }
        if !tri.v.iter().all(|p| p.is_finite()) {
            return Err(bad("non-finite vertex after transform".into()));
        }
        out.push(tri);
    }
    Ok(())
}

/// A mesh's triangles in its local frame, checked (attribute counts, indices), degenerate ones
/// dropped; the error says what is wrong.
fn mesh_triangles(
    positions: &[Vec3],
    normals: &Option<Vec<Vec3>>,
    uvs: &Option<Vec<Vec2>>,
    indices: &[[u32; 3]],
    out: &mut Vec<WorldTri>,
) -> Result<(), String> {
    let np = positions.len();
    if normals.as_ref().is_some_and(|n| n.len() != np) {
        return Err("mesh normals count differs from positions".into());
    }
    if uvs.as_ref().is_some_and(|u| u.len() != np) {
        return Err("mesh uv count differs from positions".into());
    }
    for tri in indices {
        if tri.iter().any(|&i| i as usize >= np) {
            return Err(format!("mesh index out of range in {tri:?}"));
        }
        let [a, b, c] = tri.map(|i| i as usize);
        let v = [positions[a], positions[b], positions[c]];
        if (v[1] - v[0]).cross(v[2] - v[0]).length_squared() == 0.0 {
            continue; // degenerate: can never be hit, would only slow the BVH
        }
        out.push(WorldTri {
            v,
            n: normals.as_ref().map(|n| [n[a], n[b], n[c]]),
            uv: uvs
                .as_ref()
                .map_or([Vec2::ZERO, Vec2::X, Vec2::Y], |u| [u[a], u[b], u[c]]),
        });
    }
    Ok(())
}

/// Two triangles of a planar quad given counter-clockwise (seen from its normal side),
/// with uv (0,0) at the first corner and (1,1) at the third.
fn push_quad(out: &mut Vec<WorldTri>, q: [Vec3; 4]) {
    let uv = [
        vec2(0.0, 0.0),
        vec2(1.0, 0.0),
        vec2(1.0, 1.0),
        vec2(0.0, 1.0),
    ];
    out.push(WorldTri {
        v: [q[0], q[1], q[2]],
        n: None,
        uv: [uv[0], uv[1], uv[2]],
    });
    out.push(WorldTri {
        v: [q[0], q[2], q[3]],
        n: None,
        uv: [uv[0], uv[2], uv[3]],
    });
}
