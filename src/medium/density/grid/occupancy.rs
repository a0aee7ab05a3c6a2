//! Which blocks of a grid hold no smoke, so that a ray crosses an empty block in one step
//! instead of visiting each of its cells (a thin layer or a plume leaves most of its box empty:
//! issue 27's "cost in proportion to where the fog is").
//!
//! Block `I` along an axis covers the index-space interval between sample planes `B I` and
//! `B (I + 1)` (the first block reaching down to the box's face at `-0.5`, the last up to `n -
//! 0.5`); the trilinear density there depends on samples `B I ..= B (I + 1)` only (the outer
//! half cells are clamped to the outermost samples), so a block whose samples are all 0 has
//! density 0 everywhere in it.

use glam::DVec3;

/// Cells per block along each axis.
const B: usize = 8;

#[derive(Clone, Debug, PartialEq)]
pub(super) struct Occupancy {
    /// Samples per axis of the grid.
    n: [usize; 3],
    /// Blocks per axis.
    blocks: [usize; 3],
    /// True where a block's samples are all 0 (x fastest).
    empty: Vec<bool>,
}

impl Occupancy {
    /// The empty blocks of the samples `values` (`n` per axis, x fastest).
    pub(super) fn new(n: [usize; 3], values: &[f32]) -> Self {
        let blocks = n.map(|m| (m.saturating_sub(1)).div_ceil(B).max(1));
        let mut empty = vec![true; blocks[0] * blocks[1] * blocks[2]];
        for z in 0..n[2] {
            for y in 0..n[1] {
                let row = (z * n[1] + y) * n[0];
                for x in 0..n[0] {
                    if values[row + x] == 0.0 {
                        continue;
                    }
                    // A sample on a block boundary belongs to both blocks.
                    for bz in owners(z, blocks[2]) {
                        for by in owners(y, blocks[1]) {
                            for bx in owners(x, blocks[0]) {
                                empty[(bz * blocks[1] + by) * blocks[0] + bx] = false;
                            }
                        }
                    }
                }
            }
        }
        Self { n, blocks, empty }
    }

    /// The block of index-space point `q` along each axis.
    fn block(&self, q: DVec3) -> [usize; 3] {
        let at = |k: usize| {
            let x = q[k].clamp(0.0, (self.n[k].max(1) - 1) as f64);
            // `x >= 0`: the cast is the floor.
            ((x / B as f64) as usize).min(self.blocks[k] - 1)
        };
        [at(0), at(1), at(2)]
    }

    /// Whether the block of `q` (a point of the index-space ray `a + b t`) is empty, and the
    /// distance at which the ray leaves it (a crossing of a sample plane, computed as
    /// `Crossings` computes it, or `+inf` where the block reaches the box's far side).
    pub(super) fn block_of(&self, q: DVec3, a: DVec3, b: DVec3) -> (bool, f64) {
        let [i, j, k] = self.block(q);
        let empty = self.empty[(k * self.blocks[1] + j) * self.blocks[0] + i];
        let mut exit = f64::INFINITY;
        for (axis, blk) in [(0, i), (1, j), (2, k)] {
            let bound = if b[axis] > 0.0 && blk + 1 < self.blocks[axis] {
                ((blk + 1) * B) as f64
            } else if b[axis] < 0.0 && blk > 0 {
                (blk * B) as f64
            } else {
                continue;
            };
            exit = exit.min((bound - a[axis]) / b[axis]);
        }
        (empty, exit)
    }
}

/// The blocks (out of `count`) whose samples include sample `i`.
fn owners(i: usize, count: usize) -> impl Iterator<Item = usize> {
    let hi = (i / B).min(count - 1);
    let lo = if i.is_multiple_of(B) && i > 0 {
        i / B - 1
    } else {
        hi
    };
    lo..=hi
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every point of an empty block has density 0, checked by brute force on a grid with one
    /// nonzero sample: the blocks that own it are occupied, all others empty.
    #[test]
    fn a_sample_occupies_exactly_the_blocks_it_touches() {
        let n = [20, 9, 17];
        let mut values = vec![0.0; n[0] * n[1] * n[2]];
        let (x, y, z) = (8, 3, 16);
        values[(z * n[1] + y) * n[0] + x] = 1.0;
        let occ = Occupancy::new(n, &values);
        assert_eq!(occ.blocks, [3, 1, 2]);
        let occupied: Vec<usize> = (0..occ.empty.len()).filter(|&i| !occ.empty[i]).collect();
        // x = 8 lies on the boundary of x-blocks 0 and 1; z = 16 is the last sample, in block 1.
        assert_eq!(occupied, vec![3, 4]);
        // The exit of an empty block along +x is its upper plane.
        let q = DVec3::new(17.0, 2.0, 1.0);
        let (a, b) = (DVec3::new(17.0, 2.0, 1.0), DVec3::new(-1.0, 0.0, 0.0));
        assert_eq!(occ.block_of(q, a, b), (true, 1.0));
        let inside = DVec3::new(4.0, 2.0, 12.0);
        assert_eq!(occ.block_of(inside, inside, DVec3::X), (false, 4.0));
    }
}
