//! Accumulation of pass estimates: running sums per pixel and bin, sums of squares for a noise
//! estimate, and the component layers.
//!
//! The sums are fixed-point integers (`i128`), not floats: integer addition is associative, so
//! the film of passes 0..N is bit-identical whether the passes were added in one run, resumed
//! from a checkpoint, or rendered as slices on several machines and merged in any order
//! (see docs/distributed.md). Wrapping addition keeps that property even when an intermediate
//! sum overflows; only the final sums must fit, which they do for any finite image brume can
//! produce (|total| < 2^63 in radiance units).

use rayon::prelude::*;

use crate::spectrum::SpectralGrid;

use super::blend::{Blend, BlendSums};
use super::fixed::{MAX_SAMPLE, SQ_SCALE, SUM_SCALE, to_fixed};
use super::layer::LAYERS;
use super::sensor::{self, FilmExtras, SensorKind, SensorReading};
use super::{PassBuffer, SpectralImage};

/// The film: pass estimates of a contiguous range of passes `first .. first + passes`, summed,
/// with per-pixel statistics across passes.
#[derive(Clone, Debug, PartialEq)]
pub struct Film {
    pub width: usize,
    pub height: usize,
    pub grid: SpectralGrid,
    /// Index of the first pass in the film (0 unless it is a slice of a distributed render).
    pub first: u64,
    /// Number of passes added.
    pub passes: u64,
    /// `[layer][pixel][bin]` sums of pass estimates, fixed point at `SUM_SCALE`.
    pub sum: Vec<i128>,
    /// `[pixel][bin]` sums of squared total pass estimates, fixed point at `SQ_SCALE`.
    pub sum_sq: Vec<i128>,
    /// Samples dropped because they were not finite (or beyond `MAX_SAMPLE`).
    pub dropped: u64,
    /// Sensors and light layers the film keeps.
    pub extras: FilmExtras,
    /// `[light][pixel][bin]` sums of each light's part of the image, fixed point at `SUM_SCALE`.
    pub light_sum: Vec<i128>,
    /// `[sensor][bin]` sums of the sensors' pass values, fixed point at `SUM_SCALE`.
    pub sensor_sum: Vec<i128>,
    /// `[sensor]` sums of the squared photometric pass values, fixed point at `SQ_SCALE`.
    pub sensor_sq: Vec<i128>,
    /// The automatic settings' choice, as `render --verbose` reports it: empty without
    /// automatic settings (and in films written before films kept it). Images carry it as the
    /// attribute `brumeAutoSettings`, so a merged image is the same bytes as a single run's.
    /// Not part of the film's shape: the choice follows from the render's identity.
    pub auto_settings: Vec<String>,
    /// The difference layers of the smaller radius for scattered light, when every pass of
    /// the film carried them (`blend`: the image is then blended from the two radii).
    pub blend: Option<BlendSums>,
}

/// Why two films cannot be merged.
#[derive(Debug, thiserror::Error, PartialEq, Eq)]
pub enum MergeError {
    #[error("films differ in size, spectral grid, sensors or light layers")]
    Shape,
    #[error("pass ranges are not adjacent: {0}..{1} then {2}..{3}")]
    Gap(u64, u64, u64, u64),
    /// The parts' automatic settings differ (brumes whose pilot passes choose differently).
    #[error(
        "the films' automatic settings differ: {0} in one, {1} in the other (rendered by \
         brumes whose pilot passes choose differently); merge parts of one brume's render"
    )]
    Choice(String, String),
}

impl Film {
    pub fn new(width: usize, height: usize, grid: SpectralGrid) -> Self {
        Self::starting_at(width, height, grid, 0)
    }

    /// An empty film whose first pass will be pass `first` of the seed's sequence.
    pub fn starting_at(width: usize, height: usize, grid: SpectralGrid, first: u64) -> Self {
        Self::with_extras(width, height, grid, first, FilmExtras::default())
    }

