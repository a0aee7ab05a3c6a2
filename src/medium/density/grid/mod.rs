//! A density given by samples on a grid (a Mitsuba `.vol` or an OpenVDB file), placed in the
//! world by a transform of its unit box or by the box the file gives.
//!
//! The field (data.rs gives the sample convention, Mitsuba 3's `gridvolume`): trilinear between
//! sample centres, clamped in the outer half cells, zero outside the box. Along a ray it is a
//! polynomial of degree at most 3 in the distance between two crossings of the planes through
//! sample centres (a product of three functions linear in the distance), so its integral is
//! exact piece by piece: `ray.rs` fits each piece's cubic from four values and integrates it
//! in closed form. That keeps the change of variable `u = D(s)` of the closed-form fields
//! exact here too, at the cost of visiting every cell with smoke a ray crosses (docs/media.md):
//! `crossings.rs` gives the crossings in order, `occupancy.rs` lets a ray cross a block of 8³
//! cells with no smoke in one step, and a flight builds its ray only as far as it reaches.

mod crossings;
pub mod data;
mod occupancy;
mod ray;
pub mod vdb;
pub mod vol;

use glam::{DVec3, Mat4, Vec3};

use crossings::Crossings;
pub use data::{GridData, GridFileError};
use occupancy::Occupancy;
pub use ray::GridRay;

/// A grid placed in the world.
#[derive(Debug, PartialEq)]
pub struct GridField {
    res: [usize; 3],
    values: Vec<f32>,
    /// World to index space, where sample `(i, j, k)` sits at `(i, j, k)` and the box spans
    /// `[-0.5, n - 0.5]` per axis.
    to_index: Mat4,
    /// The box's world bounds (of its eight corners).
    bounds: (Vec3, Vec3),
    /// The blocks with no smoke, crossed in one step.
    occupancy: Occupancy,
    /// Least and greatest sample.
    min: f32,
    max: f32,
    /// Where it came from, for `brume info`.
    source: String,
}

/// Why samples cannot make a field.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum GridValueError {
    #[error("sample ({i}, {j}, {k}) is {value}: densities are finite and >= 0")]
    Bad {
        i: usize,
        j: usize,
        k: usize,
        value: f32,
    },
    #[error("every sample is 0: the medium would be empty")]
    Empty,
    #[error("the grid's box is degenerate (a zero scale or no file bounds)")]
    Placement,
}

