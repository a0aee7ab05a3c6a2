//! Fits the sRGB sigmoid-polynomial coefficient table (Jakob & Hanika 2019) and writes it to
//! spectra/srgb-coefficients.bin, which brume ships so that no render pays for the fit.
//! Run: `cargo run --release --example make_rgb_table`.

use brume::colour::rgb::{CoefficientTable, FitContext};

fn main() -> std::process::ExitCode {
    let Some(ctx) = FitContext::srgb() else {
        eprintln!("make_rgb_table: the built-in colour data failed to load");
        return std::process::ExitCode::FAILURE;
    };
    let table = CoefficientTable::compute(ctx);
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/spectra/srgb-coefficients.bin");
    match std::fs::write(path, table.to_bytes()) {
        Ok(()) => {
            println!("wrote {path}");
            std::process::ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("make_rgb_table: {path}: {e}");
            std::process::ExitCode::FAILURE
        }
    }
}
