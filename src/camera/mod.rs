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

    /// The view frame: position, forward, right and up (unit, orthogonal).
    fn frame(&self) -> (Vec3, Vec3, Vec3, Vec3) {
        match *self {
            Camera::Orthographic {
                position,
                forward,
                right,
                up,
                ..
            }
            | Camera::Perspective {
                position,
                forward,
                right,
                up,
                ..
            } => (position, forward, right, up),
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

    /// Where the camera sees point `p`, for light tracing (splatting a point's radiance towards
    /// the camera into a pixel): None when `p` is behind the camera or outside the image.
    ///
    /// A pixel is the mean radiance over its rectangle on the image plane (box filter, as
    /// `generate_ray`'s uniform pixel samples make it). For a perspective camera with the plane
    /// at distance 1 from the pinhole, a plane element `du` at angle `theta_c` from the axis
    /// subtends `dw = cos^3(theta_c) du`, and a surface element `dA` at distance `d` whose normal
    /// makes `theta_x` with the direction to the pinhole subtends `dw = cos(theta_x) dA / d^2`;
    /// so a pixel of plane area `A` measures `(1/A) * integral L cos(theta_x) / (d^2 cos^3
    /// theta_c) dA` over the surface it sees, and `importance` is everything but `L
    /// cos(theta_x) dA`. An orthographic pixel of `A` square metres measures `(1/A) * integral
    /// L cos(theta_x) dA`.
    pub fn project(&self, p: Vec3) -> Option<Projection> {
        let (w, h) = self.resolution();
        let (wf, hf) = (w as f32, h as f32);
        let (position, forward, right, up) = self.frame();
        let d = p - position;
        let z = d.dot(forward);
        if z.is_nan() || z <= 0.0 {
            return None;
        }
        let (sx, sy, to_camera, dist, importance) = match *self {
            Camera::Orthographic {
                view_width,
                view_height,
                ..
            } => {
                let area = (view_width / wf) * (view_height / hf);
                let sx = d.dot(right) / (0.5 * view_width);
                let sy = d.dot(up) / (0.5 * view_height);
                (sx, sy, -forward, z, 1.0 / area)
            }
            Camera::Perspective { tan_half_v, .. } => {
                let dist = d.length();
                let aspect = wf / hf;
                let sx = d.dot(right) / (z * tan_half_v * aspect);
                let sy = d.dot(up) / (z * tan_half_v);
                let area = (2.0 * tan_half_v * aspect / wf) * (2.0 * tan_half_v / hf);
                let cos = z / dist;
                let importance = 1.0 / (area * cos * cos * cos * dist * dist);
                (sx, sy, -d / dist, dist, importance)
            }
        };
        let x = 0.5 * (sx + 1.0) * wf;
        let y = 0.5 * (1.0 - sy) * hf;
        let inside = (0.0..wf).contains(&x) && (0.0..hf).contains(&y);
        (inside && importance.is_finite()).then(|| Projection {
            pixel: (y as u32).min(h - 1) * w + (x as u32).min(w - 1),
            to_camera,
            dist,
            importance,
        })
    }
}

/// Where the camera sees a point ([`Camera::project`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Projection {
    /// Row-major pixel index (`y * width + x`).
    pub pixel: u32,
    /// Unit direction from the point towards the camera (its pinhole, or against the view
    /// direction of an orthographic camera).
    pub to_camera: Vec3,
    /// Distance to the pinhole, or to the orthographic camera's plane along the view direction.
    pub dist: f32,
    /// The pixel's importance: radiance leaving the point times `cos(theta_x) dA` times this
    /// is the pixel value it adds (see [`Camera::project`]).
    pub importance: f32,
}
