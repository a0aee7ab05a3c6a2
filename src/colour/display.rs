//! Display encoding: exposure, view transform and the sRGB transfer function.

use palette::encoding::{FromLinear, IntoLinear, Srgb};

use super::ViewTransform;

/// The exact sRGB (IEC 61966-2-1) encoding of a display-linear value in [0, 1] (palette's,
/// which has no approximation for f32 -> f32; it equals the textbook formula bit for bit on
/// every f32 in [0, 1]).
pub fn srgb_encode(v: f32) -> f32 {
    <Srgb as FromLinear<f32, f32>>::from_linear(v)
}

/// The exact sRGB decoding (within 2 ulp of the textbook formula's rounding).
pub fn srgb_decode(v: f32) -> f32 {
    <Srgb as IntoLinear<f32, f32>>::into_linear(v)
}

/// Middle grey, which the filmic curve leaves in place (scene 0.18 -> display 0.18).
const GREY: f32 = 0.18;
/// Contrast of the filmic curve: its slope in log-log space at black.
const CONTRAST: f32 = 1.2;

/// A Hill (Naka-Rushton) curve `v^n / (v^n + s^n)`: a sigmoid in log exposure that keeps
/// middle grey, lifts nothing, and rolls highlights off smoothly (4x grey-to-white maps to
/// ~0.9 instead of clipping), the photoreceptor-like response filmic curves imitate.
fn filmic_channel(v: f32) -> f32 {
    // s^n chosen so that GREY is a fixed point: GREY^n / (GREY^n + s^n) = GREY.
    let grey_n = GREY.powf(CONTRAST);
    let s_n = grey_n * (1.0 / GREY - 1.0);
    let v_n = v.max(0.0).powf(CONTRAST);
    v_n / (v_n + s_n)
}

impl ViewTransform {
    /// Scene-linear RGB (already in Rec.709 primaries) to display-linear [0, 1].
    pub fn apply(self, rgb: [f32; 3], exposure: f32) -> [f32; 3] {
        let k = exposure.exp2();
        match self {
            ViewTransform::Clip => rgb.map(|c| (c * k).clamp(0.0, 1.0)),
            ViewTransform::Filmic => {
                // Pull out-of-gamut (negative) components in towards the luminance first,
                // so the per-channel curve never sees a negative.
                let rgb = rgb.map(|c| c * k);
                let y = 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2];
                let lo = rgb.iter().copied().fold(f32::INFINITY, f32::min);
                let rgb = if lo < 0.0 && y > 0.0 {
                    let t = y / (y - lo);
                    rgb.map(|c| y + t * (c - y))
                } else {
                    rgb
                };
                rgb.map(filmic_channel)
            }
        }
    }

    /// The scene value (after exposure) this view shows as white: 1 for `Clip`; for `Filmic`
    /// the value its curve takes to 0.95 (its shoulder never quite reaches 1).
    pub fn white(self) -> f32 {
        match self {
            ViewTransform::Clip => 1.0,
            ViewTransform::Filmic => {
                // v^n / (v^n + s^n) = w  <=>  v = s (w / (1 - w))^(1/n).
                let s_n = GREY.powf(CONTRAST) * (1.0 / GREY - 1.0);
                let w: f32 = 0.95;
                (s_n * w / (1.0 - w)).powf(1.0 / CONTRAST)
            }
        }
    }

    /// Display-linear -> 8-bit sRGB code value (round to nearest).
    pub fn encode_u8(v: f32) -> u8 {
        (srgb_encode(v.clamp(0.0, 1.0)) * 255.0 + 0.5) as u8
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_views_white_is_where_they_show_white() {
        assert_eq!(ViewTransform::Clip.white(), 1.0);
        let w = ViewTransform::Filmic.white();
        assert!((filmic_channel(w) - 0.95).abs() < 1e-4, "{w}");
    }

    /// The textbook piecewise formula, which palette's encoding must reproduce exactly (the
    /// PNG's 8-bit codes depend on it).
    fn textbook_encode(v: f32) -> f32 {
        if v <= 0.003_130_8 {
            12.92 * v
        } else {
            1.055 * v.powf(1.0 / 2.4) - 0.055
        }
    }

    #[test]
    fn srgb_encoding_equals_the_textbook_formula_bit_for_bit() {
        // Every 97th f32 in [0, 1] (11 million values), both branches and the knee.
        let one = 1.0f32.to_bits();
        for bits in (0..=one).step_by(97).chain([one, 0.003_130_8f32.to_bits()]) {
            let v = f32::from_bits(bits);
            assert_eq!(
                srgb_encode(v).to_bits(),
                textbook_encode(v).to_bits(),
                "{v:e}"
            );
        }
    }

    #[test]
    fn srgb_transfer_known_values_and_inverse() {
        assert_eq!(srgb_encode(0.0), 0.0);
        assert!((srgb_encode(1.0) - 1.0).abs() < 1e-6);
        // 18% grey encodes to 0.4613561 (118/255 rounded).
        assert!((srgb_encode(0.18) - 0.461_356_1).abs() < 1e-6);
        for i in 0..=100 {
            let v = i as f32 / 100.0;
            assert!((srgb_decode(srgb_encode(v)) - v).abs() < 1e-6);
        }
    }

    #[test]
    fn filmic_is_monotone_and_rolls_off() {
        let mut prev = -1.0;
        for i in 0..200 {
            let v = 1e-4 * 1.1f32.powi(i);
            let d = filmic_channel(v);
            assert!(d >= prev && (0.0..=1.0).contains(&d));
            prev = d;
        }
        assert!(filmic_channel(4.0) < 1.0, "highlights must not clip at 4x");
        assert!((filmic_channel(GREY) - GREY).abs() < 1e-6);
        assert!(filmic_channel(0.0) == 0.0);
    }
}