impl GridField {
    /// The field of `data` times `multiplier`, its unit box mapped to the world by `unit_to_world`
    /// (or, when None, filling the box the file gives).
    pub fn new(
        data: GridData,
        multiplier: f32,
        unit_to_world: Option<Mat4>,
        source: String,
    ) -> Result<Self, GridValueError> {
        let [nx, ny, _] = data.res;
        let mut values = data.values;
        let (mut min, mut max) = (f32::INFINITY, 0.0f32);
        for (n, v) in values.iter_mut().enumerate() {
            if !(v.is_finite() && *v >= 0.0) {
                let (i, j, k) = (n % nx, (n / nx) % ny, n / (nx * ny));
                return Err(GridValueError::Bad { i, j, k, value: *v });
            }
            *v *= multiplier;
            (min, max) = (min.min(*v), max.max(*v));
        }
        if !(max > 0.0 && max.is_finite()) {
            return Err(GridValueError::Empty);
        }
        let unit = match (unit_to_world, data.bounds) {
            (Some(m), _) => m,
            (None, Some((lo, hi))) => Mat4::from_translation(lo) * Mat4::from_scale(hi - lo),
            (None, None) => return Err(GridValueError::Placement),
        };
        let res = Vec3::new(nx as f32, ny as f32, data.res[2] as f32);
        let to_index =
            Mat4::from_translation(Vec3::splat(-0.5)) * Mat4::from_scale(res) * unit.inverse();
        if !(to_index.is_finite() && unit.determinant().abs() > 1e-30) {
            return Err(GridValueError::Placement);
        }
        let corners = (0..8).map(|c| {
            let u = Vec3::new((c & 1) as f32, ((c >> 1) & 1) as f32, ((c >> 2) & 1) as f32);
            unit.transform_point3(u)
        });
        let bounds = corners.fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(a, b), p| {
            (a.min(p), b.max(p))
        });
        Ok(Self {
            occupancy: Occupancy::new(data.res, &values),
            res: data.res,
            values,
            to_index,
            bounds,
            min,
            max,
            source,
        })
    }

    /// The field in words, for `brume info`.
    pub fn describe(&self) -> String {
        let [x, y, z] = self.res;
        format!(
            "grid {x} x {y} x {z} from {}, box {} to {}, samples {} to {}",
            self.source, self.bounds.0, self.bounds.1, self.min, self.max
        )
    }

    /// Bytes of samples.
    pub fn bytes(&self) -> usize {
        std::mem::size_of_val(self.values.as_slice())
    }

    /// Least and greatest density over the world box `[lo, hi]` (samples' range; 0 when the
    /// box reaches outside the grid's).
    pub fn range(&self, lo: Vec3, hi: Vec3) -> (f32, f32) {
        let (a, b) = self.bounds;
        let outside = lo.cmplt(a).any() || hi.cmpgt(b).any();
        (if outside { 0.0 } else { self.min }, self.max)
    }

    /// The density at world point `p`.
    pub fn at(&self, p: Vec3) -> f32 {
        let q = self.to_index.transform_point3(p).as_dvec3();
        let n = self.extent();
        if q.cmplt(DVec3::splat(-0.5)).any() || q.cmpgt(n - 0.5).any() {
            return 0.0;
        }
        self.at_index(q) as f32
    }

    /// The ray `o + d s` in index space: `(a, b)` with the point at distance `s` at `a + b s`.
    fn index_ray(&self, o: Vec3, d: Vec3) -> (DVec3, DVec3) {
        let a = self.to_index.transform_point3(o).as_dvec3();
        // In f64 from the matrix's columns: `b` scales the distance.
        let b = self.to_index.transform_vector3(d).as_dvec3();
        (a, b)
    }

    fn extent(&self) -> DVec3 {
        DVec3::new(self.res[0] as f64, self.res[1] as f64, self.res[2] as f64)
    }

    /// The cell of index-space point `q` along each axis: lower and upper sample and the
    /// fraction between them (clamped to the outermost sample centres).
    fn cell(&self, q: DVec3) -> [(usize, usize, f64); 3] {
        let axis = |x: f64, n: usize| -> (usize, usize, f64) {
            let x = x.clamp(0.0, (n - 1) as f64);
            // `x >= 0`: the cast truncates, which is the floor (and much cheaper than a call).
            let i = (x as usize).min(n.saturating_sub(2));
            let j = (i + 1).min(n - 1);
            (i, j, x - i as f64)
        };
        [
            axis(q.x, self.res[0]),
            axis(q.y, self.res[1]),
            axis(q.z, self.res[2]),
        ]
    }

    /// Whether the 8 samples around index-space point `q` are all 0 (the density is then 0 in
    /// the whole cell, where a ray's piece needs no fitting).
    fn empty_at(&self, q: DVec3) -> bool {
        let [nx, ny, _] = self.res;
        let [(x0, x1, _), (y0, y1, _), (z0, z1, _)] = self.cell(q);
        [z0, z1].iter().all(|&z| {
            [y0, y1].iter().all(|&y| {
                let row = (z * ny + y) * nx;
                self.values[row + x0] == 0.0 && self.values[row + x1] == 0.0
            })
        })
    }

    /// The end of the piece of the index-space ray `a + b t` that starts at crossing `t`, whose
    /// next crossing is `next` (taken from `cross`), and whether the density is 0 over it: a
    /// piece in a block with no smoke runs to where the ray leaves the block (the crossings in
    /// between are skipped), any other piece ends at `next`. `occupied` is the distance to
    /// which the ray is known to be in a block with smoke (none is looked up before it).
    fn piece_end(
        &self,
        (cross, occupied): (&mut Crossings, &mut f64),
        (a, b): (DVec3, DVec3),
        t: f64,
        next: f64,
    ) -> (f64, bool) {
        if next <= *occupied {
            return (next, false);
        }
        let (empty, exit) = self.occupancy.block_of(a + b * (0.5 * (t + next)), a, b);
        if !empty {
            *occupied = exit;
            return (next, false);
        }
        if exit > next {
            cross.skip_to(exit);
            return (cross.next().unwrap_or(next), true);
        }
        (next, true)
    }

    /// Trilinear value at index-space point `q`, clamped to the outermost sample centres (the
    /// caller decides whether `q` is in the box).
    fn at_index(&self, q: DVec3) -> f64 {
        let [nx, ny, _] = self.res;
        let [(x0, x1, fx), (y0, y1, fy), (z0, z1, fz)] = self.cell(q);
        let v = |x: usize, y: usize, z: usize| self.values[(z * ny + y) * nx + x] as f64;
        let lerp = |a: f64, b: f64, t: f64| a + (b - a) * t;
        let y0z0 = lerp(v(x0, y0, z0), v(x1, y0, z0), fx);
        let y1z0 = lerp(v(x0, y1, z0), v(x1, y1, z0), fx);
        let y0z1 = lerp(v(x0, y0, z1), v(x1, y0, z1), fx);
        let y1z1 = lerp(v(x0, y1, z1), v(x1, y1, z1), fx);
        lerp(lerp(y0z0, y1z0, fy), lerp(y0z1, y1z1, fy), fz)
    }

    /// The crossings of the index-space ray `a + b t` with the planes through sample centres,
    /// from where it enters the box to where it leaves: consecutive ones bound the pieces on
    /// which the density is one cubic. None when the ray misses the box.
    fn crossings(&self, a: DVec3, b: DVec3) -> Option<Crossings> {
        let span = self.box_interval(a, b)?;
        Some(Crossings::new(a, b, span, self.extent()))
    }

    /// The distances `[t0, t1]` (`t0 >= 0`) over which the index-space ray `a + b t` is inside
    /// the box, or None when it misses it.
    pub(crate) fn box_interval(&self, a: DVec3, b: DVec3) -> Option<(f64, f64)> {
        let n = self.extent();
        let (mut t0, mut t1) = (0.0f64, f64::INFINITY);
        for k in 0..3 {
            if b[k] == 0.0 {
                if a[k] < -0.5 || a[k] > n[k] - 0.5 {
                    return None;
                }
                continue;
            }
            let (lo, hi) = ((-0.5 - a[k]) / b[k], (n[k] - 0.5 - a[k]) / b[k]);
            t0 = t0.max(lo.min(hi));
            t1 = t1.min(lo.max(hi));
        }
        (t0 < t1 && !t0.is_nan() && !t1.is_nan()).then_some((t0, t1))
    }

    /// The ray `o + d s` in index space (see `index_ray`), for the majorant grid's traversal.
    pub(crate) fn ray_in_index(&self, o: Vec3, d: Vec3) -> (DVec3, DVec3) {
        self.index_ray(o, d)
    }

    /// Samples per axis and the samples themselves (x fastest), for the majorant grid.
    pub(crate) fn samples(&self) -> ([usize; 3], &[f32]) {
        (self.res, &self.values)
    }

    /// The density at index-space point `q`, 0 outside the box.
    pub(crate) fn at_index_in_box(&self, q: DVec3) -> f64 {
        let n = self.extent();
        if q.cmplt(DVec3::splat(-0.5)).any() || q.cmpgt(n - 0.5).any() {
            return 0.0;
        }
        self.at_index(q)
    }

    /// The change of variable along the ray `o + d s` (`d` unit).
    pub fn along(&self, o: Vec3, d: Vec3) -> GridRay {
        GridRay::new(self, o, d)
    }

    /// The change of variable along the ray as far as `(s_max, u_max)` reaches
    /// (`GridRay::until`).
    pub fn along_until(&self, o: Vec3, d: Vec3, reach: (f32, f32)) -> GridRay {
        GridRay::until(self, o, d, reach)
    }

    /// `∫_0^s rho` along the ray `o + d s`, without keeping the pieces.
    pub fn depth(&self, o: Vec3, d: Vec3, s: f32) -> f32 {
        let (a, b) = self.index_ray(o, d);
        let s = s as f64;
        let Some(mut cross) = self.crossings(a, b) else {
            return 0.0;
        };
        // Two-point Gauss-Legendre is exact for the cubic of each piece.
        let g = 0.5 / 3f64.sqrt();
        let mut total = 0.0;
        let (mut ta, mut occupied) = (cross.first(), f64::NEG_INFINITY);
        while let Some(next) = cross.next() {
            let (end, empty) = self.piece_end((&mut cross, &mut occupied), (a, b), ta, next);
            if !empty {
                let tb = end.min(s);
                if tb <= ta {
                    break;
                }
                let (m, h) = (0.5 * (ta + tb), tb - ta);
                let f = |t: f64| self.at_index(a + b * t);
                total += 0.5 * h * (f(m - g * h) + f(m + g * h));
            } else if end >= s {
                break;
            }
            ta = end;
        }
        total as f32
    }
}

#[cfg(test)]
mod tests;