    /// An empty film starting at pass `first` that also keeps `extras` (sensors, light
    /// layers).
    pub fn with_extras(
        width: usize,
        height: usize,
        grid: SpectralGrid,
        first: u64,
        extras: FilmExtras,
    ) -> Self {
        let (px, n) = (width * height * grid.n, grid.n);
        let (lights, sensors) = (extras.light_layers.len(), extras.sensors.len());
        Self {
            width,
            height,
            grid,
            first,
            passes: 0,
            sum: vec![0; LAYERS * px],
            sum_sq: vec![0; px],
            dropped: 0,
            extras,
            light_sum: vec![0; lights * px],
            sensor_sum: vec![0; sensors * n],
            sensor_sq: vec![0; sensors],
            auto_settings: Vec::new(),
            blend: None,
        }
    }

    /// An empty pass buffer of this film's shape (image, light layers, sensors).
    pub fn pass_buffer(&self) -> PassBuffer {
        PassBuffer::with_extras(
            self.width * self.height,
            self.grid.n,
            self.extras.light_layers.len(),
            self.extras.sensors.len(),
        )
    }

    /// Whether `other` has this film's size, spectral grid, sensors and light layers (so
    /// that passes of one can continue or join the other).
    pub fn same_shape(&self, other: &Film) -> bool {
        (self.width, self.height, &self.grid, &self.extras)
            == (other.width, other.height, &other.grid, &other.extras)
    }

    /// The pass index after the last one added.
    pub fn end(&self) -> u64 {
        self.first + self.passes
    }

    pub fn add_pass(&mut self, pass: &PassBuffer) {
        let px = self.width * self.height * self.grid.n;
        let (medium, surface) = pass.data.split_at(px);
        let (sum_m, sum_s) = self.sum.split_at_mut(px);
        // Every element is independent and the drop count is an integer sum, so splitting the
        // work between threads cannot change a bit of the film.
        const BLOCK: usize = 1 << 12;
        let dropped: u64 = sum_m
            .par_chunks_mut(BLOCK)
            .zip(sum_s.par_chunks_mut(BLOCK))
            .zip(self.sum_sq.par_chunks_mut(BLOCK))
            .zip(medium.par_chunks(BLOCK).zip(surface.par_chunks(BLOCK)))
            .map(|(((sum_m, sum_s), sum_sq), (medium, surface))| {
                let mut dropped = 0u64;
                for i in 0..medium.len() {
                    let (m, s) = (medium[i] as f64, surface[i] as f64);
                    if !(m.abs() <= MAX_SAMPLE && s.abs() <= MAX_SAMPLE) {
                        dropped += 1;
                        continue;
                    }
                    sum_m[i] = sum_m[i].wrapping_add(to_fixed(m, SUM_SCALE));
                    sum_s[i] = sum_s[i].wrapping_add(to_fixed(s, SUM_SCALE));
                    let t = m + s;
                    sum_sq[i] = sum_sq[i].wrapping_add(to_fixed(t * t, SQ_SCALE));
                }
                dropped
            })
            .sum();
        self.dropped += dropped + pass.dropped;
        self.add_blend(pass);
        self.add_lights(pass);
        self.dropped += self.add_sensors(pass);
        self.passes += 1;
    }

    /// Adds the pass's difference layers (`blend`). The sums exist only while every pass of
    /// the film had them: a pass without them (or a film begun without them) leaves the film
    /// without, so that it outputs the larger radius's image, which its passes all estimate.
    fn add_blend(&mut self, pass: &PassBuffer) {
        if pass.blend.is_empty() {
            self.blend = None;
            return;
        }
        if self.passes == 0 && self.blend.is_none() {
            self.blend = Some(BlendSums::new(self.width * self.height * self.grid.n));
        }
        if let Some(b) = &mut self.blend {
            b.add(&pass.data, &pass.blend);
        }
    }

