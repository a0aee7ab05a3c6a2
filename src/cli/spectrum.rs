//! `brume spectrum`: what colour is this spectrum? Arguments here, the computation in
//! `brume::colour::describe`.

use std::process::ExitCode;

use clap::Args;

use brume::colour::describe::{self, SpectrumRequest};
use brume::colour::{Cat, Observer};
use brume::spectrum::SpectralGrid;

#[derive(Args, Clone, Debug)]
pub struct SpectrumArgs {
    /// Spectrum: a CSV file (`wavelength_nm,<column>...`, optionally `FILE:COLUMN`) or a
    /// built-in name (D65, D50, A, F2, F11, LED-B1, colorchecker:<patch name or 1-24>).
    #[arg(required_unless_present_any = ["matrices", "line"])]
    pub spectrum: Option<String>,
    /// A spectral line instead of a spectrum: `NM` or `NM:POWER` (relative power, default 1);
    /// repeat for several lines. The line gets its own narrow bin, as in a scene.
    #[arg(long, value_parser = parse_line, conflicts_with = "spectrum")]
    pub line: Vec<(f64, f64)>,
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

pub fn run(args: &SpectrumArgs) -> anyhow::Result<ExitCode> {
    if args.matrices {
        let m = describe::matrices();
        if args.json {
            outln!("{}", serde_json::to_string_pretty(&m)?)?;
        } else {
            outln!("{m:#}")?;
        }
        return Ok(ExitCode::SUCCESS);
    }
    let label = || {
        let nm = |&(l, p): &(f64, f64)| match p == 1.0 {
            true => format!("{l} nm"),
            false => format!("{l} nm x {p}"),
        };
        let lines: Vec<String> = args.line.iter().map(nm).collect();
        format!("line {}", lines.join(", "))
    };
    let wavelengths: Vec<f64> = args.line.iter().map(|l| l.0).collect();
    let request = SpectrumRequest {
        spectrum: args.spectrum.clone().unwrap_or_else(label),
        lines: args.line.clone(),
        column: args.column.clone(),
        illuminant: args.illuminant.clone(),
        observer: args.observer,
        grid: describe::check_grid(args.bins, args.lambda_min, args.lambda_max, &wavelengths)?,
        cat: args.cat.into(),
    };
    let colour = describe::spectrum_colour(&request)?;
    outln!(
        "{}",
        if args.json {
            colour.to_json()
        } else {
            colour.to_text()
        }
    )?;
    Ok(ExitCode::SUCCESS)
}

/// `NM` or `NM:POWER`: a wavelength (finite, > 0) and a relative power (finite, >= 0).
fn parse_line(text: &str) -> Result<(f64, f64), String> {
    let (nm, power) = text.split_once(':').unwrap_or((text, "1"));
    let nm: f64 = nm
        .trim()
        .parse()
        .map_err(|_| format!("{nm:?} is not a wavelength in nm"))?;
    let power: f64 = power
        .trim()
        .parse()
        .map_err(|_| format!("{power:?} is not a power"))?;
    if !(nm.is_finite() && nm > 0.0) {
        return Err(format!(
            "a line's wavelength must be finite and > 0 nm, got {nm}"
        ));
    }
    if !(power.is_finite() && power >= 0.0) {
        return Err(format!(
            "a line's power must be finite and >= 0, got {power}"
        ));
    }
    Ok((nm, power))
}
