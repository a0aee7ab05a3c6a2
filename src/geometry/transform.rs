use glam::{EulerRot, Mat3, Mat4, Quat, Vec3};

/// Object-to-world transform: scale, then rotate (Euler angles in degrees: about the world X
/// axis first, then Y, then Z, i.e. R = Rz Ry Rx), then translate.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Transform {
    m: Mat4,
    inv: Mat4,
    /// Inverse transpose of the linear part: maps normals.
    n: Mat3,
}

impl Default for Transform {
    fn default() -> Self {
        Self::IDENTITY
    }
}

impl Transform {
    pub const IDENTITY: Transform = Transform {
        m: Mat4::IDENTITY,
        inv: Mat4::IDENTITY,
        n: Mat3::IDENTITY,
    };

    pub fn new(translate: Vec3, rotate_deg: Vec3, scale: Vec3) -> Transform {
        // glam's ZYX order composes Rz * Ry * Rx: X is applied to the shape first.
        let q = Quat::from_euler(
            EulerRot::ZYX,
            rotate_deg.z.to_radians(),
            rotate_deg.y.to_radians(),
            rotate_deg.x.to_radians(),
        );
        Self::from_matrix(Mat4::from_scale_rotation_translation(scale, q, translate))
    }

    pub fn translate(t: Vec3) -> Transform {
        Self::from_matrix(Mat4::from_translation(t))
    }

    /// Any invertible affine matrix; a singular one (zero scale) gives a non-finite inverse,
    /// which [`super::Geometry::new`] rejects.
    pub fn from_matrix(m: Mat4) -> Transform {
        let inv = m.inverse();
        let n = Mat3::from_mat4(m).inverse().transpose();
        Transform { m, inv, n }
    }

    pub fn matrix(&self) -> Mat4 {
        self.m
    }

    pub fn is_valid(&self) -> bool {
        self.inv.is_finite() && self.n.is_finite() && self.m.determinant().abs() > 1e-12
    }

    pub fn point(&self, p: Vec3) -> Vec3 {
        self.m.transform_point3(p)
    }

    pub fn vector(&self, v: Vec3) -> Vec3 {
        self.m.transform_vector3(v)
    }

    /// Maps a normal and renormalises it.
    pub fn normal(&self, n: Vec3) -> Vec3 {
        (self.n * n).normalize()
    }

    pub fn inv_point(&self, p: Vec3) -> Vec3 {
        self.inv.transform_point3(p)
    }

    pub fn inv_vector(&self, v: Vec3) -> Vec3 {
        self.inv.transform_vector3(v)
    }

    /// Does the transform flip handedness (negative scale)? Outward normals of mapped triangles
    /// then need their winding reversed.
    pub fn flips(&self) -> bool {
        self.m.determinant() < 0.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn euler_angles_apply_x_then_y_then_z() {
        // +Z rotated by -90 about Y gives -X; then +45 about Z gives (-1, -1, 0)/sqrt(2).
        let t = Transform::new(Vec3::ZERO, Vec3::new(0.0, -90.0, 45.0), Vec3::ONE);
        let n = t.normal(Vec3::Z).normalize();
        let want = Vec3::new(-1.0, -1.0, 0.0).normalize();
        assert!(n.distance(want) < 1e-5, "{n}");
        // -90 about X turns +Z into +Y.
        let t = Transform::new(Vec3::ZERO, Vec3::new(-90.0, 0.0, 0.0), Vec3::ONE);
        assert!(t.normal(Vec3::Z).normalize().distance(Vec3::Y) < 1e-5);
    }
}
