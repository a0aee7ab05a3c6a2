//! Tabulated spectral data (CSV) and its exact reduction to bins.
//!
//! A table is read as piecewise-linear functions of wavelength; bin values are exact integrals
//! of those functions (no point sampling), so the only approximation left in brume's colour
//! pipeline is the bin count itself.

use std::path::Path;

use super::{Bin, MAX_BINS, SpectralGrid, Spectrum, SpectrumError};

/// What a piecewise-linear spectrum is worth outside its tabulated range.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Extrapolation {
    /// Zero outside the data (used for the colour-matching functions, which vanish there).
    Zero,
    /// The nearest end value (the default for user data, like colour-science's constant
    /// extrapolation, so a reflectance measured over 400-700 nm is not black at 390 nm).
    #[default]
    Clamp,
}

/// One spectral quantity as piecewise-linear data: strictly increasing wavelengths (nm).
#[derive(Clone, Debug, PartialEq)]
pub struct PiecewiseLinear {
    pub wavelengths: Vec<f64>,
    pub values: Vec<f64>,
}

impl PiecewiseLinear {
    /// `wavelengths` must be strictly increasing and as long as `values` (at least one point);
    /// tables from [`SpectralTable::parse`] are checked already.
    pub fn new(wavelengths: Vec<f64>, values: Vec<f64>) -> Self {
        debug_assert!(!values.is_empty() && wavelengths.len() == values.len());
        debug_assert!(wavelengths.windows(2).all(|w| w[0] < w[1]));
        Self {
            wavelengths,
            values,
        }
    }

    pub fn range(&self) -> (f64, f64) {
        (
            self.wavelengths[0],
            self.wavelengths[self.wavelengths.len() - 1],
        )
    }

    pub fn eval(&self, lambda: f64, ext: Extrapolation) -> f64 {
        let (lo, hi) = self.range();
        let w = &self.wavelengths;
        let v = &self.values;
        if lambda < lo || lambda > hi {
            return match ext {
                Extrapolation::Zero => 0.0,
                Extrapolation::Clamp if lambda < lo => v[0],
                Extrapolation::Clamp => v[v.len() - 1],
            };
        }
        if w.len() == 1 {
            return v[0];
        }
        let k = w.partition_point(|&x| x <= lambda).clamp(1, w.len() - 1);
        let t = (lambda - w[k - 1]) / (w[k] - w[k - 1]);
        v[k - 1] + t * (v[k] - v[k - 1])
    }

    /// Exact integral over `[a, b]` (a <= b) of the piecewise-linear function and its extension.
    pub fn integral(&self, a: f64, b: f64, ext: Extrapolation) -> f64 {
        if b <= a {
            return 0.0;
        }
        let (lo, hi) = self.range();
        let mut total = 0.0;
        if ext == Extrapolation::Clamp {
            let first = self.values[0];
            let last = self.values[self.values.len() - 1];
            total += first * (b.min(lo) - a).max(0.0);
            total += last * (b - a.max(hi)).max(0.0);
        }
        let (a, b) = (a.max(lo), b.min(hi));
        if b <= a {
            return total;
        }
        let w = &self.wavelengths;
        // First segment whose upper end lies above a.
        let start = w.partition_point(|&x| x <= a).max(1);
        for k in start..w.len() {
            let (s0, s1) = (w[k - 1].max(a), w[k].min(b));
            if s1 > s0 {
                // The trapezoid rule is exact on a linear segment.
                total += 0.5 * (s1 - s0) * (self.eval(s0, ext) + self.eval(s1, ext));
            }
            if w[k] >= b {
                break;
            }
        }
        total
    }

    /// Exact integral over each bin of `grid`, in bin order; a line bin's is the value at
    /// its line times its width (see [`Bin::Line`]).
    pub fn bin_integrals(&self, grid: &SpectralGrid, ext: Extrapolation) -> Vec<f64> {
        (0..grid.n)
            .map(|i| match grid.bin(i) {
                Bin::Band { lo, hi } => self.integral(lo, hi, ext),
                Bin::Line { lambda, lo, hi } => self.eval(lambda, ext) * (hi - lo),
            })
            .collect()
    }

    /// The value light transport carries in each bin: the exact average over a band, the
    /// value at the line in a line bin.
    pub fn bin_averages(&self, grid: &SpectralGrid, ext: Extrapolation) -> Spectrum {
        let mut s = Spectrum::ZERO;
        for i in 0..grid.n.min(MAX_BINS) {
            s.0[i] = match grid.bin(i) {
                Bin::Band { lo, hi } => self.integral(lo, hi, ext) / grid.bin_width(i),
                Bin::Line { lambda, .. } => self.eval(lambda, ext),
            } as f32;
        }
        s
    }
}

/// A parsed CSV table: a `wavelength_nm` column and one or more named data columns.
#[derive(Clone, Debug)]
pub struct SpectralTable {
    /// File name or built-in name, for messages.
    pub source: String,
    pub wavelengths: Vec<f64>,
    pub columns: Vec<(String, Vec<f64>)>,
}

