//! Prints, as JSON, the per-bin optics brume's droplet fog uses: a lognormal of water droplets
//! solved on a 3-bin grid whose bin centres are the requested wavelengths (each solved exactly
//! there), read back from the runtime medium's phase table. tests/python/test_mie.py compares
//! them with miepython.
//!
//! usage: mie_check [--r-eff UM] [--width SIGMA_G] [--density PER_CM3] [--lambda MIN,MAX]

use brume::medium::droplets::{DistributionKind, DropletsDesc, optics};
use brume::spectrum::SpectralGrid;

fn fail(msg: String) -> ! {
    eprintln!("mie_check: {msg}");
    std::process::exit(2)
}

fn main() {
    let (mut r_eff, mut width, mut density, mut range) = (5.0, 1.5, 100.0, (400.0, 700.0));
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        let v = args
            .next()
            .unwrap_or_else(|| fail(format!("{a} needs a value")));
        let num = |s: &str| {
            s.parse::<f64>()
                .unwrap_or_else(|_| fail(format!("{a}: bad number {s}")))
        };
        match a.as_str() {
            "--r-eff" => r_eff = num(&v),
            "--width" => width = num(&v),
            "--density" => density = num(&v),
            "--lambda" => {
                let (lo, hi) = v
                    .split_once(',')
                    .unwrap_or_else(|| fail("--lambda MIN,MAX".into()));
                range = (num(lo), num(hi));
            }
            _ => fail(format!("unknown argument {a}")),
        }
    }
    let desc = DropletsDesc {
        distribution: DistributionKind::Lognormal,
        effective_radius: r_eff,
        width: Some(width),
        alpha: None,
        gamma: None,
        number_density: Some(density),
        liquid_water_content: None,
        visibility: None,
        refractive_index: "water".into(),
        quadrature_step: brume::medium::droplets::DEFAULT_STEP,
    };
    let grid = SpectralGrid::new(3, range.0, range.1);
    let o = optics(&desc, &grid, &|f| f.into()).unwrap_or_else(|e| fail(e.to_string()));
    let angles = [0.0f64, 30.0, 90.0, 140.0, 180.0];
    let bins: Vec<serde_json::Value> = (0..grid.n)
        .map(|l| {
            let phase: Vec<f64> = angles
                .iter()
                .map(|a| o.table.eval_lane(l, a.to_radians().cos() as f32) as f64)
                .collect();
            serde_json::json!({
                "lambda_nm": grid.centre(l),
                "sigma_ext": o.sigma_ext[l],
                "sigma_sca": o.sigma_sca[l],
                "albedo": o.sigma_sca[l] / o.sigma_ext[l],
                "g": o.g[l],
                "table_g": o.table.g_lane(l),
                "phase": phase,
            })
        })
        .collect();
    let out = serde_json::json!({
        "effective_radius": r_eff,
        "width": width,
        "number_density": density,
        "angles": angles,
        "radii_per_wavelength": o.nodes,
        "bins": bins,
    });
    println!("{out}");
}
