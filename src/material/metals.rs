//! The named metals of the `conductor` material: complex refractive indices `n + ik` shipped in
//! spectra/metal_*.csv (sources in each file's header and in spectra/README.md), embedded in the
//! binary so that they work from any directory.

use crate::spectrum::{Extrapolation, SpectralGrid, SpectralTable, Spectrum, SpectrumError};

/// (name, file for messages, CSV text with columns `wavelength_nm`, `n`, `k`).
const METALS: &[(&str, &str, &str)] = &[
    (
        "aluminium",
        "spectra/metal_aluminium.csv",
        include_str!("../../spectra/metal_aluminium.csv"),
    ),
    (
        "silver",
        "spectra/metal_silver.csv",
        include_str!("../../spectra/metal_silver.csv"),
    ),
    (
        "gold",
        "spectra/metal_gold.csv",
        include_str!("../../spectra/metal_gold.csv"),
    ),
    (
        "copper",
        "spectra/metal_copper.csv",
        include_str!("../../spectra/metal_copper.csv"),
    ),
    (
        "chromium",
        "spectra/metal_chromium.csv",
        include_str!("../../spectra/metal_chromium.csv"),
    ),
    (
        "iron",
        "spectra/metal_iron.csv",
        include_str!("../../spectra/metal_iron.csv"),
    ),
];

/// The metal names a conductor's `eta` and `k` accept (case-insensitive).
pub fn metal_names() -> impl Iterator<Item = &'static str> {
    METALS.iter().map(|m| m.0)
}

pub fn is_metal(name: &str) -> bool {
    METALS.iter().any(|m| m.0.eq_ignore_ascii_case(name))
}

/// The metal's `(n, k)` averaged over each bin of `grid` (linear between the tabulated
/// wavelengths, the end values held beyond them); None for a name that is no metal.
pub fn metal_index(
    name: &str,
    grid: &SpectralGrid,
) -> Option<Result<(Spectrum, Spectrum), SpectrumError>> {
    let &(_, file, text) = METALS.iter().find(|m| m.0.eq_ignore_ascii_case(name))?;
    let spectra = || {
        let t = SpectralTable::parse(text, file, false)?;
        let n = t.column(Some("n"))?;
        let k = t.column(Some("k"))?;
        Ok((
            n.bin_averages(grid, Extrapolation::Clamp),
            k.bin_averages(grid, Extrapolation::Clamp),
        ))
    };
    Some(spectra())
}