    /// Adds each light's part of the pass to its layer (a buffer without light layers adds
    /// nothing: its light is in no layer). Values beyond `MAX_SAMPLE` are left out, as the
    /// image leaves them out.
    fn add_lights(&mut self, pass: &PassBuffer) {
        if pass.lights != self.extras.light_layers.len() {
            return;
        }
        const BLOCK: usize = 1 << 12;
        self.light_sum
            .par_chunks_mut(BLOCK)
            .zip(pass.light_data.par_chunks(BLOCK))
            .for_each(|(sum, v)| {
                for (s, v) in sum.iter_mut().zip(v) {
                    let v = *v as f64;
                    if v.abs() <= MAX_SAMPLE {
                        *s = s.wrapping_add(to_fixed(v, SUM_SCALE));
                    }
                }
            });
    }

    /// Adds each sensor's value of the pass (luminance sensors from the pass's pixels, the
    /// others from what the integrator splatted); returns how many were dropped as not finite
    /// or too large.
    fn add_sensors(&mut self, pass: &PassBuffer) -> u64 {
        let n = self.grid.n;
        let px = self.width * self.height * n;
        let (medium, surface) = pass.data.split_at(px.min(pass.data.len()));
        let w = sensor::weights(&self.grid);
        let mut v = vec![0.0f64; n];
        let mut dropped = 0;
        for (k, s) in self.extras.sensors.iter().enumerate() {
            match s.kind {
                SensorKind::Luminance { region } => {
                    sensor::region_mean(region, self.width, n, medium, surface, &mut v)
                }
                SensorKind::Illuminance { .. } => {
                    let from = pass.sensor_data.get(k * n..k * n + n);
                    for (b, x) in v.iter_mut().enumerate() {
                        *x = from.map_or(0.0, |f| f[b] as f64);
                    }
                }
            }
            let y: f64 = v.iter().zip(&w).map(|(v, w)| v * w).sum();
            if !(y.abs() <= MAX_SAMPLE && v.iter().all(|x| x.abs() <= MAX_SAMPLE)) {
                dropped += 1;
                continue;
            }
            for (sum, x) in self.sensor_sum[k * n..k * n + n].iter_mut().zip(&v) {
                *sum = sum.wrapping_add(to_fixed(*x, SUM_SCALE));
            }
            self.sensor_sq[k] = self.sensor_sq[k].wrapping_add(to_fixed(y * y, SQ_SCALE));
        }
        dropped
    }

    /// With light layers, the fraction of the image's light (summed over pixels and bins) that
    /// no light layer holds: 0 up to rounding when every splat named its light.
    pub fn unattributed(&self) -> Option<f64> {
        if self.extras.light_layers.is_empty() {
            return None;
        }
        let total: f64 = self.sum.iter().map(|v| *v as f64).sum();
        let layers: f64 = self.light_sum.iter().map(|v| *v as f64).sum();
        Some(if total != 0.0 {
            (total - layers) / total
        } else {
            0.0
        })
    }

    /// Each sensor's estimate over the film's passes.
    pub fn sensor_readings(&self) -> Vec<SensorReading> {
        let n = self.grid.n;
        self.extras
            .sensors
            .iter()
            .enumerate()
            .map(|(k, s)| {
                sensor::reading(
                    s,
                    &self.grid,
                    self.passes,
                    &self.sensor_sum[k * n..k * n + n],
                    self.sensor_sq[k],
                    (SUM_SCALE, SQ_SCALE),
                )
            })
            .collect()
    }

