//! Chromatic adaptation (von Kries scaling in a cone-like space). palette adapts between white
//! points known as types; brume's whites come at run time (an illuminant's measured white), and
//! palette has no CAT02, so the von Kries step is written here on palette's matrix algebra.

use serde::{Deserialize, Serialize};

use palette::lms::matrix::{Bradford, XyzToLms};

use super::matrix::{self, Mat3};

/// The cone-response space a chromatic adaptation scales in.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Cat {
    /// Bradford (Lam 1985), as used by ICC profiles and OCIO's built-in configs.
    #[default]
    Bradford,
    /// CAT02 (CIECAM02).
    Cat02,
}

/// Bradford's cone responses, as palette defines them (Lam 1985).
fn bradford() -> Mat3 {
    let m = <Bradford as XyzToLms<f64>>::xyz_to_lms_matrix();
    [[m[0], m[1], m[2]], [m[3], m[4], m[5]], [m[6], m[7], m[8]]]
}

/// CAT02 (CIE 159:2004), which palette does not define.
const CAT02: Mat3 = [
    [0.7328, 0.4296, -0.1624],
    [-0.7036, 1.6975, 0.0061],
    [0.0030, 0.0136, 0.9834],
];

impl Cat {
    fn cone(self) -> Mat3 {
        match self {
            Cat::Bradford => bradford(),
            Cat::Cat02 => CAT02,
        }
    }

    /// The XYZ -> XYZ matrix that maps colours seen under white `src` (chromaticity) to
    /// the corresponding colours under white `dst`.
    pub fn matrix(self, src: [f64; 2], dst: [f64; 2]) -> Mat3 {
        self.matrix_xyz(matrix::xy_to_xyz(src), matrix::xy_to_xyz(dst))
    }

    /// As [`Cat::matrix`], with the whites given as XYZ.
    pub fn matrix_xyz(self, src: [f64; 3], dst: [f64; 3]) -> Mat3 {
        let m = self.cone();
        let s = matrix::apply(&m, src);
        let d = matrix::apply(&m, dst);
        let scale = matrix::diag([d[0] / s[0], d[1] / s[1], d[2] / s[2]]);
        matrix::mul(&matrix::invert(&m), &matrix::mul(&scale, &m))
    }
}
