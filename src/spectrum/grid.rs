use super::{MAX_BINS, Spectrum};

/// Width of the narrow bin given to a spectral line, nm. A line's own power is weighted exactly
/// at its wavelength whatever the width (line bins hold values at the line, [`Bin::Line`]); the
/// width matters for continuous light falling in the same bin, weighted as at the line. Over
/// 0.1 nm the CIE 1931 colour-matching functions (1 nm table, piecewise linear) change by at
/// most 0.2 % of their peak for x-bar and y-bar (steepest slope 0.022 per nm) and 0.5 % for
/// z-bar (0.082 per nm), and linearly, so that error is far below visibility. Narrower gains
/// nothing and raises the density (per nm) a line's power becomes.
pub const LINE_WIDTH: f64 = 0.1;

/// Two distinct lines closer than this (nm) are refused: their bins would be too narrow to
/// hold a sensible density, and no film brume writes could tell them apart.
pub const MIN_LINE_SEPARATION: f64 = 0.01;

/// One spectral bin.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Bin {
    /// A band `[lo, hi]` nm: a quantity's value in it is its average over the band, so bin
    /// values times widths reproduce integrals.
    Band { lo: f64, hi: f64 },
    /// The narrow bin `[lo, hi]` holding the spectral line at `lambda`: reflectances,
    /// coefficients and colour-matching functions take their value at `lambda` (the line's
    /// light is all at that wavelength); the width only turns a line's power into the
    /// density (per nm) that transport carries.
    Line { lambda: f64, lo: f64, hi: f64 },
}

impl Bin {
    pub fn edges(&self) -> (f64, f64) {
        match *self {
            Bin::Band { lo, hi } | Bin::Line { lo, hi, .. } => (lo, hi),
        }
    }
}

/// How the bins are laid out.
#[derive(Clone, Debug, PartialEq)]
enum Layout {
    /// `n` equal bins with edges `lambda_min + i * width`: the arithmetic of every grid before
    /// lines existed, kept exactly so that scenes without lines render bit-identically.
    Uniform,
    /// `uniform` equal bins split around a narrow bin at each line (increasing, distinct).
    Lines {
        uniform: usize,
        lines: Vec<f64>,
        bins: Vec<Bin>,
    },
}

/// Why a grid with lines cannot be made.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum GridError {
    #[error("a line at {lambda} nm is not a wavelength (it must be finite and > 0)")]
    NotAWavelength { lambda: f64 },
    #[error(
        "a line at {lambda} nm is outside the film's range {min}-{max} nm: widen \
         film.lambda_min / film.lambda_max to include it, or remove the line"
    )]
    Outside { lambda: f64, min: f64, max: f64 },
    #[error(
        "lines at {a} and {b} nm are closer than {MIN_LINE_SEPARATION} nm: brume cannot give \
         them separate bins; merge them into one line"
    )]
    TooClose { a: f64, b: f64 },
    #[error(
        "the spectral grid would need {needed} bins ({uniform} equal bins split around \
         {lines} line(s)), above the {MAX_BINS} brume carries: use fewer equal bins or lines"
    )]
    TooManyBins {
        needed: usize,
        uniform: usize,
        lines: usize,
    },
}

/// The scene's spectral sampling: a list of bins covering `[lambda_min, lambda_max]` nm without
/// gaps or overlaps, in increasing wavelength. It starts as `film.bins` equal bins; each
/// spectral line gets a narrow bin of its own ([`LINE_WIDTH`]), the bin it falls in split
/// around it.
///
/// Light transport carries one value per bin; a band's value is the average of the spectral
/// quantity over it (not a point sample), so values times bin widths reproduce integrals.
/// Construct with [`SpectralGrid::new`] or [`SpectralGrid::with_lines`]; `n` is the number of
/// bins of either kind.
#[derive(Clone, Debug, PartialEq)]
pub struct SpectralGrid {
    pub n: usize,
    pub lambda_min: f64,
    pub lambda_max: f64,
    layout: Layout,
}

impl SpectralGrid {
    /// `n` equal bins. Panics only on programmer error; user input is validated by the scene
    /// loader first.
    pub fn new(n: usize, lambda_min: f64, lambda_max: f64) -> Self {
        assert!((1..=MAX_BINS).contains(&n) && lambda_max > lambda_min);
        Self {
            n,
            lambda_min,
            lambda_max,
            layout: Layout::Uniform,
        }
    }

