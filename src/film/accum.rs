//! Accumulation of pass estimates: running sums per pixel and bin (f64, so thousands of passes
//! lose nothing), sums of squares for a noise estimate, and the component layers.

use rayon::prelude::*;

use crate::spectrum::SpectralGrid;

use super::SpectralImage;

/// The components a pass estimate is split into (the paper compares them separately).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Layer {
    /// The medium's own luminance (gathered by integration volumes).
    Medium = 0,
    /// Surfaces (and emitters) seen directly or through the medium.
    Surface = 1,
}

pub const LAYERS: usize = 2;

/// One pass's estimate per layer, pixel and bin, in radiance units.
#[derive(Clone, Debug)]
pub struct PassBuffer {
    pub pixels: usize,
    pub n: usize,
    /// `[layer][pixel][bin]`.
    pub data: Vec<f32>,
}

impl PassBuffer {
    pub fn new(pixels: usize, n: usize) -> Self {
        Self {
            pixels,
            n,
            data: vec![0.0; LAYERS * pixels * n],
        }
    }

    #[inline]
    pub fn slot(&mut self, layer: Layer, pixel: usize) -> &mut [f32] {
        let i = (layer as usize * self.pixels + pixel) * self.n;
        &mut self.data[i..i + self.n]
    }

    /// Adds `other` elementwise; the order of calls fixes the floating-point result.
    pub fn add(&mut self, other: &PassBuffer) {
        self.data
            .par_chunks_mut(1 << 14)
            .zip(other.data.par_chunks(1 << 14))
            .for_each(|(a, b)| a.iter_mut().zip(b).for_each(|(x, y)| *x += *y));
    }

    pub fn scale(&mut self, s: f32) {
        self.data.par_iter_mut().for_each(|x| *x *= s);
    }
}

/// The film: pass estimates averaged, with per-pixel statistics across passes.
#[derive(Clone, Debug)]
pub struct Film {
    pub width: usize,
    pub height: usize,
    pub grid: SpectralGrid,
    pub passes: u64,
    /// `[layer][pixel][bin]` sums of pass estimates.
    pub sum: Vec<f64>,
    /// `[pixel][bin]` sums of squared total pass estimates.
    pub sum_sq: Vec<f64>,
    /// Samples dropped because they were not finite.
    pub dropped: u64,
}

impl Film {
    pub fn new(width: usize, height: usize, grid: SpectralGrid) -> Self {
        let px = width * height * grid.n;
        Self {
            width,
            height,
            grid,
            passes: 0,
            sum: vec![0.0; LAYERS * px],
            sum_sq: vec![0.0; px],
            dropped: 0,
        }
    }

    pub fn add_pass(&mut self, pass: &PassBuffer) {
        let px = self.width * self.height * self.grid.n;
        let (medium, surface) = pass.data.split_at(px);
        let (sum_m, sum_s) = self.sum.split_at_mut(px);
        let mut dropped = 0u64;
        for i in 0..px {
            let (m, s) = (medium[i] as f64, surface[i] as f64);
            if !(m.is_finite() && s.is_finite()) {
                dropped += 1;
                continue;
            }
            sum_m[i] += m;
            sum_s[i] += s;
            self.sum_sq[i] += (m + s) * (m + s);
        }
        self.dropped += dropped;
        self.passes += 1;
    }

    /// The mean over passes, its standard error, and the two component layers.
    pub fn image(&self) -> SpectralImage {
        let px = self.width * self.height * self.grid.n;
        let p = self.passes.max(1) as f64;
        let mut img = SpectralImage::new(self.width, self.height, self.grid);
        let (sum_m, sum_s) = self.sum.split_at(px);
        let mut noise = vec![0.0f32; px];
        for i in 0..px {
            let total = sum_m[i] + sum_s[i];
            let mean = total / p;
            img.data[i] = mean as f32;
            if self.passes > 1 {
                let var = ((self.sum_sq[i] - p * mean * mean) / (p - 1.0)).max(0.0);
                noise[i] = (var / p).sqrt() as f32;
            }
        }
        img.noise = Some(noise);
        img.layers = vec![
            (
                "medium".into(),
                sum_m.iter().map(|v| (v / p) as f32).collect(),
            ),
            (
                "surface".into(),
                sum_s.iter().map(|v| (v / p) as f32).collect(),
            ),
        ];
        img
    }
}
