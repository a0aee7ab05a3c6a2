//! Cameras: map continuous pixel coordinates to primary rays.

use glam::Vec3;

use crate::geometry::Ray;

/// Pixel coordinates are continuous: pixel (i, j) covers [i, i+1) x [j, j+1), its centre is
/// (i + 0.5, j + 0.5), and y = 0 is the top row.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Camera {
    /// Parallel rays along `forward`, from a `view_width` x `view_height` metre rectangle centred
    /// on `position`.
    Orthographic {
        width: u32,
        height: u32,
        position: Vec3,
        forward: Vec3,
        right: Vec3,
        up: Vec3,
        view_width: f32,
        view_height: f32,
    },
    /// Pinhole at `position`; `tan_half_v` = tan(vertical fov / 2).
    Perspective {
        width: u32,
        height: u32,
        position: Vec3,
        forward: Vec3,
        right: Vec3,
        up: Vec3,
        tan_half_v: f32,
    },
}

/// Right-handed view basis: right = forward x up, then up re-orthogonalised. A degenerate `up`
/// (parallel to the view direction) falls back to another axis rather than producing NaNs.
fn basis(position: Vec3, look_at: Vec3, up: Vec3) -> (Vec3, Vec3, Vec3) {
    let forward = (look_at - position).normalize_or(Vec3::NEG_Z);
    let mut right = forward.cross(up);
    if right.length_squared() < 1e-12 {
        right = forward.cross(if forward.y.abs() < 0.9 {
            Vec3::Y
        } else {
            Vec3::Z
        });
    }
    let right = right.normalize();
    (forward, right, right.cross(forward))
}

impl Camera {
    pub fn orthographic(
        width: u32,
        height: u32,
        position: Vec3,
        look_at: Vec3,
        up: Vec3,
        view_width: f32,
        view_height: f32,
    ) -> Camera {
        let (forward, right, up) = basis(position, look_at, up);
        Camera::Orthographic {
            width,
            height,
            position,
            forward,
            right,
            up,
            view_width,
            view_height,
        }
    }

    pub fn perspective(
        width: u32,
        height: u32,
        position: Vec3,
        look_at: Vec3,
        up: Vec3,
        vfov_degrees: f32,
    ) -> Camera {
        let (forward, right, up) = basis(position, look_at, up);
        Camera::Perspective {
            width,
            height,
            position,
            forward,
            right,
            up,
            tan_half_v: (0.5 * vfov_degrees).to_radians().tan(),
        }
    }

    pub fn resolution(&self) -> (u32, u32) {
        match *self {
            Camera::Orthographic { width, height, .. }
            | Camera::Perspective { width, height, .. } => (width, height),
        }
    }

    /// Position of the view direction's origin and the viewing axis.
    pub fn position(&self) -> Vec3 {
        match *self {
            Camera::Orthographic { position, .. } | Camera::Perspective { position, .. } => {
                position
            }
        }
    }

    /// Ray through continuous pixel coordinates (x, y).
    pub fn generate_ray(&self, x: f32, y: f32) -> Ray {
        let (w, h) = self.resolution();
        // Screen coordinates in [-1, 1], +y up.
        let sx = 2.0 * x / w as f32 - 1.0;
        let sy = 1.0 - 2.0 * y / h as f32;
        match *self {
            Camera::Orthographic {
                position,
                forward,
                right,
                up,
                view_width,
                view_height,
                ..
            } => Ray::new(
                position + right * (0.5 * view_width * sx) + up * (0.5 * view_height * sy),
                forward,
            ),
            Camera::Perspective {
                position,
                forward,
                right,
                up,
                tan_half_v,
                ..
            } => {
                let aspect = w as f32 / h as f32;
                let d = forward + right * (sx * tan_half_v * aspect) + up * (sy * tan_half_v);
                Ray::new(position, d.normalize())
            }
        }
    }
}
