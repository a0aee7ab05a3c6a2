//! The node hierarchy (the scene picked, or the named nodes and their children) with each
//! node's world matrix, and a primitive's triangles in that frame.

use glam::{Mat3, Mat4, Vec2, Vec3};
use gltf::accessor::{DataType, Dimensions};
use gltf::mesh::Mode;

use super::accessor::{read_floats, read_indices};
use super::file::{Fault, GltfFile};
use crate::geometry::ShapeKind;
use crate::scene::shapes::SceneRef;

/// Most vertices or indices of one primitive: indices are u32.
const MAX_ELEMENTS: usize = u32::MAX as usize;

/// The nodes to import, depth first in file order, each with its world matrix.
pub fn nodes<'a>(
    f: &'a GltfFile,
    scene: Option<&SceneRef>,
    names: &[String],
) -> Result<Vec<(gltf::Node<'a>, Mat4)>, Fault> {
    let roots = roots(f, scene)?;
    let limit = f.doc.nodes().len();
    let mut out = Vec::new();
    let mut found = vec![false; names.len()];
    // (node, parent's world matrix, inside a named node, depth)
    let mut stack: Vec<(gltf::Node, Mat4, bool, usize)> = roots
        .into_iter()
        .rev()
        .map(|n| (n, Mat4::IDENTITY, names.is_empty(), 0))
        .collect();
    while let Some((node, parent, inside, depth)) = stack.pop() {
        if depth > limit {
            return Err(Fault::at(
                format!("nodes[{}]", node.index()),
                "the node hierarchy has a cycle (a node is its own ancestor)",
            ));
        }
        let local = Mat4::from_cols_array_2d(&node.transform().matrix());
        let world = if local == Mat4::IDENTITY {
            parent
        } else {
            parent * local
        };
        let named = node.name().and_then(|n| names.iter().position(|m| m == n));
        if let Some(i) = named {
            found[i] = true;
        }
        let inside = inside || named.is_some();
        if inside {
            out.push((node.clone(), world));
        }
        let children: Vec<_> = node.children().collect();
        for c in children.into_iter().rev() {
            stack.push((c, world, inside, depth + 1));
        }
    }
    if let Some(i) = found.iter().position(|f| !f) {
        return Err(Fault::at(
            "nodes",
            format!("no node named `{}` in the scene read", names[i]),
        ));
    }
    Ok(out)
}

/// The root nodes of the scene picked, of the file's default scene, of its first, or (a file
/// without scenes) every node that is no other's child.
fn roots<'a>(f: &'a GltfFile, scene: Option<&SceneRef>) -> Result<Vec<gltf::Node<'a>>, Fault> {
    let n = f.doc.scenes().len();
    let picked = match scene {
        Some(SceneRef::Index(i)) => Some(f.doc.scenes().nth(*i).ok_or_else(|| {
            Fault::at("scenes", format!("no scenes[{i}]: the file has {n} scenes"))
        })?),
        Some(SceneRef::Name(name)) => Some(
            f.doc
                .scenes()
                .find(|s| s.name() == Some(name.as_str()))
                .ok_or_else(|| Fault::at("scenes", format!("no scene named `{name}`")))?,
        ),
        None => f.doc.default_scene().or_else(|| f.doc.scenes().next()),
    };
    if let Some(s) = picked {
        return Ok(s.nodes().collect());
    }
    let mut child = vec![false; f.doc.nodes().len()];
    for node in f.doc.nodes() {
        for c in node.children() {
            child[c.index()] = true;
        }
    }
    Ok(f.doc.nodes().filter(|n| !child[n.index()]).collect())
}

