//! Spectral data shipped inside the binary (from `spectra/`), so brume works from any directory.

use std::path::Path;

use super::{PiecewiseLinear, SpectralTable, SpectrumError};

/// Built-in tables: (name, file name for messages, CSV text, may hold negative values).
const BUILTIN: &[(&str, &str, &str, bool)] = &[
    (
        "cie1931",
        "spectra/cie1931_2deg.csv",
        include_str!("../../spectra/cie1931_2deg.csv"),
        false,
    ),
    (
        "cie1964",
        "spectra/cie1964_10deg.csv",
        include_str!("../../spectra/cie1964_10deg.csv"),
        false,
    ),
    (
        "D65",
        "spectra/illuminant_D65.csv",
        include_str!("../../spectra/illuminant_D65.csv"),
        false,
    ),
    (
        "D50",
        "spectra/illuminant_D50.csv",
        include_str!("../../spectra/illuminant_D50.csv"),
        false,
    ),
    (
        "A",
        "spectra/illuminant_A.csv",
        include_str!("../../spectra/illuminant_A.csv"),
        false,
    ),
    (
        "F2",
        "spectra/illuminant_F2.csv",
        include_str!("../../spectra/illuminant_F2.csv"),
        false,
    ),
    (
        "F11",
        "spectra/illuminant_F11.csv",
        include_str!("../../spectra/illuminant_F11.csv"),
        false,
    ),
    (
        "LED-B1",
        "spectra/illuminant_LED-B1.csv",
        include_str!("../../spectra/illuminant_LED-B1.csv"),
        false,
    ),
    (
        "colorchecker",
        "spectra/colorchecker.csv",
        include_str!("../../spectra/colorchecker.csv"),
        false,
    ),
];

/// Names accepted by [`builtin_table`] (case-insensitive).
pub fn builtin_names() -> impl Iterator<Item = &'static str> {
    BUILTIN.iter().map(|b| b.0)
}

/// A built-in table by name, e.g. `"D65"`, `"cie1931"`, `"colorchecker"`.
pub fn builtin_table(name: &str) -> Option<Result<SpectralTable, SpectrumError>> {
    BUILTIN
        .iter()
        .find(|b| b.0.eq_ignore_ascii_case(name))
        .map(|&(_, file, text, neg)| SpectralTable::parse(text, file, neg))
}

/// Resolves a user's spectrum reference: a built-in name (`D65`, `colorchecker:dark_skin`,
/// `colorchecker:13`) or a CSV file path (`file.csv`, or `file.csv:column`). `column`, when
/// given, overrides a `:column` suffix. Negative values are refused unless `allow_negative`.
pub fn resolve(
    spec: &str,
    column: Option<&str>,
    allow_negative: bool,
) -> Result<PiecewiseLinear, SpectrumError> {
    let (base, suffix) = match spec.rsplit_once(':') {
        // A bare path that exists wins over a `path:column` reading (paths may contain ':').
        Some((b, c)) if !Path::new(spec).exists() && !c.contains('/') => (b, Some(c)),
        _ => (spec, None),
    };
    let column = column.or(suffix);
    if let Some(table) = builtin_table(base) {
        return table?.column(column);
    }
    let path = Path::new(base);
    if path.exists() {
        return SpectralTable::load(path, allow_negative)?.column(column);
    }
    Err(SpectrumError::Unknown(
        spec.to_string(),
        builtin_names().collect::<Vec<_>>().join(", "),
    ))
}
