//! What colour is this spectrum? The computation behind `brume spectrum` (the command-line
//! arguments live in the binary; this takes a plain request), also the tests' way in.

use serde_json::json;

use super::matrix::{self, Mat3};
use super::{ACES_XY, Cat, ColourError, ColourSpace, D65_XY, Observer, XyzWeights, srgb_encode};
use crate::spectrum::{Extrapolation, MAX_BINS, SpectralGrid, lines as line_spectrum, resolve};

/// A spectrum to describe and how.
#[derive(Clone, Debug)]
pub struct SpectrumRequest {
    /// A CSV file (optionally `FILE:COLUMN`) or a built-in name; only a label when `lines`
    /// are given.
    pub spectrum: String,
    /// Spectral lines (nm, relative power) to describe instead: an emission, each line in its
    /// own narrow bin of `grid` (see [`check_grid`]).
    pub lines: Vec<(f64, f64)>,
    /// Data column of a multi-column file (name or 1-based index).
    pub column: Option<String>,
    /// Treat the spectrum as a reflectance under this illuminant (else it is an emission).
    pub illuminant: Option<String>,
    pub observer: Observer,
    pub grid: SpectralGrid,
    /// Adaptation of the illuminant's white to sRGB's D65.
    pub cat: Cat,
}

/// The colour of a spectrum, computed exactly as the film computes it.
#[derive(Clone, Debug)]
pub struct SpectrumColour {
    pub request: SpectrumRequest,
    /// "emission" or "reflectance under NAME".
    pub kind: String,
    pub xyz: [f64; 3],
    pub xy: [f64; 2],
    pub white_xy: [f64; 2],
    pub srgb_linear: [f64; 3],
    pub srgb: [f64; 3],
    pub srgb_8bit: [u8; 3],
    pub bin_values: Vec<f32>,
    /// Of an emission spectrum: lumens per watt of its power over the grid's range, as the
    /// renderer converts a light's `luminous_flux` (K_m = 683 lm/W, CIE 1931 V(λ)).
    pub luminous_efficacy: Option<f64>,
}

fn mat_json(m: &Mat3) -> serde_json::Value {
    json!(m.to_vec())
}

/// The matrices the tests compare with colour-science.
pub fn matrices() -> serde_json::Value {
    json!({
        "xyz_to_srgb": mat_json(&ColourSpace::Srgb.xyz_to_rgb_unadapted()),
        "xyz_to_acescg": mat_json(&ColourSpace::Acescg.xyz_to_rgb_unadapted()),
        "xyz_d65_to_acescg_bradford": mat_json(&ColourSpace::Acescg.xyz_to_rgb(D65_XY, Cat::Bradford)),
        "xyz_d65_to_acescg_cat02": mat_json(&ColourSpace::Acescg.xyz_to_rgb(D65_XY, Cat::Cat02)),
        "cat_bradford_d65_to_aces": mat_json(&Cat::Bradford.matrix(D65_XY, ACES_XY)),
        "cat_cat02_d65_to_aces": mat_json(&Cat::Cat02.matrix(D65_XY, ACES_XY)),
        "whites": { "d65": D65_XY, "aces": ACES_XY },
    })
}

/// Checks that a spectral grid is one brume can use: `bins` equal bins split around a narrow
/// bin at each of `lines` (nm).
pub fn check_grid(
    bins: usize,
    lambda_min: f64,
    lambda_max: f64,
    lines: &[f64],
) -> Result<SpectralGrid, ColourError> {
    let valid = (1..=MAX_BINS).contains(&bins) && lambda_max > lambda_min && lambda_min > 0.0;
    if !valid {
        return Err(ColourError::Other(format!(
            "--bins must be 1..={MAX_BINS} and 0 < --lambda-min < --lambda-max"
        )));
    }
    SpectralGrid::with_lines(bins, lambda_min, lambda_max, lines)
        .map_err(|e| ColourError::Other(format!("--line: {e}")))
}