    /// Adds the passes of `other`, which must directly follow or precede this film's range.
    /// The result is bit-identical to rendering the union in one run.
    pub fn merge(&mut self, other: &Film) -> Result<(), MergeError> {
        if !self.same_shape(other) {
            return Err(MergeError::Shape);
        }
        if let (Some(a), Some(b)) = (self.auto_choice(), other.auto_choice())
            && a != b
        {
            return Err(MergeError::Choice(a.into(), b.into()));
        }
        if self.passes > 0 && other.passes > 0 {
            if other.first == self.end() {
                // other follows
            } else if other.end() == self.first {
                self.first = other.first;
            } else {
                return Err(MergeError::Gap(
                    self.first,
                    self.end(),
                    other.first,
                    other.end(),
                ));
            }
        } else if self.passes == 0 {
            self.first = other.first;
        }
        for (mine, theirs) in [
            (&mut self.sum, &other.sum),
            (&mut self.sum_sq, &other.sum_sq),
            (&mut self.light_sum, &other.light_sum),
            (&mut self.sensor_sum, &other.sensor_sum),
            (&mut self.sensor_sq, &other.sensor_sq),
        ] {
            for (a, b) in mine.iter_mut().zip(theirs) {
                *a = a.wrapping_add(*b);
            }
        }
        self.blend = match (self.blend.take(), &other.blend) {
            (Some(mut a), Some(b)) => {
                a.merge(b);
                Some(a)
            }
            (None, Some(b)) if self.passes == 0 => Some(b.clone()),
            (Some(a), None) if other.passes == 0 => Some(a),
            // One part had no difference layers: the merge estimates the larger radius's image.
            (Some(_) | None, None) | (None, Some(_)) => None,
        };
        self.passes += other.passes;
        self.dropped += other.dropped;
        // Parts of one render made the same choice; a part written before films kept it has
        // none. (Checked before anything is added, below.)
        if self.auto_settings.is_empty() {
            self.auto_settings.clone_from(&other.auto_settings);
        }
        Ok(())
    }

    /// The settings the automatic choice recorded on this film gave its passes (`q = [..],
    /// forward_rays = .., camera_samples = ..`, the end of the report's first line); None
    /// without one.
    pub fn auto_choice(&self) -> Option<&str> {
        let first = self.auto_settings.first()?;
        first.rfind(": q = ").map(|i| &first[i + 2..])
    }

    /// The weight of the smaller radius for scattered light in the image (`blend`), None when
    /// the film has no difference layers.
    pub fn blend(&self) -> Option<Blend> {
        let px = self.width * self.height * self.grid.n;
        let (sum_m, sum_s) = self.sum.split_at(px);
        let b = self.blend.as_ref()?;
        Some(b.weight(|i| sum_m[i].wrapping_add(sum_s[i]), self.passes))
    }

