//! `reference.bin`, brume's own exact reference format: `BRUMEREF` (8 bytes), then
//! little-endian u32 version (1), u32 width, u32 height, u32 bins, f64 lambda_min,
//! f64 lambda_max, u64 passes, f64 seconds, then four f32 arrays of width * height * bins values
//! in the film's layout: total, medium, surface, noise. Version 2 (written only for a spectral
//! grid with lines) puts u32 equal bins, u32 line count and the lines (f64 each) before the
//! arrays.

use std::path::Path;

use super::{Layers, Reference, Values};
use crate::spectrum::{MAX_BINS, SpectralGrid};
use crate::study::{StudyError, io_err};

pub const REFERENCE_MAGIC: &[u8; 8] = b"BRUMEREF";
const VERSION: u32 = 1;
const VERSION_LINES: u32 = 2;
const HEADER: usize = 56;

impl Reference {
    /// Writes `reference.bin` (atomically). Only spectral references have this format; missing
    /// layers and noise are written as zeros.
    pub fn save(&self, path: &Path) -> Result<(), StudyError> {
        let Values::Spectral(grid) = &self.values else {
            return Err(io_err(
                path,
                "an RGB reference cannot be saved as reference.bin",
            ));
        };
        let zeros = vec![0.0f32; self.total.len()];
        let (medium, surface) = match &self.layers {
            Some(l) => (&l.medium, &l.surface),
            None => (&zeros, &zeros),
        };
        let noise = self.noise.as_ref().unwrap_or(&zeros);
        let mut b = Vec::with_capacity(HEADER + 16 * self.total.len());
        b.extend_from_slice(REFERENCE_MAGIC);
        let lines = grid.lines();
        let version = if lines.is_empty() {
            VERSION
        } else {
            VERSION_LINES
        };
        for v in [
            version,
            self.width as u32,
            self.height as u32,
            grid.n as u32,
        ] {
            b.extend_from_slice(&v.to_le_bytes());
        }
        for v in [grid.lambda_min, grid.lambda_max] {
            b.extend_from_slice(&v.to_le_bytes());
        }
        b.extend_from_slice(&self.passes.to_le_bytes());
        b.extend_from_slice(&self.seconds.to_le_bytes());
        if !lines.is_empty() {
            for v in [grid.uniform_bins(), lines.len()] {
                b.extend_from_slice(&(v as u32).to_le_bytes());
            }
            lines
                .iter()
                .for_each(|l| b.extend_from_slice(&l.to_le_bytes()));
        }
        for arr in [&self.total, medium, surface, noise] {
            for v in arr.iter() {
                b.extend_from_slice(&v.to_le_bytes());
            }
        }
        crate::film::atomic::replace(path, |tmp| std::fs::write(tmp, &b))
            .map_err(|e| io_err(path, e))
    }

    /// Reads `reference.bin`.
    pub fn load(path: &Path) -> Result<Self, StudyError> {
        let bytes = std::fs::read(path).map_err(|e| io_err(path, e))?;
        let bad = |m: &str| StudyError::Reference {
            path: path.to_path_buf(),
            message: m.to_string(),
        };
        if bytes.len() < HEADER || &bytes[..8] != REFERENCE_MAGIC {
            return Err(bad("not a brume reference: missing BRUMEREF header"));
        }
        let u32_at = |o: usize| u32::from_le_bytes(bytes[o..o + 4].try_into().unwrap_or([0; 4]));
        let u64_at = |o: usize| u64::from_le_bytes(bytes[o..o + 8].try_into().unwrap_or([0; 8]));
        let version = u32_at(8);
        if version != VERSION && version != VERSION_LINES {
            return Err(bad("unknown version"));
        }
        let (width, height, n) = (
            u32_at(12) as usize,
            u32_at(16) as usize,
            u32_at(20) as usize,
        );
        let (lambda_min, lambda_max) = (f64::from_bits(u64_at(24)), f64::from_bits(u64_at(32)));
        let sane_range =
            lambda_min.is_finite() && lambda_max.is_finite() && lambda_max > lambda_min;
        if n == 0 || n > MAX_BINS || width == 0 || height == 0 || !sane_range {
            return Err(bad("bad image size or spectral range"));
        }
        // Version 2: the equal bins and the lines, which make the grid's `n` bins.
        let (uniform, nlines) = match version {
            VERSION_LINES if bytes.len() >= HEADER + 8 => {
                (u32_at(HEADER) as usize, u32_at(HEADER + 4) as usize)
            }
            VERSION_LINES => return Err(bad("truncated header")),
            _ => (n, 0),
        };
        let start = if version == VERSION {
            HEADER
        } else {
            HEADER + 8 + 8 * nlines.min(MAX_BINS)
        };
        if nlines > MAX_BINS || bytes.len() < start || !(1..=MAX_BINS).contains(&uniform) {
            return Err(bad("bad spectral grid"));
        }
        let lines: Vec<f64> = (0..nlines)
            .map(|k| f64::from_bits(u64_at(HEADER + 8 + 8 * k)))
            .collect();
        let grid = SpectralGrid::with_lines(uniform, lambda_min, lambda_max, &lines)
            .ok()
            .filter(|g| g.n == n)
            .ok_or_else(|| bad("bad spectral grid"))?;
        let count = width
            .checked_mul(height)
            .and_then(|p| p.checked_mul(n))
            .ok_or_else(|| bad("bad image size"))?;
        if Some(bytes.len()) != count.checked_mul(16).map(|b| b + start) {
            return Err(bad("truncated or oversized data"));
        }
        let arr = |k: usize| -> Vec<f32> {
            let start = start + 4 * count * k;
            bytes[start..start + 4 * count]
                .chunks_exact(4)
                .map(|c| f32::from_le_bytes([c[0], c[1], c[2], c[3]]))
                .collect()
        };
        Ok(Self {
            width,
            height,
            values: Values::Spectral(grid),
            passes: u64_at(40),
            seconds: f64::from_bits(u64_at(48)),
            total: arr(0),
            layers: Some(Layers {
                medium: arr(1),
                surface: arr(2),
            }),
            noise: Some(arr(3)),
            notes: Vec::new(),
        })
    }
}
