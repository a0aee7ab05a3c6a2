//! 3x3 matrices in f64 (row-major) for colour-space conversions: products and XYZ / xyY
//! conversions through palette (the same operations in the same order as before, so the same
//! bits), the inverse by brume's cofactors (see `invert`).

use palette::convert::{Convert, FromColorUnclamped};
use palette::white_point::Any;
use palette::{Xyz, Yxy};

pub type Mat3 = [[f64; 3]; 3];

pub const IDENTITY: Mat3 = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];

/// A linear map of 3-vectors in palette's terms (the colour types only tag the arrays).
type Linear = palette::convert::Matrix3<Xyz<Any, f64>, Xyz<Any, f64>>;

fn to_palette(m: &Mat3) -> Linear {
    Linear::from_array([
        m[0][0], m[0][1], m[0][2], m[1][0], m[1][1], m[1][2], m[2][0], m[2][1], m[2][2],
    ])
}

fn from_palette(m: Linear) -> Mat3 {
    let a = m.into_array();
    [[a[0], a[1], a[2]], [a[3], a[4], a[5]], [a[6], a[7], a[8]]]
}

/// The product `a b` (apply `b` first).
pub fn mul(a: &Mat3, b: &Mat3) -> Mat3 {
    from_palette(to_palette(b).then(to_palette(a)))
}

pub fn apply(m: &Mat3, v: [f64; 3]) -> [f64; 3] {
    let out = to_palette(m).convert(Xyz::new(v[0], v[1], v[2]));
    [out.x, out.y, out.z]
}

pub fn diag(v: [f64; 3]) -> Mat3 {
    [[v[0], 0.0, 0.0], [0.0, v[1], 0.0], [0.0, 0.0, v[2]]]
}

/// The inverse, by cofactors divided by the determinant. Not palette's `invert`, which multiplies
/// by the determinant's reciprocal: that moves the last bits of the XYZ -> RGB matrices, and the
/// shipped RGB -> spectrum table (fitted through them, and so every rendered RGB material) is
/// checked to equal a fresh fit (`tests/spectrum_rgb_table.rs`). The matrices inverted are all
/// fixed in the code (primaries, cone responses) and well conditioned.
pub fn invert(m: &Mat3) -> Mat3 {
    let c =
        |r0: usize, r1: usize, c0: usize, c1: usize| m[r0][c0] * m[r1][c1] - m[r0][c1] * m[r1][c0];
    let cof = [
        [c(1, 2, 1, 2), -c(1, 2, 0, 2), c(1, 2, 0, 1)],
        [-c(0, 2, 1, 2), c(0, 2, 0, 2), -c(0, 2, 0, 1)],
        [c(0, 1, 1, 2), -c(0, 1, 0, 2), c(0, 1, 0, 1)],
    ];
    let det = m[0][0] * cof[0][0] + m[0][1] * cof[0][1] + m[0][2] * cof[0][2];
    // The inverse is the transposed cofactor matrix over the determinant.
    let mut inv = [[0.0; 3]; 3];
    for (i, row) in inv.iter_mut().enumerate() {
        for (j, v) in row.iter_mut().enumerate() {
            *v = cof[j][i] / det;
        }
    }
    inv
}

/// XYZ (with Y = 1) of a chromaticity.
pub fn xy_to_xyz(xy: [f64; 2]) -> [f64; 3] {
    let xyz = Xyz::<Any, f64>::from_color_unclamped(Yxy::new(xy[0], xy[1], 1.0));
    [xyz.x, xyz.y, xyz.z]
}

/// Chromaticity of an XYZ colour ((0, 0) for black).
pub fn xyz_to_xy(xyz: [f64; 3]) -> [f64; 2] {
    let c = Yxy::<Any, f64>::from_color_unclamped(Xyz::new(xyz[0], xyz[1], xyz[2]));
    [c.x, c.y]
}

/// The RGB -> XYZ matrix of an RGB space (its "normalised primary matrix"): columns are the
/// primaries' XYZ, scaled so that RGB (1, 1, 1) maps to the white with Y = 1.
pub fn rgb_to_xyz(primaries: [[f64; 2]; 3], white: [f64; 2]) -> Mat3 {
    let p = primaries.map(xy_to_xyz);
    let cols: Mat3 = [
        [p[0][0], p[1][0], p[2][0]],
        [p[0][1], p[1][1], p[2][1]],
        [p[0][2], p[1][2], p[2][2]],
    ];
    let s = apply(&invert(&cols), xy_to_xyz(white));
    mul(&cols, &diag(s))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn inverse_round_trips() {
        let m = [[0.4, 0.35, 0.18], [0.21, 0.71, 0.07], [0.02, 0.12, 0.95]];
        let p = mul(&m, &invert(&m));
        for (i, row) in p.iter().enumerate() {
            for (j, v) in row.iter().enumerate() {
                let e = if i == j { 1.0 } else { 0.0 };
                assert!((v - e).abs() < 1e-12);
            }
        }
    }
}