    /// `uniform` equal bins over the range, plus a narrow bin at each line (nm, any order,
    /// repeats allowed). Without lines this is [`SpectralGrid::new`]. Panics on a bad
    /// `uniform` or range like `new`; bad lines and too many bins are errors.
    pub fn with_lines(
        uniform: usize,
        lambda_min: f64,
        lambda_max: f64,
        lines: &[f64],
    ) -> Result<Self, GridError> {
        let base = Self::new(uniform, lambda_min, lambda_max);
        let lines = checked_lines(lines, lambda_min, lambda_max)?;
        if lines.is_empty() {
            return Ok(base);
        }
        let bins = split_bins(&base, &lines);
        if bins.len() > MAX_BINS {
            return Err(GridError::TooManyBins {
                needed: bins.len(),
                uniform,
                lines: lines.len(),
            });
        }
        Ok(Self {
            n: bins.len(),
            lambda_min,
            lambda_max,
            layout: Layout::Lines {
                uniform,
                lines,
                bins,
            },
        })
    }

    /// The number of equal bins the grid started from (`film.bins`).
    pub fn uniform_bins(&self) -> usize {
        match &self.layout {
            Layout::Uniform => self.n,
            Layout::Lines { uniform, .. } => *uniform,
        }
    }

    /// The lines that have a bin of their own, increasing.
    pub fn lines(&self) -> &[f64] {
        match &self.layout {
            Layout::Uniform => &[],
            Layout::Lines { lines, .. } => lines,
        }
    }

    /// Width of each of the equal bins the grid started from.
    fn uniform_width(&self) -> f64 {
        (self.lambda_max - self.lambda_min) / self.uniform_bins() as f64
    }

    /// Bin `i`.
    pub fn bin(&self, i: usize) -> Bin {
        match &self.layout {
            Layout::Uniform => {
                let w = self.uniform_width();
                Bin::Band {
                    lo: self.lambda_min + w * i as f64,
                    hi: self.lambda_min + w * (i + 1) as f64,
                }
            }
            Layout::Lines { bins, .. } => bins[i],
        }
    }

    /// Lower and upper edge of bin `i` in nm.
    pub fn edges(&self, i: usize) -> (f64, f64) {
        self.bin(i).edges()
    }

    /// Width of bin `i` in nm (for equal bins, the range over the count, as always).
    pub fn bin_width(&self, i: usize) -> f64 {
        match &self.layout {
            Layout::Uniform => self.uniform_width(),
            Layout::Lines { bins, .. } => {
                let (lo, hi) = bins[i].edges();
                hi - lo
            }
        }
    }

    /// The wavelength that stands for bin `i`: a band's centre, or a line bin's line.
    pub fn centre(&self, i: usize) -> f64 {
        match self.bin(i) {
            Bin::Band { lo, hi } => 0.5 * (lo + hi),
            Bin::Line { lambda, .. } => lambda,
        }
    }

    pub fn centres(&self) -> Vec<f64> {
        (0..self.n).map(|i| self.centre(i)).collect()
    }

    /// The bin containing wavelength `lambda`, if any (the lower bin on a shared edge).
    pub fn bin_of(&self, lambda: f64) -> Option<usize> {
        if !(lambda >= self.lambda_min && lambda <= self.lambda_max) {
            return None;
        }
        match &self.layout {
            Layout::Uniform => {
                let i = ((lambda - self.lambda_min) / self.uniform_width()) as usize;
                Some(i.min(self.n - 1))
            }
            Layout::Lines { bins, .. } => {
                let i = bins.partition_point(|b| b.edges().1 < lambda);
                Some(i.min(self.n - 1))
            }
        }
    }

    /// The bin holding the line at `lambda`, if the grid has that line.
    pub fn line_bin(&self, lambda: f64) -> Option<usize> {
        let i = self.bin_of(lambda)?;
        match self.bin(i) {
            Bin::Line { lambda: l, .. } if l == lambda => Some(i),
            Bin::Line { .. } | Bin::Band { .. } => None,
        }
    }

    /// The integral over the range of a spectral density given as bin values:
    /// `sum_i s_i * width_i`.
    pub fn integral(&self, s: &Spectrum) -> f64 {
        match &self.layout {
            // The sum of all lanes times the common width, as every grid computed it before.
            Layout::Uniform => s.sum() as f64 * self.uniform_width(),
            Layout::Lines { .. } => (0..self.n).map(|i| s.0[i] as f64 * self.bin_width(i)).sum(),
        }
    }
}

