//! One ray through a grid: the pieces between crossings of the planes through sample centres,
//! each with its cubic density and the depth at its start, so that `depth(s)` and its inverse
//! `distance(u)` are a binary search and a closed form (or a safeguarded Newton root of a
//! monotone quartic) away.
//!
//! A piece of length `h` starting at `t` writes its density in `y = 3 (s - t) / h`, `y in
//! [0, 3]`, as `p(y) = c0 + c1 y + c2 y² + c3 y³`, fitted through its values at `y = 0, 1, 2,
//! 3` by forward differences (exact: the trilinear field is such a cubic along the piece);
//! the depth within the piece is `(h / 3) Q(y)` with `Q(y) = ∫_0^y p`.

use glam::{DVec3, Vec3};

use super::GridField;

#[derive(Clone, Copy, Debug)]
struct Piece {
    t: f64,
    h: f64,
    /// Depth at the piece's start.
    d0: f64,
    c: [f64; 4],
}

impl Piece {
    /// The piece of length `h` from `t` of the index-space ray `(a, b)`, its cubic fitted
    /// through four values.
    fn fit(field: &GridField, (a, b): (DVec3, DVec3), t: f64, h: f64, d0: f64) -> Self {
        let f = |j: f64| field.at_index(a + b * (t + h * j / 3.0));
        let (f0, f1, f2, f3) = (f(0.0), f(1.0), f(2.0), f(3.0));
        let d1 = f1 - f0;
        let d2 = f2 - 2.0 * f1 + f0;
        let d3 = f3 - 3.0 * f2 + 3.0 * f1 - f0;
        Piece {
            t,
            h,
            d0,
            c: [f0, d1 - d2 / 2.0 + d3 / 3.0, d2 / 2.0 - d3 / 2.0, d3 / 6.0],
        }
    }

    fn p(&self, y: f64) -> f64 {
        let c = &self.c;
        c[0] + y * (c[1] + y * (c[2] + y * c[3]))
    }

    /// `∫_0^y p`, never negative (rounding of a density that is 0 over the piece).
    fn q(&self, y: f64) -> f64 {
        let c = &self.c;
        (y * (c[0] + y * (c[1] / 2.0 + y * (c[2] / 3.0 + y * c[3] / 4.0)))).max(0.0)
    }

    /// Depth across the whole piece.
    fn depth(&self) -> f64 {
        self.h / 3.0 * self.q(3.0)
    }

    /// The `y` at which the depth within the piece is `g` (`0 <= g <= depth()`): `Q` is
    /// nondecreasing, so Newton's steps are kept inside a shrinking bracket.
    fn solve(&self, g: f64) -> f64 {
        let target = 3.0 * g / self.h;
        let (mut lo, mut hi) = (0.0f64, 3.0f64);
        let whole = self.q(3.0);
        let mut y = if whole > 0.0 {
            3.0 * target / whole
        } else {
            0.0
        };
        for _ in 0..64 {
            let f = self.q(y) - target;
            if f > 0.0 {
                hi = y;
            } else {
                lo = y;
            }
            let slope = self.p(y);
            let mut next = if slope > 0.0 { y - f / slope } else { f64::NAN };
            if !(next > lo && next < hi) {
                next = 0.5 * (lo + hi);
            }
            if (next - y).abs() <= 1e-13 || hi - lo <= 1e-13 {
                return next;
            }
            y = next;
        }
        y
    }
}

/// The pieces of one ray (none where it misses the grid's box).
#[derive(Clone, Debug)]
pub struct GridRay {
    pieces: Vec<Piece>,
}

impl GridRay {
    /// Every piece of the ray inside the box.
    pub(super) fn new(field: &GridField, o: Vec3, d: Vec3) -> Self {
        Self::until(field, o, d, (f32::INFINITY, f32::INFINITY))
    }

    /// The pieces up to distance `s_max` or to the first piece end at which the depth, as an
    /// f32, exceeds `u_max`, whichever comes first. Within that reach `depth` and `distance`
    /// give the whole ray's numbers bit for bit (its pieces are the whole ray's first ones).
    /// Beyond it `depth` gives the depth built so far, which is at most the whole ray's (and,
    /// when cut by `u_max`, still more than `u_max`), and `distance` gives `+inf`.
    pub(super) fn until(field: &GridField, o: Vec3, d: Vec3, (s_max, u_max): (f32, f32)) -> Self {
        let (a, b) = field.index_ray(o, d);
        let mut pieces: Vec<Piece> = Vec::new();
        let Some(mut cross) = field.crossings(a, b) else {
            return Self { pieces };
        };
        // A NaN depth (a flight that never collides) reaches as far as s_max.
        let u_max = if u_max.is_nan() {
            f64::INFINITY
        } else {
            u_max as f64
        };
        let s_max = s_max as f64;
        let mut t = cross.first();
        let (mut d0, mut occupied) = (0.0, f64::NEG_INFINITY);
        while t < s_max && (d0 as f32 as f64) <= u_max {
            let Some(next) = cross.next() else { break };
            let (end, empty) = field.piece_end((&mut cross, &mut occupied), (a, b), t, next);
            let h = end - t;
            if empty || field.empty_at(a + b * (t + 0.5 * h)) {
                // No smoke in the cell or block: one zero piece, merged with an empty one
                // before it.
                match pieces.last_mut() {
                    Some(p) if p.c == [0.0; 4] => p.h = t + h - p.t,
                    Some(_) | None => pieces.push(Piece {
                        t,
                        h,
                        d0,
                        c: [0.0; 4],
                    }),
                }
            } else {
                let piece = Piece::fit(field, (a, b), t, h, d0);
                d0 += piece.depth();
                pieces.push(piece);
            }
            t = end;
        }
        Self { pieces }
    }

    /// The piece containing distance `s`, if any.
    fn piece_at(&self, s: f64) -> Option<&Piece> {
        let i = self.pieces.partition_point(|p| p.t <= s);
        let p = self.pieces.get(i.checked_sub(1)?)?;
        (s <= p.t + p.h).then_some(p)
    }

    pub fn depth(&self, s: f32) -> f32 {
        let s = s as f64;
        let i = self.pieces.partition_point(|p| p.t <= s);
        let Some(p) = i.checked_sub(1).and_then(|i| self.pieces.get(i)) else {
            return 0.0;
        };
        let y = (3.0 * (s - p.t) / p.h).min(3.0);
        (p.d0 + p.h / 3.0 * p.q(y)) as f32
    }

    pub fn distance(&self, u: f32) -> f32 {
        let u = u as f64;
        if u <= 0.0 {
            return 0.0;
        }
        let i = self.pieces.partition_point(|p| p.d0 + p.depth() < u);
        let Some(p) = self.pieces.get(i) else {
            // The whole depth, given back as f32 (rounded up), still ends at the last piece.
            return match self.pieces.last() {
                Some(p) if u <= (p.d0 + p.depth()) as f32 as f64 => (p.t + p.h) as f32,
                Some(_) | None => f32::INFINITY,
            };
        };
        let g = (u - p.d0).clamp(0.0, p.depth());
        (p.t + p.h / 3.0 * p.solve(g)) as f32
    }

    pub fn rho(&self, s: f32) -> f32 {
        let s = s as f64;
        self.piece_at(s)
            .map_or(0.0, |p| p.p(3.0 * (s - p.t) / p.h).max(0.0) as f32)
    }
}
