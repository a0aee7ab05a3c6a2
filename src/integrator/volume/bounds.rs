use glam::Vec3;

/// Axis-aligned box for building a BVH over gather volumes (convert to the BVH crate's type at
/// the call site).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aabb {
    /// Lower corner.
    pub min: Vec3,
    /// Upper corner.
    pub max: Vec3,
}

/// Box of the sphere of centre `c`, radius `r`.
pub fn sphere_aabb(c: Vec3, r: f32) -> Aabb {
    Aabb {
        min: c - Vec3::splat(r),
        max: c + Vec3::splat(r),
    }
}

/// Box of the capsule (all points within `r` of segment `[a, b]`); also a valid, looser box for
/// a flat-capped cylinder.
pub fn capsule_aabb(a: Vec3, b: Vec3, r: f32) -> Aabb {
    Aabb {
        min: a.min(b) - Vec3::splat(r),
        max: a.max(b) + Vec3::splat(r),
    }
}

/// Tight box of the flat-capped cylinder of radius `r` around `[a, a + u len]` (`u` unit): a cap
/// disc extends `r sqrt(1 - u_i^2)` along axis i.
pub fn cylinder_aabb(a: Vec3, u: Vec3, len: f32, r: f32) -> Aabb {
    let b = a + u * len;
    let e = (Vec3::ONE - u * u).max(Vec3::ZERO).powf(0.5) * r;
    Aabb {
        min: a.min(b) - e,
        max: a.max(b) + e,
    }
}

/// Box of a forward segment `[o, o + v len]`.
pub fn segment_aabb(o: Vec3, v: Vec3, len: f32) -> Aabb {
    let b = o + v * len;
    Aabb {
        min: o.min(b),
        max: o.max(b),
    }
}