impl SpectralGrid {
    /// `sum_i s_i * width_i / w` with `w` the equal bins' width: proportional to the integral
    /// of `s`, and on a grid without lines exactly the plain sum of the bins (the weight lights
    /// were always picked by, kept bit for bit). For choosing in proportion to power.
    pub fn weighted_sum(&self, s: &Spectrum) -> f64 {
        match &self.layout {
            Layout::Uniform => s.sum() as f64,
            Layout::Lines { .. } => {
                let w = self.uniform_width();
                (0..self.n)
                    .map(|i| s.0[i] as f64 * (self.bin_width(i) / w))
                    .sum()
            }
        }
    }
}

/// The distinct lines, increasing, after checking each lies in the range and no two distinct
/// ones are closer than [`MIN_LINE_SEPARATION`].
fn checked_lines(lines: &[f64], min: f64, max: f64) -> Result<Vec<f64>, GridError> {
    let mut out = Vec::with_capacity(lines.len());
    for &lambda in lines {
        if !(lambda.is_finite() && lambda > 0.0) {
            return Err(GridError::NotAWavelength { lambda });
        }
        if lambda < min || lambda > max {
            return Err(GridError::Outside { lambda, min, max });
        }
        out.push(lambda);
    }
    out.sort_by(f64::total_cmp);
    out.dedup();
    if let Some(w) = out.windows(2).find(|w| w[1] - w[0] < MIN_LINE_SEPARATION) {
        return Err(GridError::TooClose { a: w[0], b: w[1] });
    }
    Ok(out)
}

/// The bins of `base` (equal bins) split around a narrow bin at each line.
///
/// Each line's bin is `lambda ± LINE_WIDTH / 2`, clipped to the range. A gap narrower than
/// `eps` (half the smaller of the line width and the equal bins' width) between two line bins,
/// or between a line bin and the end of the range, goes to the line bins (they meet halfway or
/// reach the end), and an equal bin's edge within `eps` of a line bin is dropped, so no sliver
/// bins waste the bin budget. Every other equal edge is kept with its exact value.
fn split_bins(base: &SpectralGrid, lines: &[f64]) -> Vec<Bin> {
    let (min, max) = (base.lambda_min, base.lambda_max);
    let eps = 0.5 * LINE_WIDTH.min(base.uniform_width());
    let half = 0.5 * LINE_WIDTH;
    let mut spans: Vec<(f64, f64)> = lines
        .iter()
        .map(|&l| ((l - half).max(min), (l + half).min(max)))
        .collect();
    for k in 1..spans.len() {
        if spans[k].0 - spans[k - 1].1 < eps {
            let mid = 0.5 * (lines[k - 1] + lines[k]);
            (spans[k - 1].1, spans[k].0) = (mid, mid);
        }
    }
    let last = spans.len() - 1;
    if spans[0].0 - min < eps {
        spans[0].0 = min;
    }
    if max - spans[last].1 < eps {
        spans[last].1 = max;
    }
    let equal_edges: Vec<f64> = (1..base.n).map(|i| base.edges(i).0).collect();
    let mut bins = Vec::new();
    let mut start = min;
    for (&lambda, &(lo, hi)) in lines.iter().zip(&spans) {
        push_bands(&mut bins, &equal_edges, start, lo, eps);
        bins.push(Bin::Line { lambda, lo, hi });
        start = hi;
    }
    push_bands(&mut bins, &equal_edges, start, max, eps);
    bins
}

/// The bands covering `[from, to]` (nothing if empty), split at the equal edges inside it
/// farther than `eps` from both ends.
fn push_bands(bins: &mut Vec<Bin>, edges: &[f64], from: f64, to: f64, eps: f64) {
    if to <= from {
        return;
    }
    let mut lo = from;
    for &e in edges.iter().filter(|&&e| e > from + eps && e < to - eps) {
        bins.push(Bin::Band { lo, hi: e });
        lo = e;
    }
    bins.push(Bin::Band { lo, hi: to });
}

impl Default for SpectralGrid {
    /// 32 bins of 12.5 nm over 380-780 nm: the fewest (of 8/16/32/64) for which the 24
    /// ColorChecker patches under D65 and A stay within mean CIEDE2000 0.3 / max 1.0 of the
    /// 1 nm reference (docs/colour.md).
    fn default() -> Self {
        Self::new(32, 380.0, 780.0)
    }
}
