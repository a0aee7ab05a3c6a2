//! Chromatic adaptation (von Kries scaling in a cone-like space).

use serde::{Deserialize, Serialize};

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

const BRADFORD: Mat3 = [
    [0.8951, 0.2664, -0.1614],
    [-0.7502, 1.7135, 0.0367],
    [0.0389, -0.0685, 1.0296],
];

const CAT02: Mat3 = [
    [0.7328, 0.4296, -0.1624],
    [-0.7036, 1.6975, 0.0061],
    [0.0030, 0.0136, 0.9834],
];

impl Cat {
    fn cone(self) -> Mat3 {
        match self {
            Cat::Bradford => BRADFORD,
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
