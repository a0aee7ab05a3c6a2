//! The directional light's beam: uniform over the silhouette of an axis-aligned box.
//!
//! Seen along a direction d, a box's silhouette is tiled without overlap by the (up to) three
//! faces that face the light, face i covering |d_i| times its own area. Picking a face in
//! proportion to that projected area and a uniform point on it is therefore uniform over the
//! silhouette, and every ray enters the box.

use glam::{Vec2, Vec3};

pub struct Beam {
    min: Vec3,
    extent: Vec3,
    direction: Vec3,
    /// Projected area of the faces facing the light, per axis.
    face: [f32; 3],
    /// Silhouette area (m^2): the beam's flux is irradiance times this.
    pub area: f32,
    /// How far behind its entry face a ray starts, so that it starts outside the box.
    back: f32,
}

impl Beam {
    pub fn empty() -> Self {
        Self {
            min: Vec3::ZERO,
            extent: Vec3::ZERO,
            direction: Vec3::NEG_Z,
            face: [0.0; 3],
            area: 0.0,
            back: 0.0,
        }
    }

    /// The beam over the box `[min, max]` along the unit vector `direction`.
    pub fn new(min: Vec3, max: Vec3, direction: Vec3) -> Self {
        let e = (max - min).max(Vec3::ZERO);
        let d = direction.abs();
        let face = [d.x * e.y * e.z, d.y * e.x * e.z, d.z * e.x * e.y];
        let area = face.iter().sum::<f32>();
        if !(area > 0.0 && area.is_finite()) {
            return Self::empty();
        }
        Self {
            min,
            extent: e,
            direction,
            face,
            area,
            back: 0.01 * e.length().max(1e-6),
        }
    }

    /// A ray origin from two uniforms on the face and one for the face choice.
    pub fn sample(&self, u: Vec2, u_face: f32) -> Vec3 {
        let pick = u_face * self.area;
        let axis = if pick < self.face[0] {
            0
        } else if pick < self.face[0] + self.face[1] || self.face[2] == 0.0 {
            1
        } else {
            2
        };
        let (j, k) = ((axis + 1) % 3, (axis + 2) % 3);
        let mut p = self.min;
        // The light enters through the face its direction points away from.
        if self.direction[axis] < 0.0 {
            p[axis] += self.extent[axis];
        }
        p[j] += u.x * self.extent[j];
        p[k] += u.y * self.extent[k];
        p - self.direction * self.back
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A unit cube seen along a diagonal-ish direction: the projected area is the sum of
    /// |d_i| (one per visible face), and every sampled ray meets the cube from outside.
    #[test]
    fn cube_silhouette_area_and_entry() {
        let d = Vec3::new(0.5, -0.5, -std::f32::consts::FRAC_1_SQRT_2).normalize();
        let b = Beam::new(Vec3::splat(-0.5), Vec3::splat(0.5), d);
        let expect = d.x.abs() + d.y.abs() + d.z.abs();
        assert!((b.area - expect).abs() < 1e-6);
        for i in 0..1000 {
            let u = Vec2::new((i as f32 * 0.618).fract(), (i as f32 * 0.414).fract());
            let o = b.sample(u, (i as f32 * 0.7317).fract());
            // Outside the cube, and the ray o + t d enters it.
            assert!(o.abs().max_element() > 0.5);
            let inv = d.recip();
            let t0 = (Vec3::splat(-0.5) - o) * inv;
            let t1 = (Vec3::splat(0.5) - o) * inv;
            let (near, far) = (t0.min(t1).max_element(), t0.max(t1).min_element());
            assert!(near >= 0.0 && far >= near - 1e-5, "{o} misses");
        }
    }

    #[test]
    fn flat_box_edge_on_has_no_beam() {
        let b = Beam::new(Vec3::new(0.0, 0.0, 0.0), Vec3::new(1.0, 1.0, 0.0), Vec3::X);
        assert_eq!(b.area, 0.0);
    }
}
