//! The majorant of a grid density: a coarse grid of blocks of `block`³ samples, each holding the
//! greatest density anywhere in it, walked along a ray by a 3D DDA (Amanatides and Woo 1987).
//! A tracker draws tentative collisions at the block's majorant times the extinction, so its
//! work follows the fog actually crossed: an empty block costs one DDA step, a thin block few
//! tentative points. One block covering the whole grid is the global majorant (the baseline
//! that costs as if the whole box were at its densest).
//!
//! Why the block maximum is a bound: the field is trilinear between sample centres (a convex
//! combination of the 8 samples around a point) and clamped to the outermost centres, so its
//! value anywhere in a block is at most the greatest sample among those within one index of
//! the block's samples.

use std::sync::Arc;

use glam::DVec3;

use crate::medium::density::GridField;

/// Samples per block side when the scene does not say.
pub const DEFAULT_BLOCK: usize = 8;

/// A grid density's majorant grid (see the module's comment).
#[derive(Debug, PartialEq)]
pub struct Majorant {
    grid: Arc<GridField>,
    block: usize,
    dims: [usize; 3],
    /// Per block (x fastest), the greatest density in it.
    max: Vec<f32>,
}

impl Majorant {
    /// Blocks of `block`³ samples over `grid`; `None` for one block holding the global maximum.
    pub fn new(grid: Arc<GridField>, block: Option<usize>) -> Self {
        let (res, values) = grid.samples();
        let block = block
            .unwrap_or_else(|| res.iter().copied().max().unwrap_or(1))
            .max(1);
        let dims = res.map(|n| n.div_ceil(block).max(1));
        let mut max = vec![0.0f32; dims[0] * dims[1] * dims[2]];
        // Samples that reach into block b along an axis: [b B - 1, (b + 1) B], clamped.
        let reach =
            |b: usize, n: usize| (b * block).saturating_sub(1)..((b + 1) * block + 1).min(n);
        for bz in 0..dims[2] {
            for by in 0..dims[1] {
                for bx in 0..dims[0] {
                    let mut m = 0.0f32;
                    for z in reach(bz, res[2]) {
                        for y in reach(by, res[1]) {
                            let row = (z * res[1] + y) * res[0];
                            for x in reach(bx, res[0]) {
                                m = m.max(values[row + x]);
                            }
                        }
                    }
                    max[(bz * dims[1] + by) * dims[0] + bx] = m;
                }
            }
        }
        Self {
            grid,
            block,
            dims,
            max,
        }
    }

    /// The field the majorant bounds.
    pub fn grid(&self) -> &GridField {
        &self.grid
    }

    /// Number of blocks.
    pub fn blocks(&self) -> usize {
        self.max.len()
    }

    /// Bytes the majorant keeps.
    pub fn bytes(&self) -> usize {
        std::mem::size_of_val(self.max.as_slice())
    }

    /// Calls `f(t_in, t_out, majorant)` for each block the index-space ray `a + b t` crosses
    /// over `[from, to]`, in order, until `f` returns false. Nothing outside the grid's box.
    pub fn segments(
        &self,
        (a, b): (DVec3, DVec3),
        from: f64,
        to: f64,
        mut f: impl FnMut(f64, f64, f32) -> bool,
    ) {
        let Some((t0, t1)) = self.grid.box_interval(a, b) else {
            return;
        };
        let (mut t, end) = (t0.max(from), t1.min(to));
        if t >= end || t.is_nan() || end.is_nan() {
            return;
        }
        let bs = self.block as f64;
        // Block coordinates: index-space q maps to (q + 0.5) / B.
        let p = (a + b * t + 0.5) / bs;
        let mut cell = [0usize; 3];
        let mut next = [f64::INFINITY; 3];
        let mut delta = [f64::INFINITY; 3];
        let mut step = [0isize; 3];
        for k in 0..3 {
            let c = (p[k].floor().max(0.0) as usize).min(self.dims[k] - 1);
            cell[k] = c;
            if b[k] > 0.0 {
                step[k] = 1;
                next[k] = (((c + 1) as f64) * bs - 0.5 - a[k]) / b[k];
                delta[k] = bs / b[k];
            } else if b[k] < 0.0 {
                step[k] = -1;
                next[k] = ((c as f64) * bs - 0.5 - a[k]) / b[k];
                delta[k] = -bs / b[k];
            }
        }
        loop {
            let k = if next[0] <= next[1] && next[0] <= next[2] {
                0
            } else if next[1] <= next[2] {
                1
            } else {
                2
            };
            let out = next[k].min(end);
            let m = self.max[(cell[2] * self.dims[1] + cell[1]) * self.dims[0] + cell[0]];
            if out > t && !f(t, out, m) {
                return;
            }
            if out >= end {
                return;
            }
            t = out;
            let c = cell[k] as isize + step[k];
            if c < 0 || c >= self.dims[k] as isize {
                return;
            }
            cell[k] = c as usize;
            next[k] += delta[k];
        }
    }
}
