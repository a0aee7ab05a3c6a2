use glam::Vec3;

/// A ray with unit direction `d`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ray {
    pub o: Vec3,
    pub d: Vec3,
}

impl Ray {
    pub fn new(o: Vec3, d: Vec3) -> Ray {
        Ray { o, d }
    }

    pub fn at(&self, t: f32) -> Vec3 {
        self.o + self.d * t
    }
}

/// Axis-aligned bounding box.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aabb {
    pub min: Vec3,
    pub max: Vec3,
}

impl Aabb {
    pub const EMPTY: Aabb = Aabb {
        min: Vec3::splat(f32::INFINITY),
        max: Vec3::splat(f32::NEG_INFINITY),
    };

    pub fn grow(&mut self, p: Vec3) {
        self.min = self.min.min(p);
        self.max = self.max.max(p);
    }

    pub fn union(&self, o: &Aabb) -> Aabb {
        Aabb {
            min: self.min.min(o.min),
            max: self.max.max(o.max),
        }
    }

    pub fn is_empty(&self) -> bool {
        self.min.cmpgt(self.max).any()
    }

    pub fn centre(&self) -> Vec3 {
        0.5 * (self.min + self.max)
    }

    pub fn diagonal(&self) -> Vec3 {
        self.max - self.min
    }

    pub fn contains(&self, p: Vec3) -> bool {
        p.cmpge(self.min).all() && p.cmple(self.max).all()
    }
}

/// Relative size of the origin offset: float rounding of hit points grows with their magnitude,
/// so the offset scales with the largest coordinate (plus an absolute floor near the origin).
const SPAWN_REL: f32 = 2e-5;
const SPAWN_ABS: f32 = 1e-5;

/// How far [`spawn`] moves a ray's origin off the surface at `p`: a surface nearer than this
/// behind the one just crossed is skipped by the spawned ray.
pub(crate) fn spawn_offset(p: Vec3) -> f32 {
    SPAWN_ABS + SPAWN_REL * p.abs().max_element()
}

/// A ray leaving surface point `p` in direction `dir`, with the origin pushed along the geometric
/// normal to the side `dir` goes to. Offsetting along `ng` (not along `dir`) keeps grazing rays on
/// the correct side of the surface, which is what keeps medium bookkeeping right at silhouettes.
pub fn spawn(p: Vec3, ng: Vec3, dir: Vec3) -> Ray {
    let eps = spawn_offset(p);
    let side = if dir.dot(ng) >= 0.0 { 1.0 } else { -1.0 };
    Ray {
        o: p + ng * (eps * side),
        d: dir,
    }
}

/// The rank of a null boundary hit at `t` (infinite: no hit): `t` plus the offset [`super::spawn`]
/// would move the ray's origin there, kept below `t_max`. Crossing a null boundary spawns the
/// ray that far beyond it, so a surface with a material closer than that behind it (a floor
/// coplanar with a fog box's bottom face) would be skipped and light would leak through it;
/// ranked this way the surface is met first, the ray stays in the medium it was in (the
/// boundary's other side starts beyond the surface) and scatters or stops there.
pub(crate) fn null_rank(ray: &Ray, t: f32, t_max: f32) -> f32 {
    if t < t_max {
        (t + spawn_offset(ray.at(t))).min(t_max.next_down()).max(t)
    } else {
        t
    }
}
