//! `brume spectrum`: what colour is this spectrum? The user's tool and the tests' way in.

use serde_json::json;

use super::matrix::{self, Mat3};
use super::{ACES_XY, Cat, ColourError, ColourSpace, D65_XY, Observer, XyzWeights, srgb_encode};
use crate::spectrum::{Extrapolation, MAX_BINS, SpectralGrid, resolve};

#[derive(clap::Args, Clone, Debug)]
pub struct SpectrumArgs {
    /// Spectrum: a CSV file (`wavelength_nm,<column>...`, optionally `FILE:COLUMN`) or a
    /// built-in name (D65, D50, A, F2, F11, LED-B1, colorchecker:<patch name or 1-24>).
    #[arg(required_unless_present = "matrices")]
    pub spectrum: Option<String>,
    /// Data column to use from a multi-column file (name or 1-based index).
    #[arg(long)]
    pub column: Option<String>,
    /// Treat the spectrum as a reflectance seen under this illuminant (name or file).
    /// Without it the spectrum is an emission (radiance) spectrum.
    #[arg(long)]
    pub illuminant: Option<String>,
    /// CIE standard observer: 1931 (2 degree) or 1964 (10 degree).
    #[arg(long, default_value = "1931")]
    pub observer: Observer,
    /// Number of spectral bins.
    #[arg(long, default_value_t = SpectralGrid::default().n)]
    pub bins: usize,
    #[arg(long, default_value_t = 380.0)]
    pub lambda_min: f64,
    #[arg(long, default_value_t = 780.0)]
    pub lambda_max: f64,
    /// Chromatic adaptation used to bring the illuminant's white to sRGB's D65.
    #[arg(long, value_enum, default_value = "bradford")]
    pub cat: CatArg,
    /// Print JSON instead of text.
    #[arg(long)]
    pub json: bool,
    /// Print brume's colour matrices (XYZ -> working spaces, chromatic adaptations) instead.
    #[arg(long)]
    pub matrices: bool,
}

#[derive(clap::ValueEnum, Clone, Copy, Debug)]
pub enum CatArg {
    Bradford,
    Cat02,
}

impl From<CatArg> for Cat {
    fn from(c: CatArg) -> Cat {
        match c {
            CatArg::Bradford => Cat::Bradford,
            CatArg::Cat02 => Cat::Cat02,
        }
    }
}

fn mat_json(m: &Mat3) -> serde_json::Value {
    json!(m.to_vec())
}

fn matrices() -> serde_json::Value {
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

/// Colour of the spectrum, computed exactly as the film does: bin averages times the CMF bin
/// integrals. Reflectances are scaled so the perfect white under the illuminant has Y = 100
/// (colour-science's convention); emission spectra so a constant radiance of 1 has Y = 1.
pub fn run(args: &SpectrumArgs) -> Result<String, ColourError> {
    if args.matrices {
        return Ok(if args.json {
            serde_json::to_string_pretty(&matrices()).unwrap_or_default()
        } else {
            format!("{:#}", matrices())
        });
    }
    let valid = (1..=MAX_BINS).contains(&args.bins)
        && args.lambda_max > args.lambda_min
        && args.lambda_min > 0.0;
    if !valid {
        return Err(ColourError::Other(format!(
            "--bins must be 1..={MAX_BINS} and 0 < --lambda-min < --lambda-max"
        )));
    }
    let grid = SpectralGrid::new(args.bins, args.lambda_min, args.lambda_max);
    let spec = args.spectrum.as_deref().unwrap_or_default();
    let s = resolve(spec, args.column.as_deref(), false)?.bin_averages(&grid, Extrapolation::Clamp);
    let w = XyzWeights::new(args.observer, &grid)?;
    let cat: Cat = args.cat.into();
    let (xyz, white_xy, kind) = match &args.illuminant {
        Some(ill) => {
            let e = resolve(ill, None, false)?.bin_averages(&grid, Extrapolation::Clamp);
            let white = w.xyz_of(&e);
            if white[1] <= 0.0 {
                return Err(ColourError::Other(format!(
                    "illuminant {ill} has no luminance"
                )));
            }
            let xyz = w.xyz_of(&(s * e)).map(|c| 100.0 * c / white[1]);
            (
                xyz,
                matrix::xyz_to_xy(white),
                format!("reflectance under {ill}"),
            )
        }
        None => (w.xyz_of(&s), D65_XY, "emission".to_string()),
    };
    let xy = matrix::xyz_to_xy(xyz);
    // Display the colour as sRGB would: adapt the illuminant's white to D65, and scale so the
    // reference white (reflectance) or the spectrum itself (emission) has Y = 1.
    let norm = if args.illuminant.is_some() {
        100.0
    } else {
        xyz[1].max(f64::MIN_POSITIVE)
    };
    let m = matrix::mul(
        &ColourSpace::Srgb.xyz_to_rgb_unadapted(),
        &cat.matrix(white_xy, D65_XY),
    );
    let lin = matrix::apply(&m, xyz.map(|c| c / norm));
    let enc = lin.map(|c| srgb_encode(c.clamp(0.0, 1.0) as f32) as f64);
    let code = enc.map(|c| (c * 255.0 + 0.5).floor() as u8);
    let obs = match args.observer {
        Observer::Cie1931 => "CIE 1931 2 degree",
        Observer::Cie1964 => "CIE 1964 10 degree",
    };
    if args.json {
        let v = json!({
            "spectrum": spec,
            "kind": kind,
            "observer": obs,
            "bins": grid.n,
            "lambda_min": grid.lambda_min,
            "lambda_max": grid.lambda_max,
            "XYZ": xyz,
            "xy": xy,
            "white_xy": white_xy,
            "srgb_linear": lin,
            "srgb": enc,
            "srgb_8bit": code,
            "bin_values": s.as_slice(grid.n),
        });
        return Ok(serde_json::to_string_pretty(&v).unwrap_or_default());
    }
    Ok(format!(
        "{spec}: {kind}, {obs} observer, {} bins over {}-{} nm\n\
         XYZ          {:.4} {:.4} {:.4}\n\
         xy           {:.5} {:.5}\n\
         sRGB linear  {:.5} {:.5} {:.5}  (white Y = 1, adapted to D65)\n\
         sRGB 8-bit   {} {} {}  (#{:02x}{:02x}{:02x})",
        grid.n,
        grid.lambda_min,
        grid.lambda_max,
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
    ))
}
