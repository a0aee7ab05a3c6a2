use glam::{Vec2, Vec3};

use super::Transform;

/// Shape geometry in its local frame.
#[derive(Clone, Debug, PartialEq)]
pub enum ShapeKind {
    /// Centred in the local XY plane, normal +Z, uv in [0,1]^2.
    Quad { size: Vec2 },
    /// Centred, outward normals, uv in [0,1]^2 on each face.
    Box { size: Vec3 },
    /// Centred; uv = (azimuth / 2pi, polar / pi) around local +Z.
    Sphere { radius: f32 },
    /// Local XY plane, normal +Z; uv = (r / radius, azimuth / 2pi).
    Disc { radius: f32 },
    /// Triangle mesh; counter-clockwise winding seen from outside gives outward normals.
    Mesh {
        positions: Vec<Vec3>,
        normals: Option<Vec<Vec3>>,
        uvs: Option<Vec<Vec2>>,
        indices: Vec<[u32; 3]>,
    },
}

/// A shape placed in the scene, with what lies on either side of it.
///
/// `material: None` is an index-matched ("null") boundary: rays pass straight through and only
/// the medium changes. `interior` / `exterior` are medium ids (`None` = vacuum); the exterior is
/// the side the geometric normal points to. A surface that does not bound a volume should have
/// `interior == exterior` (the medium it sits in): [`super::Geometry::medium_at`] skips such shapes.
/// `light` is the id of the area light the shape emits as.
#[derive(Clone, Debug, PartialEq)]
pub struct ShapeDesc {
    pub kind: ShapeKind,
    pub transform: Transform,
    pub material: Option<u32>,
    pub interior: Option<u32>,
    pub exterior: Option<u32>,
    pub light: Option<u32>,
}

impl ShapeDesc {
    /// A shape with no material, media or light, for building up with struct update syntax.
    pub fn new(kind: ShapeKind, transform: Transform) -> ShapeDesc {
        ShapeDesc {
            kind,
            transform,
            material: None,
            interior: None,
            exterior: None,
            light: None,
        }
    }

    /// Does the shape separate two different media?
    pub fn is_medium_boundary(&self) -> bool {
        self.interior != self.exterior
    }
}
