//! Working spaces: which RGB primaries and white scene-linear output is written in.

use super::ColourSpace;
use super::adapt::Cat;
use super::matrix::{self, IDENTITY, Mat3};

/// CIE 1931 D65 as sRGB / Rec.709 define it.
pub const D65_XY: [f64; 2] = [0.3127, 0.3290];
/// The ACES white (close to, but not exactly, CIE D60).
pub const ACES_XY: [f64; 2] = [0.32168, 0.33767];
/// Illuminant E, the white of XYZ itself.
pub const E_XY: [f64; 2] = [1.0 / 3.0, 1.0 / 3.0];

pub const REC709_PRIMARIES: [[f64; 2]; 3] = [[0.64, 0.33], [0.30, 0.60], [0.15, 0.06]];
pub const AP1_PRIMARIES: [[f64; 2]; 3] = [[0.713, 0.293], [0.165, 0.830], [0.128, 0.044]];
/// Chromaticities that make an RGB file's channels equal to X, Y, Z (OpenEXR's convention).
pub const XYZ_PRIMARIES: [[f64; 2]; 3] = [[1.0, 0.0], [0.0, 1.0], [0.0, 0.0]];

impl ColourSpace {
    /// Primaries (R, G, B) and white chromaticities, as written to EXR `chromaticities`.
    pub fn chromaticities(self) -> ([[f64; 2]; 3], [f64; 2]) {
        match self {
            ColourSpace::Srgb => (REC709_PRIMARIES, D65_XY),
            ColourSpace::Acescg => (AP1_PRIMARIES, ACES_XY),
            ColourSpace::Xyz => (XYZ_PRIMARIES, E_XY),
        }
    }

    pub fn white(self) -> [f64; 2] {
        self.chromaticities().1
    }

    /// XYZ -> RGB for colours already relative to this space's own white (no adaptation).
    pub fn xyz_to_rgb_unadapted(self) -> Mat3 {
        match self {
            ColourSpace::Xyz => IDENTITY,
            _ => {
                let (p, w) = self.chromaticities();
                matrix::invert(&matrix::rgb_to_xyz(p, w))
            }
        }
    }

    /// XYZ -> RGB for colours whose adopted white is `scene_white`.
    ///
    /// A renderer's XYZ is absolute, but its "white" (what should come out neutral) is the
    /// white the scene is meant to be viewed in, D65 for brume (sRGB's). Spaces with another
    /// white (ACEScg) get a chromatic adaptation `scene_white -> space white` first, so a
    /// D65-neutral surface is RGB-neutral in every space, exactly as OCIO converts between
    /// Rec.709 and ACEScg. XYZ output is left unadapted: it is the measurement itself.
    pub fn xyz_to_rgb(self, scene_white: [f64; 2], cat: Cat) -> Mat3 {
        let to_rgb = self.xyz_to_rgb_unadapted();
        if self == ColourSpace::Xyz || self.white() == scene_white {
            return to_rgb;
        }
        matrix::mul(&to_rgb, &cat.matrix(scene_white, self.white()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: &Mat3, b: &Mat3, tol: f64) {
        for i in 0..3 {
            for j in 0..3 {
                assert!((a[i][j] - b[i][j]).abs() < tol, "{a:?} vs {b:?}");
            }
        }
    }

    #[test]
    fn srgb_matrix_matches_iec_61966() {
        // IEC 61966-2-1 (amendment 1) XYZ -> linear sRGB, derived from the same primaries.
        let m = ColourSpace::Srgb.xyz_to_rgb(D65_XY, Cat::Bradford);
        let known = [
            [3.2409699, -1.5373832, -0.4986108],
            [-0.9692436, 1.8759675, 0.0415551],
            [0.0556301, -0.2039770, 1.0569715],
        ];
        close(&m, &known, 1e-6);
    }

    #[test]
    fn ap1_matrix_matches_aces_spec() {
        // S-2014-004 (ACEScg): XYZ -> AP1 for ACES-white-relative XYZ.
        let m = ColourSpace::Acescg.xyz_to_rgb_unadapted();
        let known = [
            [1.6410233797, -0.3248032942, -0.2364246952],
            [-0.6636628587, 1.6153315917, 0.0167563477],
            [0.0117218943, -0.0082844420, 0.9883948585],
        ];
        close(&m, &known, 1e-6);
    }

    #[test]
    fn bradford_d65_to_d50_matches_lindbloom() {
        // Bradford D65 -> D50 as published by B. Lindbloom, with his XYZ whites.
        let m = Cat::Bradford.matrix_xyz([0.95047, 1.0, 1.08883], [0.96422, 1.0, 0.82521]);
        let known = [
            [1.0478112, 0.0228866, -0.0501270],
            [0.0295424, 0.9904844, -0.0170491],
            [-0.0092345, 0.0150436, 0.7521316],
        ];
        close(&m, &known, 1e-6);
    }

    #[test]
    fn adaptation_maps_source_white_to_destination_white() {
        for cat in [Cat::Bradford, Cat::Cat02] {
            let w = matrix::apply(&cat.matrix(D65_XY, ACES_XY), matrix::xy_to_xyz(D65_XY));
            let d = matrix::xy_to_xyz(ACES_XY);
            for c in 0..3 {
                assert!((w[c] - d[c]).abs() < 1e-12, "{cat:?}");
            }
        }
    }

    #[test]
    fn d65_white_is_neutral_in_every_rgb_space() {
        let w = matrix::xy_to_xyz(D65_XY);
        for cs in [ColourSpace::Srgb, ColourSpace::Acescg] {
            for cat in [Cat::Bradford, Cat::Cat02] {
                let rgb = matrix::apply(&cs.xyz_to_rgb(D65_XY, cat), w);
                for c in rgb {
                    assert!((c - 1.0).abs() < 1e-12, "{cs:?} {cat:?} {rgb:?}");
                }
            }
        }
    }
}
