//! The distances at which a ray crosses the planes through sample centres, in increasing order,
//! generated one at a time (a 3D DDA over the sample lattice) rather than collected and sorted:
//! a ray that stops early (a flight that collides a few cells in) then pays only for the cells
//! it visits, and a long one never sorts.
//!
//! The sequence is the box interval's ends `t0` and `t1` and, between them, every crossing
//! `t = (p - a_k) / b_k` of an integer plane `p` of axis `k` within the samples' range, equal
//! distances of two axes given once. Each axis's crossings are increasing in `t` (correctly
//! rounded subtraction and division are monotone), so merging the three axes gives the same
//! numbers, bit for bit, as sorting them all.

use glam::DVec3;

/// One axis's remaining planes: the next plane, its step (+1 or -1) and the last plane.
#[derive(Clone, Copy, Debug)]
struct Axis {
    plane: f64,
    step: f64,
    last: f64,
    /// Distance of `plane` (`+inf` when the axis has no plane left).
    t: f64,
}

impl Axis {
    fn t_of(&self, a: f64, b: f64) -> f64 {
        let past = if self.step > 0.0 {
            self.plane > self.last
        } else {
            self.plane < self.last
        };
        if past {
            f64::INFINITY
        } else {
            (self.plane - a) / b
        }
    }
}

/// The crossings of one index-space ray `a + b t` over its box interval `[t0, t1]`.
#[derive(Clone, Debug)]
pub(super) struct Crossings {
    a: DVec3,
    b: DVec3,
    t1: f64,
    axes: [Axis; 3],
    /// The last distance given (`t0` before the first call of `next`).
    prev: f64,
    done: bool,
}

impl Crossings {
    /// The crossings over `[t0, t1]` of a box with `n` samples per axis.
    pub(super) fn new(a: DVec3, b: DVec3, (t0, t1): (f64, f64), n: DVec3) -> Self {
        let axis = |k: usize| -> Axis {
            let none = Axis {
                plane: 0.0,
                step: 1.0,
                last: -1.0,
                t: f64::INFINITY,
            };
            if b[k] == 0.0 || n[k] < 2.0 {
                return none;
            }
            let (ea, eb) = (a[k] + b[k] * t0, a[k] + b[k] * t1);
            let (lo, hi) = (ea.min(eb).max(0.0), ea.max(eb).min(n[k] - 1.0));
            // The integers in [lo, hi], walked in the direction the ray moves.
            let mut ax = if b[k] > 0.0 {
                Axis {
                    plane: lo.ceil(),
                    step: 1.0,
                    last: hi,
                    t: 0.0,
                }
            } else {
                Axis {
                    plane: hi.floor(),
                    step: -1.0,
                    last: lo,
                    t: 0.0,
                }
            };
            ax.t = ax.t_of(a[k], b[k]);
            // Rounding can put the first planes at or before t0: they are not crossings.
            while ax.t <= t0 {
                ax.plane += ax.step;
                ax.t = ax.t_of(a[k], b[k]);
            }
            ax
        };
        Self {
            a,
            b,
            t1,
            axes: [axis(0), axis(1), axis(2)],
            prev: t0,
            done: false,
        }
    }

    /// The first distance, `t0` (called before `next`, which moves on from it).
    pub(super) fn first(&self) -> f64 {
        self.prev
    }
}

impl Crossings {
    /// Drops the crossings before `t` (a crossing itself, or beyond `t1`), so that the next one
    /// given is `t` or, past the box, `t1`.
    pub(super) fn skip_to(&mut self, t: f64) {
        for k in 0..3 {
            let ax = &mut self.axes[k];
            while ax.t < t {
                ax.plane += ax.step;
                ax.t = ax.t_of(self.a[k], self.b[k]);
            }
        }
    }
}

impl Iterator for Crossings {
    type Item = f64;

    /// The next distance after the last one given, ending with `t1`.
    fn next(&mut self) -> Option<f64> {
        if self.done {
            return None;
        }
        loop {
            let k = (0..3)
                .min_by(|&i, &j| self.axes[i].t.total_cmp(&self.axes[j].t))
                .unwrap_or(0);
            let t = self.axes[k].t;
            if t >= self.t1 {
                self.done = true;
                self.prev = self.t1;
                return Some(self.t1);
            }
            let ax = &mut self.axes[k];
            ax.plane += ax.step;
            ax.t = ax.t_of(self.a[k], self.b[k]);
            if t > self.prev {
                self.prev = t;
                return Some(t);
            }
        }
    }
}