/// Colour of the spectrum, computed exactly as the film does: bin averages times the CMF bin
/// integrals. Reflectances are scaled so the perfect white under the illuminant has Y = 100
/// (colour-science's convention); emission spectra so a constant radiance of 1 has Y = 1.
pub fn spectrum_colour(req: &SpectrumRequest) -> Result<SpectrumColour, ColourError> {
    let grid = &req.grid;
    let s = if req.lines.is_empty() {
        resolve(&req.spectrum, req.column.as_deref(), false)?
            .bin_averages(grid, Extrapolation::Clamp)
    } else if req.illuminant.is_some() {
        return Err(ColourError::Other(
            "spectral lines are an emission: --illuminant does not apply".into(),
        ));
    } else {
        line_spectrum(&req.lines, grid).map_err(|l| {
            ColourError::Other(format!("the grid has no bin for the line at {l} nm"))
        })?
    };
    let w = XyzWeights::new(req.observer, grid)?;
    let (xyz, white_xy, kind) = match &req.illuminant {
        Some(ill) => {
            let e = resolve(ill, None, false)?.bin_averages(grid, Extrapolation::Clamp);
            let white = w.xyz_of(&e);
            if white[1] <= 0.0 {
                return Err(ColourError::Other(format!(
                    "illuminant {ill} has no luminance"
                )));
            }
            let xyz = w.xyz_of(&(s * e)).map(|c| 100.0 * c / white[1]);
            let kind = format!("reflectance under {ill}");
            (xyz, matrix::xyz_to_xy(white), kind)
        }
        None => (w.xyz_of(&s), D65_XY, "emission".to_string()),
    };
    // Display the colour as sRGB would: adapt the illuminant's white to D65, and scale so the
    // reference white (reflectance) or the spectrum itself (emission) has Y = 1.
    let norm = if req.illuminant.is_some() {
        100.0
    } else {
        xyz[1].max(f64::MIN_POSITIVE)
    };
    let m = matrix::mul(
        &ColourSpace::Srgb.xyz_to_rgb_unadapted(),
        &req.cat.matrix(white_xy, D65_XY),
    );
    let lin = matrix::apply(&m, xyz.map(|c| c / norm));
    let enc = lin.map(|c| srgb_encode(c.clamp(0.0, 1.0) as f32) as f64);
    Ok(SpectrumColour {
        request: req.clone(),
        kind,
        xyz,
        xy: matrix::xyz_to_xy(xyz),
        white_xy,
        srgb_linear: lin,
        srgb: enc,
        srgb_8bit: enc.map(|c| (c * 255.0 + 0.5).floor() as u8),
        bin_values: s.as_slice(grid.n).to_vec(),
        luminous_efficacy: match req.illuminant {
            Some(_) => None,
            None => {
                let w = super::photometry::luminous_weights(grid)?;
                super::photometry::luminous_efficacy(&w, s.as_slice(grid.n), grid)
            }
        },
    })
}

impl SpectrumColour {
    fn observer_name(&self) -> &'static str {
        match self.request.observer {
            Observer::Cie1931 => "CIE 1931 2 degree",
            Observer::Cie1964 => "CIE 1964 10 degree",
        }
    }

    pub fn to_json(&self) -> String {
        let g = &self.request.grid;
        let v = json!({
            "spectrum": self.request.spectrum,
            "kind": self.kind,
            "observer": self.observer_name(),
            "bins": g.n,
            "lambda_min": g.lambda_min,
            "lambda_max": g.lambda_max,
            "lines": g.lines(),
            "XYZ": self.xyz,
            "xy": self.xy,
            "white_xy": self.white_xy,
            "srgb_linear": self.srgb_linear,
            "srgb": self.srgb,
            "srgb_8bit": self.srgb_8bit,
            "bin_values": self.bin_values,
            "luminous_efficacy_lm_per_w": self.luminous_efficacy,
        });
        serde_json::to_string_pretty(&v).unwrap_or_default()
    }

    pub fn to_text(&self) -> String {
        let mut text = self.colour_text();
        if let Some(e) = self.luminous_efficacy {
            let g = &self.request.grid;
            text.push_str(&format!(
                "\nluminous efficacy  {e:.3} lm/W  (over {}-{} nm, K_m = 683 lm/W, CIE 1931 V; \
                 the lumens-to-watts factor of a light with this spectrum)",
                g.lambda_min, g.lambda_max
            ));
        }
        text
    }

    fn colour_text(&self) -> String {
        let (g, xyz, xy, lin, code) = (
            &self.request.grid,
            self.xyz,
            self.xy,
            self.srgb_linear,
            self.srgb_8bit,
        );
        format!(
            "{}: {}, {} observer, {} bins over {}-{} nm\n\
             XYZ          {:.4} {:.4} {:.4}\n\
             xy           {:.5} {:.5}\n\
             sRGB linear  {:.5} {:.5} {:.5}  (white Y = 1, adapted to D65)\n\
             sRGB 8-bit   {} {} {}  (#{:02x}{:02x}{:02x})",
            self.request.spectrum,
            self.kind,
            self.observer_name(),
            g.n,
            g.lambda_min,
            g.lambda_max,
            xyz[0],
            xyz[1],
            xyz[2],
            xy[0],
            xy[1],
            lin[0],
            lin[1],
            lin[2],
            code[0],
            code[1],
            code[2],
            code[0],
            code[1],
            code[2],
        )
    }
}