impl SpectralTable {
    /// Parses CSV text: `#` comment lines and blank lines are skipped; the first other line is
    /// the header, whose first column must be `wavelength_nm`; every later line holds one
    /// wavelength and one value per column. Wavelengths must be strictly increasing, values
    /// finite, and non-negative unless `allow_negative`.
    pub fn parse(text: &str, source: &str, allow_negative: bool) -> Result<Self, SpectrumError> {
        let perr = |line: usize, message: String| SpectrumError::Parse {
            file: source.to_string(),
            line,
            message,
        };
        let mut lines = text
            .lines()
            .enumerate()
            .map(|(i, l)| (i + 1, l.trim()))
            .filter(|(_, l)| !l.is_empty() && !l.starts_with('#'));
        let (hline, header) = lines.next().ok_or_else(|| SpectrumError::Data {
            file: source.to_string(),
            message: "empty file: expected a header row `wavelength_nm,<column>,...`".into(),
        })?;
        let names: Vec<String> = header.split(',').map(|s| s.trim().to_string()).collect();
        if !names[0].eq_ignore_ascii_case("wavelength_nm") {
            // The line is not quoted: a path named by mistake (a scene's or a `--set`'s) must
            // not have its first line printed.
            return Err(perr(
                hline,
                "not a spectrum table: its first line (after comments) must be the header \
                 `wavelength_nm,<column>,...` (wavelengths in nanometres)"
                    .into(),
            ));
        }
        if names.len() < 2 || names[1..].iter().any(|n| n.is_empty()) {
            return Err(perr(
                hline,
                "header needs at least one named data column".into(),
            ));
        }
        let ncol = names.len() - 1;
        let mut wavelengths = Vec::new();
        let mut data = vec![Vec::new(); ncol];
        for (lno, line) in lines {
            let row = parse_row(line, &names, allow_negative).map_err(|m| perr(lno, m))?;
            let lambda = row[0];
            if lambda <= 0.0 {
                return Err(perr(
                    lno,
                    format!("wavelength {lambda} nm must be positive"),
                ));
            }
            if let Some(&prev) = wavelengths.last().filter(|&&p| lambda <= p) {
                return Err(perr(
                    lno,
                    format!(
                        "wavelengths must be strictly increasing: {lambda} nm follows {prev} nm"
                    ),
                ));
            }
            wavelengths.push(lambda);
            for (d, v) in data.iter_mut().zip(&row[1..]) {
                d.push(*v);
            }
        }
        if wavelengths.len() < 2 {
            return Err(SpectrumError::Data {
                file: source.to_string(),
                message: "needs at least two data rows".into(),
            });
        }
        Ok(Self {
            source: source.to_string(),
            wavelengths,
            columns: names[1..].iter().cloned().zip(data).collect(),
        })
    }

    pub fn load(path: &Path, allow_negative: bool) -> Result<Self, SpectrumError> {
        let text = std::fs::read_to_string(path).map_err(|source| SpectrumError::Io {
            path: path.to_path_buf(),
            source,
        })?;
        Self::parse(&text, &path.display().to_string(), allow_negative)
    }

    /// A column by name, or by 1-based index given as a number; `None` means the first.
    pub fn column(&self, name: Option<&str>) -> Result<PiecewiseLinear, SpectrumError> {
        let idx = match name {
            None => Some(0),
            Some(n) => self
                .columns
                .iter()
                .position(|(c, _)| c.eq_ignore_ascii_case(n))
                .or_else(|| {
                    n.parse::<usize>()
                        .ok()
                        .filter(|&k| (1..=self.columns.len()).contains(&k))
                        .map(|k| k - 1)
                }),
        };
        let idx = idx.ok_or_else(|| SpectrumError::NoColumn {
            file: self.source.clone(),
            column: name.unwrap_or_default().to_string(),
            available: self
                .columns
                .iter()
                .map(|(c, _)| c.as_str())
                .collect::<Vec<_>>()
                .join(", "),
        })?;
        Ok(PiecewiseLinear::new(
            self.wavelengths.clone(),
            self.columns[idx].1.clone(),
        ))
    }

    pub fn column_names(&self) -> impl Iterator<Item = &str> {
        self.columns.iter().map(|(c, _)| c.as_str())
    }
}
/// One data row of a table: the wavelength and one finite value per column (non-negative
/// unless allowed).
fn parse_row(line: &str, names: &[String], allow_negative: bool) -> Result<Vec<f64>, String> {
    let fields: Vec<&str> = line.split(',').map(str::trim).collect();
    if fields.len() != names.len() {
        return Err(format!(
            "expected {} fields, found {}",
            names.len(),
            fields.len()
        ));
    }
    // Fields are named by their column (from the header, which made this file a spectrum
    // table), never quoted: a file's content is not echoed in messages.
    let mut row = Vec::with_capacity(names.len());
    for (f, name) in fields.iter().zip(names) {
        let v: f64 = f
            .parse()
            .map_err(|_| format!("column {name:?}: the value is not a number"))?;
        if !v.is_finite() {
            return Err(format!("column {name:?}: the value is not finite"));
        }
        if !row.is_empty() && v < 0.0 && !allow_negative {
            return Err(format!(
                "column {name:?}: a negative value is not allowed here"
            ));
        }
        row.push(v);
    }
    Ok(row)
}