    /// The mean over passes, its standard error, and the two component layers; with
    /// difference layers, blended from the two radii by the weight [`Self::blend`] chooses.
    pub fn image(&self) -> SpectralImage {
        let px = self.width * self.height * self.grid.n;
        let p = self.passes.max(1) as f64;
        let mut img = SpectralImage::new(self.width, self.height, self.grid.clone());
        let (sum_m, sum_s) = self.sum.split_at(px);
        let mut noise = vec![0.0f32; px];
        let w = self.blend().map(|b| b.w);
        let (mut medium, mut surface) = (vec![0.0f32; px], vec![0.0f32; px]);
        for i in 0..px {
            let total = sum_m[i].wrapping_add(sum_s[i]);
            let (mut m, mut s) = (
                sum_m[i] as f64 / SUM_SCALE / p,
                sum_s[i] as f64 / SUM_SCALE / p,
            );
            let mut mean = (total as f64 / SUM_SCALE) / p;
            let mut var = if self.passes > 1 {
                let sq = self.sum_sq[i] as f64 / SQ_SCALE;
                (sq - p * mean * mean) / (p - 1.0)
            } else {
                0.0
            };
            if let (Some(b), Some(w)) = (&self.blend, w) {
                let (dm, ds, dv) = b.shift(i, total, self.passes, w);
                (m, s, var) = (m + dm, s + ds, var + dv);
                mean += dm + ds;
            }
            (medium[i], surface[i]) = (m as f32, s as f32);
            img.data[i] = mean as f32;
            if self.passes > 1 {
                noise[i] = (var.max(0.0) / p).sqrt() as f32;
            }
        }
        img.noise = Some(noise);
        let layer = |s: &[i128]| {
            s.iter()
                .map(|v| (*v as f64 / SUM_SCALE / p) as f32)
                .collect()
        };
        img.layers = vec![("medium".into(), medium), ("surface".into(), surface)];
        for (k, name) in self.extras.light_layers.iter().enumerate() {
            img.layers
                .push((name.clone(), layer(&self.light_sum[k * px..(k + 1) * px])));
        }
        img
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::film::Layer;

    fn grid() -> SpectralGrid {
        SpectralGrid::new(2, 400.0, 700.0)
    }

    fn pass(values: &[f32]) -> PassBuffer {
        let mut b = PassBuffer::new(2, 2);
        b.data.copy_from_slice(values);
        b
    }

    #[test]
    fn merge_in_any_grouping_equals_sequential_adds() {
        let passes: Vec<PassBuffer> = (0..6)
            .map(|p| {
                let v: Vec<f32> = (0..8)
                    .map(|i| ((p * 8 + i) as f32 * 0.731).sin() * 10f32.powi(i - 4))
                    .collect();
                pass(&v)
            })
            .collect();
        let mut straight = Film::new(2, 1, grid());
        passes.iter().for_each(|p| straight.add_pass(p));
        let slice = |a: usize, b: usize| {
            let mut f = Film::starting_at(2, 1, grid(), a as u64);
            passes[a..b].iter().for_each(|p| f.add_pass(p));
            f
        };
        let mut merged = slice(4, 6);
        merged.merge(&slice(1, 4)).unwrap();
        merged.merge(&slice(0, 1)).unwrap();
        assert_eq!(merged, straight);
        let a = straight.image();
        let b = merged.image();
        assert_eq!(a.data, b.data);
        assert_eq!(a.noise, b.noise);
    }

    #[test]
    fn non_finite_and_huge_samples_are_dropped_and_counted() {
        let mut f = Film::new(2, 1, grid());
        f.add_pass(&pass(&[
            f32::NAN,
            1.0,
            2.0,
            1e30,
            0.0,
            0.0,
            0.0,
            f32::INFINITY,
        ]));
        assert_eq!(f.dropped, 2);
        let img = f.image();
        assert!(img.data.iter().all(|v| v.is_finite()));
        assert_eq!(img.data[1], 1.0);
        assert_eq!(img.data[2], 2.0);
    }

    #[test]
    fn a_non_finite_sample_is_dropped_without_erasing_its_pixel() {
        let mut b = PassBuffer::new(2, 2);
        b.splat(Layer::Medium, 1, &[1.0, 2.0], &[3.0, 4.0], 0.5);
        b.splat(Layer::Medium, 1, &[1.0, f32::NAN], &[3.0, 4.0], 0.5);
        b.splat(Layer::Medium, 1, &[1e30, 1.0], &[1e30, 1.0], 1.0);
        b.splat_scaled(Layer::Surface, 0, &[f32::INFINITY, 0.0], 1.0);
        b.splat_scaled(Layer::Surface, 0, &[1.0, 2.0], 2.0);
        assert_eq!(b.dropped, 3);
        let mut f = Film::new(2, 1, grid());
        f.add_pass(&b);
        assert_eq!(f.dropped, 3);
        let img = f.image();
        assert_eq!(img.data, vec![2.0, 4.0, 1.5, 4.0]);
    }

    #[test]
    fn gaps_and_shape_mismatches_are_refused() {
        let mut a = Film::starting_at(2, 1, grid(), 0);
        a.add_pass(&pass(&[0.0; 8]));
        let mut b = Film::starting_at(2, 1, grid(), 2);
        b.add_pass(&pass(&[0.0; 8]));
        assert_eq!(a.merge(&b), Err(MergeError::Gap(0, 1, 2, 3)));
        let c = Film::new(1, 2, grid());
        assert_eq!(a.clone().merge(&c), Err(MergeError::Shape));
    }
}
