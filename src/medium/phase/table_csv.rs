//! Reading a tabulated phase function from CSV: angle in degrees, then one value column (the
//! same phase in every bin) or one column per wavelength (header: the wavelength in nm).

use std::path::Path;

use super::tabulated::PhaseTable;
use crate::medium::MediumError;
use crate::spectrum::{Bin, Extrapolation, PiecewiseLinear, SpectralGrid};

/// The parsed file: angles (degrees, strictly increasing from 0 to 180) and value columns.
#[derive(Clone, Debug, PartialEq)]
pub struct PhaseCsv {
    pub angles: Vec<f64>,
    /// Each column's wavelength (nm) when there are several, and its values by row.
    pub columns: Vec<(Option<f64>, Vec<f64>)>,
    /// Line of the header, for errors about whole columns.
    pub header_line: usize,
}

fn parse_err(file: &Path, line: usize, message: impl Into<String>) -> MediumError {
    MediumError::PhaseFile {
        file: file.to_path_buf(),
        line,
        message: message.into(),
    }
}

/// A column name as a wavelength: `550`, `550nm` or `550 nm`.
fn wavelength_of(name: &str) -> Option<f64> {
    let t = name.trim().trim_end_matches("nm").trim();
    t.parse::<f64>().ok().filter(|w| w.is_finite() && *w > 0.0)
}

/// Parses the text of `file`. Lines starting with `#` and blank lines are skipped; the first
/// other line is the header. Errors name the file and the 1-based line.
pub fn parse(text: &str, file: &Path) -> Result<PhaseCsv, MediumError> {
    let mut rows = text
        .lines()
        .enumerate()
        .map(|(i, l)| (i + 1, l.trim()))
        .filter(|(_, l)| !l.is_empty() && !l.starts_with('#'));
    let Some((header_line, header)) = rows.next() else {
        return Err(parse_err(file, 1, "empty file: expected a header line"));
    };
    let waves = parse_header(header, file, header_line)?;
    let mut angles: Vec<f64> = Vec::new();
    let mut cols: Vec<Vec<f64>> = vec![Vec::new(); waves.len()];
    let mut last_line = header_line;
    for (line, row) in rows {
        last_line = line;
        let nums = parse_row(row, waves.len() + 1, angles.last().copied())
            .map_err(|m| parse_err(file, line, m))?;
        angles.push(nums[0]);
        for (c, v) in cols.iter_mut().zip(&nums[1..]) {
            c.push(*v);
        }
    }
    if angles.len() < 2 {
        return Err(parse_err(
            file,
            last_line,
            format!("needs at least two rows of data, got {}", angles.len()),
        ));
    }
    let (first, last) = (angles[0], angles[angles.len() - 1]);
    if first != 0.0 || last != 180.0 {
        return Err(parse_err(
            file,
            last_line,
            format!(
                "the angles must cover the whole sphere, from 0 to 180 degrees (got {first} to \
                 {last})"
            ),
        ));
    }
    Ok(PhaseCsv {
        angles,
        columns: waves.into_iter().zip(cols).collect(),
        header_line,
    })
}

/// The value columns' wavelengths from the header: `None` for a single value column, else
/// each column's name read as a wavelength in nm (strictly increasing).
fn parse_header(header: &str, file: &Path, line: usize) -> Result<Vec<Option<f64>>, MediumError> {
    let names: Vec<&str> = header.split(',').map(str::trim).collect();
    if names.len() < 2 {
        return Err(parse_err(
            file,
            line,
            "the header needs an angle column and at least one value column",
        ));
    }
    if names.len() == 2 {
        return Ok(vec![None]);
    }
    let waves = names[1..]
        .iter()
        .enumerate()
        .map(|(k, n)| {
            // The file's text is never echoed (it may be any file): the column is named by
            // its position.
            wavelength_of(n).map(Some).ok_or_else(|| {
                let m = format!(
                    "with several value columns each must be named by its wavelength in nm; \
                     column {} is not",
                    k + 2
                );
                parse_err(file, line, m)
            })
        })
        .collect::<Result<Vec<_>, _>>()?;
    if waves.windows(2).any(|w| w[0] >= w[1]) {
        return Err(parse_err(file, line, "column wavelengths must increase"));
    }
    Ok(waves)
}

