//! `brume probe`: luminance and its noise read back from an EXR output, at a pixel or as the
//! mean over a region.

use std::path::PathBuf;
use std::process::ExitCode;

use clap::Args;
use serde_json::json;

use brume::film::output::Units;
use brume::film::output::probe::{self, ProbeImage};

#[derive(Args, Clone, Debug)]
#[command(group = clap::ArgGroup::new("at").required(true).args(["px", "region"]))]
pub struct ProbeArgs {
    /// An EXR written by `brume render` or `brume merge`.
    pub image: PathBuf,
    /// One pixel: column X, row Y (row 0 at the top).
    #[arg(long, value_name = "X,Y")]
    pub px: Option<String>,
    /// The mean over pixels X0 <= x < X1, Y0 <= y < Y1.
    #[arg(long, value_name = "X0,Y0,X1,Y1")]
    pub region: Option<String>,
    /// Print JSON instead of text.
    #[arg(long)]
    pub json: bool,
}

/// `n` comma-separated pixel coordinates.
fn coords(text: &str, n: usize, flag: &str) -> anyhow::Result<Vec<usize>> {
    let v: Vec<usize> = text
        .split(',')
        .map(|t| t.trim().parse::<usize>())
        .collect::<Result<_, _>>()
        .map_err(|_| {
            anyhow::anyhow!("{flag} {text}: expected {n} whole numbers separated by commas")
        })?;
    anyhow::ensure!(
        v.len() == n,
        "{flag} {text}: expected {n} numbers, got {}",
        v.len()
    );
    Ok(v)
}

/// What the Y of the file is in, in words, and the factor to cd/m² when known.
fn units(img: &ProbeImage) -> (String, Option<f64>) {
    match (img.units, img.white_luminance) {
        (Some(Units::Photometric), _) => ("luminance in cd/m2 (photometric EXR)".into(), Some(1.0)),
        (Some(Units::Radiometric), Some(k)) => (
            format!("Y of a radiometric EXR (film units; x {k:.1} for cd/m2, its whiteLuminance)"),
            Some(k),
        ),
        (Some(Units::Radiometric), None) | (None, _) => (
            "Y as the file holds it (no brume units attribute: not known to be cd/m2)".into(),
            None,
        ),
    }
}

pub fn run(args: &ProbeArgs) -> anyhow::Result<ExitCode> {
    let img = probe::read(&args.image)?;
    let region = match (&args.px, &args.region) {
        (Some(p), _) => {
            let v = coords(p, 2, "--px")?;
            [v[0], v[1], v[0] + 1, v[1] + 1]
        }
        (None, Some(r)) => {
            let v = coords(r, 4, "--region")?;
            [v[0], v[1], v[2], v[3]]
        }
        (None, None) => anyhow::bail!("give --px X,Y or --region X0,Y0,X1,Y1"),
    };
    let Some(m) = img.region(region) else {
        anyhow::bail!(
            "{}: region {:?} is empty or outside the {}x{} image",
            args.image.display(),
            region,
            img.width,
            img.height
        );
    };
    if m.non_finite > 0 {
        eprintln!(
            "brume: warning: {}: {} of the region's {} pixels are NaN or infinite (in Y or its \
             standard error): left out of the statistics",
            args.image.display(),
            m.non_finite,
            m.non_finite + m.pixels
        );
    }
    // With no finite pixel there is nothing to report: a NaN printed with success would be
    // read as an answer.
    anyhow::ensure!(
        m.pixels > 0,
        "{}: every pixel of region {:?} is NaN or infinite: no statistics",
        args.image.display(),
        region
    );
    let (what, to_cd) = units(&img);
    if args.json {
        let v = json!({
            "image": args.image,
            "region": region,
            "pixels": m.pixels,
            "non_finite_pixels": m.non_finite,
            "units": what,
            "mean": m.mean,
            "std_error": m.std_error,
            "std_error_is_lower_bound": m.pixels > 1,
            "luminance_cd_m2": to_cd.map(|k| m.mean * k),
            "luminance_std_error_cd_m2": to_cd.zip(m.std_error).map(|(k, e)| e * k),
        });
        outln!("{}", serde_json::to_string_pretty(&v)?)?;
        return Ok(ExitCode::SUCCESS);
    }
    let [x0, y0, x1, y1] = region;
    outln!("{}: {what}", args.image.display())?;
    outln!("pixels {x0}..{x1} x {y0}..{y1} ({} pixels)", m.pixels)?;
    outln!("mean        {:.6}", m.mean)?;
    match m.std_error {
        Some(e) if m.pixels > 1 => outln!(
            "std error   {e:.6}  LOWER BOUND: the noise layer with the pixels taken as \
             independent, but the pixels of a pass share its forward rays, so the error of \
             their mean can be several times larger (8x measured); a luminance sensor on the \
             region ([[sensors]]) gives its exact error"
        )?,
        Some(e) => outln!("std error   {e:.6}  (from the noise layer)")?,
        None => {
            outln!("std error   unknown: no noise layer (render with film.noise_layer = true)")?
        }
    }
    if let Some(k) = to_cd.filter(|k| *k != 1.0) {
        outln!("luminance   {:.6} cd/m2", m.mean * k)?;
    }
    Ok(ExitCode::SUCCESS)
}
