//! The reference image a study measures against, kept exactly (f32 per pixel and bin, total and
//! both layers) in brume's own little binary format:
//!
//! `BRUMEREF` (8 bytes), then little-endian u32 version (1), u32 width, u32 height, u32 bins,
//! f64 lambda_min, f64 lambda_max, u64 passes, f64 seconds, then four f32 arrays of
//! width * height * bins values in the film's layout: total, medium, surface, noise. Version 2
//! (written only for a spectral grid with lines) puts u32 equal bins, u32 line count and the
//! lines (f64 each) before the arrays.

use std::io::{Read, Write};
use std::path::Path;

use super::{StudyError, io_err};
use crate::film::SpectralImage;
use crate::spectrum::{MAX_BINS, SpectralGrid};

pub const REFERENCE_MAGIC: &[u8; 8] = b"BRUMEREF";
const VERSION: u32 = 1;
const VERSION_LINES: u32 = 2;

#[derive(Clone, Debug, PartialEq)]
pub struct Reference {
    pub width: usize,
    pub height: usize,
    pub grid: SpectralGrid,
    pub passes: u64,
    pub seconds: f64,
    pub total: Vec<f32>,
    pub medium: Vec<f32>,
    pub surface: Vec<f32>,
    pub noise: Vec<f32>,
}

/// A named layer of the image, or zeros when the image lacks it.
pub(crate) fn layer<'a>(img: &'a SpectralImage, name: &str) -> Option<&'a [f32]> {
    img.layers
        .iter()
        .find(|(n, _)| n == name)
        .map(|(_, l)| l.as_slice())
}

impl Reference {
    pub fn from_image(img: &SpectralImage, passes: u64, seconds: f64) -> Self {
        let zeros = vec![0.0; img.data.len()];
        Self {
            width: img.width,
            height: img.height,
            grid: img.grid.clone(),
            passes,
            seconds,
            total: img.data.clone(),
            medium: layer(img, "medium").map_or(zeros.clone(), |l| l.to_vec()),
            surface: layer(img, "surface").map_or(zeros.clone(), |l| l.to_vec()),
            noise: img.noise.clone().unwrap_or(zeros),
        }
    }

    /// "W x H x N bins" for messages.
    pub fn shape(&self) -> String {
        format!("{} x {} x {} bins", self.width, self.height, self.grid.n)
    }

    /// Mean squared standard error of the reference: the floor its own noise adds to every
    /// measured MSE.
    pub fn noise_mse(&self) -> f64 {
        if self.noise.is_empty() {
            return 0.0;
        }
        self.noise.iter().map(|&v| (v as f64).powi(2)).sum::<f64>() / self.noise.len() as f64
    }

    pub fn save(&self, path: &Path) -> Result<(), StudyError> {
        let mut b = Vec::with_capacity(56 + 16 * self.total.len());
        b.extend_from_slice(REFERENCE_MAGIC);
        let lines = self.grid.lines();
        for v in [
            if lines.is_empty() {
                VERSION
            } else {
                VERSION_LINES
            },
            self.width as u32,
            self.height as u32,
            self.grid.n as u32,
        ] {
            b.extend_from_slice(&v.to_le_bytes());
        }
        b.extend_from_slice(&self.grid.lambda_min.to_le_bytes());
        b.extend_from_slice(&self.grid.lambda_max.to_le_bytes());
        b.extend_from_slice(&self.passes.to_le_bytes());
        b.extend_from_slice(&self.seconds.to_le_bytes());
        if !lines.is_empty() {
            b.extend_from_slice(&(self.grid.uniform_bins() as u32).to_le_bytes());
            b.extend_from_slice(&(lines.len() as u32).to_le_bytes());
            lines
                .iter()
                .for_each(|l| b.extend_from_slice(&l.to_le_bytes()));
        }
        for arr in [&self.total, &self.medium, &self.surface, &self.noise] {
            for v in arr.iter() {
                b.extend_from_slice(&v.to_le_bytes());
            }
        }
        let tmp = path.with_extension("tmp");
        let mut f = std::fs::File::create(&tmp).map_err(|e| io_err(&tmp, e))?;
        f.write_all(&b).map_err(|e| io_err(&tmp, e))?;
        drop(f);
        std::fs::rename(&tmp, path).map_err(|e| io_err(path, e))
    }

    pub fn load(path: &Path) -> Result<Self, StudyError> {
        let mut bytes = Vec::new();
        std::fs::File::open(path)
            .and_then(|mut f| f.read_to_end(&mut bytes))
            .map_err(|e| io_err(path, e))?;
        let bad = |m: &str| StudyError::Reference {
            path: path.to_path_buf(),
            message: m.to_string(),
        };
        if bytes.len() < 56 || &bytes[..8] != REFERENCE_MAGIC {
            return Err(bad("missing BRUMEREF header"));
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
        if n == 0 || n > crate::spectrum::MAX_BINS || width == 0 || height == 0 {
            return Err(bad("bad image size"));
        }
        let (lambda_min, lambda_max) = (f64::from_bits(u64_at(24)), f64::from_bits(u64_at(32)));
        if !(lambda_min.is_finite() && lambda_max.is_finite() && lambda_max > lambda_min) {
            return Err(bad("bad spectral range"));
        }
        // Version 2: the equal bins and the lines, which make the grid's `n` bins.
        let (uniform, nlines) = match version {
            VERSION_LINES if bytes.len() >= 64 => (u32_at(56) as usize, u32_at(60) as usize),
            VERSION_LINES => return Err(bad("truncated header")),
            _ => (n, 0),
        };
        let start = if version == VERSION {
            56
        } else {
            64 + 8 * nlines.min(MAX_BINS)
        };
        if nlines > MAX_BINS || bytes.len() < start || !(1..=MAX_BINS).contains(&uniform) {
            return Err(bad("bad spectral grid"));
        }
        let lines: Vec<f64> = (0..nlines)
            .map(|k| f64::from_bits(u64_at(64 + 8 * k)))
            .collect();
        let grid = SpectralGrid::with_lines(uniform, lambda_min, lambda_max, &lines)
            .ok()
            .filter(|g| g.n == n)
            .ok_or_else(|| bad("bad spectral grid"))?;
        let passes = u64_at(40);
        let seconds = f64::from_bits(u64_at(48));
        let count = width
            .checked_mul(height)
            .and_then(|p| p.checked_mul(n))
            .ok_or_else(|| bad("bad image size"))?;
        if bytes.len() != start + 16 * count {
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
            grid,
            passes,
            seconds,
            total: arr(0),
            medium: arr(1),
            surface: arr(2),
            noise: arr(3),
        })
    }
}