/// One data row: `width` finite numbers, the angle in [0, 180] and above `prev`, the values
/// non-negative.
fn parse_row(row: &str, width: usize, prev: Option<f64>) -> Result<Vec<f64>, String> {
    let cells: Vec<&str> = row.split(',').map(str::trim).collect();
    if cells.len() != width {
        return Err(format!("expected {width} values, got {}", cells.len()));
    }
    let nums = cells
        .iter()
        .enumerate()
        .map(|(k, c)| {
            c.parse::<f64>()
                .ok()
                .filter(|v| v.is_finite())
                .ok_or_else(|| format!("column {} is not a finite number", k + 1))
        })
        .collect::<Result<Vec<f64>, String>>()?;
    let angle = nums[0];
    if !(0.0..=180.0).contains(&angle) {
        return Err(format!("angle {angle} is outside [0, 180] degrees"));
    }
    if let Some(prev) = prev
        && angle <= prev
    {
        return Err(format!(
            "angles must increase strictly (got {angle} after {prev})"
        ));
    }
    if let Some(v) = nums[1..].iter().find(|v| **v < 0.0) {
        return Err(format!("negative phase value {v}"));
    }
    Ok(nums)
}

impl PhaseCsv {
    /// Parses CSV text (see [`parse`]); `file` names it in errors.
    pub fn parse(text: &str, file: &Path) -> Result<Self, MediumError> {
        parse(text, file)
    }

    /// The table for `grid`: one lane if the file has one value column, else one lane per bin,
    /// each the exact band average (a line bin: the value at its line) of the columns
    /// interpolated linearly in wavelength (held constant beyond the first and last column). Every column is a normalised phase after
    /// normalisation, so each bin's lane is a convex combination of them.
    pub fn table(&self, grid: &SpectralGrid, file: &Path) -> Result<PhaseTable, MediumError> {
        // Rows run from 0° to 180°, i.e. mu from 1 down to -1: reverse them.
        let mut mu: Vec<f64> = self
            .angles
            .iter()
            .rev()
            .map(|a| a.to_radians().cos())
            .collect();
        let last = mu.len() - 1;
        mu[0] = -1.0;
        mu[last] = 1.0;
        let at_header = |m: String| parse_err(file, self.header_line, m);
        if mu.windows(2).any(|w| w[0] >= w[1]) {
            return Err(at_header(
                "two angles are too close to tell apart in cos θ".into(),
            ));
        }
        let normalised: Vec<Vec<f64>> = self
            .columns
            .iter()
            .map(|(w, v)| {
                let rev: Vec<f64> = v.iter().rev().copied().collect();
                normalise(&mu, &rev).ok_or_else(|| {
                    let name = w.map_or("the value column".into(), |w| format!("column {w} nm"));
                    at_header(format!("{name} is zero at every angle"))
                })
            })
            .collect::<Result<_, _>>()?;
        let lanes = if normalised.len() == 1 {
            normalised
        } else {
            let waves: Vec<f64> = self.columns.iter().filter_map(|(w, _)| *w).collect();
            bin_lanes(&waves, &normalised, grid)
        };
        PhaseTable::new(mu, &lanes, file.display().to_string())
            .map_err(|e| at_header(e.to_string()))
    }
}

/// `v` scaled so that its piecewise-linear interpolant integrates to 1 over the sphere; `None`
/// if it integrates to 0.
fn normalise(mu: &[f64], v: &[f64]) -> Option<Vec<f64>> {
    let total: f64 = (1..mu.len())
        .map(|i| std::f64::consts::PI * (mu[i] - mu[i - 1]) * (v[i - 1] + v[i]))
        .sum();
    (total > 0.0).then(|| v.iter().map(|x| x / total).collect())
}

/// Per bin, the band average of the hat function of each column (or its value at a line bin's
/// line): the weight of that column in the bin's lane, applied to the columns.
fn bin_lanes(waves: &[f64], cols: &[Vec<f64>], grid: &SpectralGrid) -> Vec<Vec<f64>> {
    let weights: Vec<Vec<f64>> = (0..waves.len())
        .map(|c| {
            let hat: Vec<f64> = (0..waves.len())
                .map(|j| f64::from(u8::from(j == c)))
                .collect();
            let pl = PiecewiseLinear::new(waves.to_vec(), hat);
            (0..grid.n)
                .map(|b| match grid.bin(b) {
                    Bin::Band { lo, hi } => pl.integral(lo, hi, Extrapolation::Clamp) / (hi - lo),
                    Bin::Line { lambda, .. } => pl.eval(lambda, Extrapolation::Clamp),
                })
                .collect()
        })
        .collect();
    (0..grid.n)
        .map(|b| {
            (0..cols[0].len())
                .map(|i| (0..cols.len()).map(|c| weights[c][b] * cols[c][i]).sum())
                .collect()
        })
        .collect()
}

#[cfg(test)]
mod echo_tests {
    use super::*;

    /// Errors name the line and column, never the file's text (issue 31: a file named as a
    /// table could be any file).
    #[test]
    fn errors_do_not_echo_the_file() {
        let file = Path::new("t.csv");
        for text in [
            "angle,value\n0,secret-word\n",
            "angle,secret-word,550\n0,1,1\n",
        ] {
            let e = parse(text, file).expect_err("refused").to_string();
            assert!(!e.contains("secret"), "{e}");
            assert!(e.contains("column"), "{e}");
        }
    }
}
