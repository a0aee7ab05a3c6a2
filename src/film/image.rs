use crate::spectrum::SpectralGrid;

/// A finished spectral image: per pixel and bin, radiance in W / (m^2 sr nm), bin-averaged.
///
/// Row-major, top row first; `data[(y * width + x) * grid.n + bin]`. Extra named layers (such
/// as the medium's own luminance and the surfaces seen through it) share the layout.
#[derive(Clone, Debug)]
pub struct SpectralImage {
    pub width: usize,
    pub height: usize,
    pub grid: SpectralGrid,
    pub data: Vec<f32>,
    /// Per pixel and bin: standard error of the pixel mean, when known.
    pub noise: Option<Vec<f32>>,
    pub layers: Vec<(String, Vec<f32>)>,
}

impl SpectralImage {
    pub fn new(width: usize, height: usize, grid: SpectralGrid) -> Self {
        Self {
            width,
            height,
            data: vec![0.0; width * height * grid.n],
            grid,
            noise: None,
            layers: Vec::new(),
        }
    }

    pub fn pixel(&self, x: usize, y: usize) -> &[f32] {
        let n = self.grid.n;
        let i = (y * self.width + x) * n;
        &self.data[i..i + n]
    }
}