/// The triangles of primitive `p` at `world` (`at` is its glTF path). Strips and fans become
/// triangles; points and lines are refused.
pub fn triangles(
    f: &GltfFile,
    p: &gltf::Primitive,
    world: Mat4,
    at: &str,
) -> Result<ShapeKind, Fault> {
    let Some(pos) = p.get(&gltf::Semantic::Positions) else {
        return Err(Fault::at(at, "has no POSITION attribute"));
    };
    let pos_at = format!("{at}.attributes.POSITION");
    let positions = read_floats(f, &pos, Dimensions::Vec3, &[DataType::F32], &pos_at)?;
    let n = positions.len() / 3;
    if n > MAX_ELEMENTS {
        return Err(Fault::at(
            pos_at,
            format!("{n} vertices: more than u32 indices reach"),
        ));
    }
    let order: Vec<u32> = match p.indices() {
        Some(acc) => read_indices(f, &acc, &format!("{at}.indices"))?,
        None => (0..n as u32).collect(),
    };
    if let Some((k, i)) = order.iter().enumerate().find(|(_, i)| **i as usize >= n) {
        return Err(Fault::at(
            format!("{at}.indices"),
            format!("index {i} (entry {k}) is beyond the primitive's {n} vertices"),
        ));
    }
    let mut indices = assemble(p.mode(), &order, at)?;
    let normals = match p.get(&gltf::Semantic::Normals) {
        Some(acc) => {
            let a = format!("{at}.attributes.NORMAL");
            let v = read_floats(f, &acc, Dimensions::Vec3, &[DataType::F32], &a)?;
            same_count(v.len() / 3, n, &a)?;
            Some(
                v.chunks_exact(3)
                    .map(|c| Vec3::new(c[0], c[1], c[2]))
                    .collect::<Vec<_>>(),
            )
        }
        None => None,
    };
    let uvs = match p.get(&gltf::Semantic::TexCoords(0)) {
        Some(acc) => {
            let a = format!("{at}.attributes.TEXCOORD_0");
            let types = [DataType::F32, DataType::U8, DataType::U16];
            let v = read_floats(f, &acc, Dimensions::Vec2, &types, &a)?;
            same_count(v.len() / 2, n, &a)?;
            // glTF's v runs down the image, brume's up.
            Some(
                v.chunks_exact(2)
                    .map(|c| Vec2::new(c[0], 1.0 - c[1]))
                    .collect(),
            )
        }
        None => None,
    };
    let mut positions: Vec<Vec3> = positions
        .chunks_exact(3)
        .map(|c| Vec3::new(c[0], c[1], c[2]))
        .collect();
    let mut normals = normals;
    if world != Mat4::IDENTITY {
        place(world, &mut positions, normals.as_deref_mut(), &mut indices);
    }
    Ok(ShapeKind::Mesh {
        positions,
        normals,
        uvs,
        indices,
    })
}

/// Moves vertices and normals by `world` (normals by its inverse transpose).
fn place(
    world: Mat4,
    positions: &mut [Vec3],
    normals: Option<&mut [Vec3]>,
    indices: &mut [[u32; 3]],
) {
    for q in positions.iter_mut() {
        *q = world.transform_point3(*q);
    }
    let m = Mat3::from_mat4(world);
    let normal = m.inverse().transpose();
    for v in normals.into_iter().flatten() {
        *v = (normal * *v).normalize_or_zero();
    }
    // A mirroring transform turns counter-clockwise faces clockwise (glTF 2.0, 3.7.4).
    if m.determinant() < 0.0 {
        for t in indices.iter_mut() {
            t.swap(1, 2);
        }
    }
}

fn same_count(got: usize, n: usize, at: &str) -> Result<(), Fault> {
    if got == n {
        return Ok(());
    }
    Err(Fault::at(
        at,
        format!("{got} entries for the primitive's {n} vertices"),
    ))
}

/// Index triples of the triangles `mode` makes of `order`.
fn assemble(mode: Mode, order: &[u32], at: &str) -> Result<Vec<[u32; 3]>, Fault> {
    let tris = match mode {
        Mode::Triangles => {
            if !order.len().is_multiple_of(3) {
                return Err(Fault::at(
                    at,
                    format!("{} indices do not make whole triangles", order.len()),
                ));
            }
            order.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect()
        }
        // Every other strip triangle is flipped to keep one winding.
        Mode::TriangleStrip => (2..order.len())
            .map(|i| {
                let (a, b, c) = (order[i - 2], order[i - 1], order[i]);
                if i % 2 == 0 { [a, b, c] } else { [b, a, c] }
            })
            .collect(),
        Mode::TriangleFan => (2..order.len())
            .map(|i| [order[0], order[i - 1], order[i]])
            .collect(),
        Mode::Points | Mode::Lines | Mode::LineLoop | Mode::LineStrip => {
            return Err(Fault::at(
                format!("{at}.mode"),
                format!("{mode:?} is not a surface: brume reads triangles, strips and fans"),
            ));
        }
    };
    Ok(tris)
}
