//! Watertight ray-triangle intersection (Woop, Benthin and Wald 2013): rays through a shared edge
//! or vertex hit at least one of the triangles, so closed meshes cannot leak a path (and with it
//! the medium bookkeeping).

use glam::Vec3A;

#[derive(Clone, Copy, Debug)]
pub(crate) struct TriGeom {
    pub v: [Vec3A; 3],
}

impl TriGeom {
    pub const INVALID: TriGeom = TriGeom {
        v: [Vec3A::splat(f32::NAN); 3],
    };

    pub fn is_valid(&self) -> bool {
        !self.v[0].x.is_nan()
    }

    /// Unnormalised geometric normal (outward by winding).
    pub fn normal(&self) -> Vec3A {
        (self.v[1] - self.v[0]).cross(self.v[2] - self.v[0])
    }
}

/// Per-ray constants of the watertight test: the shear that maps the ray onto +z, as three rows
/// (dot products instead of per-triangle dynamic axis indexing; every vertex is still mapped by
/// the same deterministic arithmetic, which is all watertightness needs).
#[derive(Clone, Copy, Debug)]
pub(crate) struct ShearedRay {
    o: Vec3A,
    rx: Vec3A,
    ry: Vec3A,
    rz: Vec3A,
}

impl ShearedRay {
    #[inline(always)]
    pub fn new(o: Vec3A, d: Vec3A) -> ShearedRay {
        let a = d.abs();
        let kz = if a.x > a.y {
            if a.x > a.z { 0 } else { 2 }
        } else if a.y > a.z {
            1
        } else {
            2
        };
        let mut kx = (kz + 1) % 3;
        let mut ky = (kx + 1) % 3;
        if d[kz] < 0.0 {
            std::mem::swap(&mut kx, &mut ky); // keep the winding
        }
        let sz = 1.0 / d[kz];
        let unit = |k: usize| Vec3A::AXES[k];
        ShearedRay {
            o,
            rx: unit(kx) - unit(kz) * (d[kx] * sz),
            ry: unit(ky) - unit(kz) * (d[ky] * sz),
            rz: unit(kz) * sz,
        }
    }

    /// (t, b0, b1, b2) with t infinite on a miss or outside `(0, t_max)`.
    #[inline(always)]
    pub fn hit(&self, tri: &TriGeom, t_max: f32) -> (f32, f32, f32, f32) {
        const MISS: (f32, f32, f32, f32) = (f32::INFINITY, 0.0, 0.0, 0.0);
        let a = tri.v[0] - self.o;
        let b = tri.v[1] - self.o;
        let c = tri.v[2] - self.o;
        let (ax, ay) = (a.dot(self.rx), a.dot(self.ry));
        let (bx, by) = (b.dot(self.rx), b.dot(self.ry));
        let (cx, cy) = (c.dot(self.rx), c.dot(self.ry));
        let mut u = cx * by - cy * bx;
        let mut v = ax * cy - ay * cx;
        let mut w = bx * ay - by * ax;
        if u == 0.0 || v == 0.0 || w == 0.0 {
            // Exactly on an edge in single precision: decide the sign in double precision.
            let (ax, ay, bx, by, cx, cy) = (
                ax as f64, ay as f64, bx as f64, by as f64, cx as f64, cy as f64,
            );
            u = (cx * by - cy * bx) as f32;
            v = (ax * cy - ay * cx) as f32;
            w = (bx * ay - by * ax) as f32;
        }
        if (u < 0.0 || v < 0.0 || w < 0.0) && (u > 0.0 || v > 0.0 || w > 0.0) {
            return MISS;
        }
        let det = u + v + w;
        if det == 0.0 || det.is_nan() {
            return MISS;
        }
        let t_scaled = u * a.dot(self.rz) + v * b.dot(self.rz) + w * c.dot(self.rz);
        let inv = 1.0 / det;
        let t = t_scaled * inv;
        if t > 0.0 && t < t_max {
            (t, u * inv, v * inv, w * inv)
        } else {
            MISS
        }
    }
}
