//! Unit vectors in 32 bits (octahedral map, 16 bits per coordinate): surface gather records
//! keep their normal and outgoing direction this way. The error is below 1e-4 rad, far below
//! anything a diffuse estimator resolves.

use glam::{Vec2, Vec3};

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Oct(u32);

fn sign_not_zero(v: Vec2) -> Vec2 {
    Vec2::new(
        if v.x >= 0.0 { 1.0 } else { -1.0 },
        if v.y >= 0.0 { 1.0 } else { -1.0 },
    )
}

fn quantise(x: f32) -> u32 {
    ((x.clamp(-1.0, 1.0) * 0.5 + 0.5) * 65535.0).round() as u32
}

impl Oct {
    /// A placeholder for an absent direction (it decodes to some unit vector).
    pub const ZERO: Oct = Oct(0);

    /// Encodes a unit vector (any non-zero vector is normalised by the projection).
    pub fn encode(v: Vec3) -> Self {
        let l1 = v.x.abs() + v.y.abs() + v.z.abs();
        let mut p = Vec2::new(v.x, v.y) / l1;
        if v.z < 0.0 {
            p = (Vec2::ONE - Vec2::new(p.y.abs(), p.x.abs())) * sign_not_zero(p);
        }
        Self(quantise(p.x) | (quantise(p.y) << 16))
    }

    #[inline]
    pub fn decode(self) -> Vec3 {
        let f = |b: u32| (b & 0xffff) as f32 * (2.0 / 65535.0) - 1.0;
        let p = Vec2::new(f(self.0), f(self.0 >> 16));
        let z = 1.0 - p.x.abs() - p.y.abs();
        let t = (-z).max(0.0);
        let x = p.x + if p.x >= 0.0 { -t } else { t };
        let y = p.y + if p.y >= 0.0 { -t } else { t };
        Vec3::new(x, y, z).normalize()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};

    #[test]
    fn round_trip_error_is_below_1e_4_rad() {
        let mut rng = rand_pcg::Pcg64Mcg::seed_from_u64(3);
        let axes = [
            Vec3::X,
            Vec3::NEG_X,
            Vec3::Y,
            Vec3::NEG_Y,
            Vec3::Z,
            Vec3::NEG_Z,
        ];
        let random = (0..20_000).map(|_| {
            let v = Vec3::new(rng.random(), rng.random(), rng.random()) * 2.0 - Vec3::ONE;
            v.normalize()
        });
        for v in axes.into_iter().chain(random) {
            let d = Oct::encode(v).decode();
            let angle = v.cross(d).length().asin();
            assert!(angle < 1e-4, "{v} -> {d}: {angle} rad");
        }
    }
}
