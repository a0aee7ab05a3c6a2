//! One pass's estimate before it joins the film: per layer, pixel and bin, and, when the film
//! has them, per light layer and per sensor.

use rayon::prelude::*;

use super::layer::{LAYERS, Layer, products_finite};

/// One pass's estimate per layer, pixel and bin, in radiance units.
#[derive(Clone, Debug)]
pub struct PassBuffer {
    pub pixels: usize,
    pub n: usize,
    /// `[layer][pixel][bin]`.
    pub data: Vec<f32>,
    /// Number of light layers (0: none are kept).
    pub lights: usize,
    /// `[light][pixel][bin]`: the part of `data` (both layers) each light brought.
    pub light_data: Vec<f32>,
    /// Number of sensors.
    pub sensors: usize,
    /// `[sensor][bin]`: what the integrator splatted for each sensor (illuminance sensors:
    /// spectral irradiance, W/(m² nm)).
    pub sensor_data: Vec<f32>,
    /// Samples not added because a value was not finite (reaches `Film::dropped`).
    pub dropped: u64,
    /// `[variant][pixel]`: per-pixel totals (over layers and bins) of the estimates nested in
    /// a pass (`integrator::nest`); empty but in the automatic settings' nested pilots. Never
    /// added to a film.
    pub variants: Vec<f64>,
    /// Empty unless the pass estimates scattered light at two radii (`film::blend`). While
    /// the pass is traced: `[radius][layer][pixel][bin]`, the larger radius's estimate of
    /// scattered light (taken out of `data`, where it belongs) and the smaller's; once it is
    /// done ([`Self::fold_blend`]), `[layer][pixel][bin]`: `data` holds the larger radius's
    /// image and this the difference `small - large`. Splitting it so, a hit outside the
    /// smaller ball costs one splat, as without the blend, and one inside it two.
    pub blend: Vec<f32>,
}

/// Which of a pass's two radii for scattered light a deposit is at (`PassBuffer::blend`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BlendRadius {
    /// The larger: the image's (its deposits go to `data` when the pass is folded).
    Large = 0,
    /// The direct radius.
    Small = 1,
}

impl PassBuffer {
    /// A buffer without light layers or sensors.
    pub fn new(pixels: usize, n: usize) -> Self {
        Self::with_extras(pixels, n, 0, 0)
    }

    /// A buffer with `lights` light layers and `sensors` sensor slots (see `Film::pass_buffer`).
    pub fn with_extras(pixels: usize, n: usize, lights: usize, sensors: usize) -> Self {
        Self {
            pixels,
            n,
            data: vec![0.0; LAYERS * pixels * n],
            lights,
            light_data: vec![0.0; lights * pixels * n],
            sensors,
            sensor_data: vec![0.0; sensors * n],
            dropped: 0,
            variants: Vec::new(),
            blend: Vec::new(),
        }
    }

    /// This buffer with the two radii's layers of `film::blend` when `blend` is true.
    pub fn with_blend(mut self, blend: bool) -> Self {
        if blend {
            self.blend = vec![0.0; 2 * LAYERS * self.pixels * self.n];
        }
        self
    }

    /// Ends a pass traced with two radii: the larger radius's deposits join `data`, and
    /// `blend` keeps the difference of the smaller's from them (see [`Self::blend`]).
    pub fn fold_blend(&mut self) {
        let values = LAYERS * self.pixels * self.n;
        if self.blend.len() != 2 * values {
            return;
        }
        let (large, small) = self.blend.split_at_mut(values);
        self.data
            .par_chunks_mut(1 << 14)
            .zip(large.par_chunks_mut(1 << 14))
            .zip(small.par_chunks(1 << 14))
            .for_each(|((data, large), small)| {
                for ((d, l), s) in data.iter_mut().zip(large.iter_mut()).zip(small) {
                    *d += *l;
                    *l = *s - *l;
                }
            });
        self.blend.truncate(values);
    }

    /// This buffer with room for the totals of `count` nested estimates (`variants`).
    pub fn with_variants(mut self, count: usize) -> Self {
        self.variants = vec![0.0; count * self.pixels];
        self
    }

    /// Adds the sample `w * f * scale` (per bin) to a pixel, unless some bin of it is not
    /// finite: then the whole sample is dropped and counted, so one bad path cannot poison a
    /// pixel (a NaN would otherwise erase every other sample of the pass in that slot).
    #[inline]
    pub fn splat(&mut self, layer: Layer, pixel: usize, w: &[f32], f: &[f32], scale: f32) {
        self.splat_from(layer, pixel, None, w, f, scale);
    }

    /// [`Self::splat`] of light from light `light` (its index in the scene's `LightSet`): also
    /// added to that light's layer when the buffer keeps light layers.
    #[inline]
    pub fn splat_from(
        &mut self,
        layer: Layer,
        pixel: usize,
        light: Option<u32>,
        w: &[f32],
        f: &[f32],
        scale: f32,
    ) {
        if !products_finite(w, f, scale) {
            self.dropped += 1;
            return;
        }
        let n = self.n;
        let slot = self.slot(layer, pixel);
        for ((s, w), f) in slot.iter_mut().zip(w).zip(f) {
            *s += w * f * scale;
        }
        if let Some(l) = self.light_slot(light, pixel) {
            let d = &mut self.light_data[l..l + n];
            for ((s, w), f) in d.iter_mut().zip(w).zip(f) {
                *s += w * f * scale;
            }
        }
    }

    /// Adds the sample `v * scale` to a pixel, or drops and counts it (see `splat`).
    #[inline]
    pub fn splat_scaled(&mut self, layer: Layer, pixel: usize, v: &[f32], scale: f32) {
        self.splat_scaled_from(layer, pixel, None, v, scale);
    }

    /// [`Self::splat_scaled`] of light from light `light` (see [`Self::splat_from`]).
    #[inline]
    pub fn splat_scaled_from(
        &mut self,
        layer: Layer,
        pixel: usize,
        light: Option<u32>,
        v: &[f32],
        scale: f32,
    ) {
        if !v.iter().fold(true, |ok, x| ok & (x * scale).is_finite()) {
            self.dropped += 1;
            return;
        }
        let n = self.n;
        for (s, x) in self.slot(layer, pixel).iter_mut().zip(v) {
            *s += x * scale;
        }
        if let Some(l) = self.light_slot(light, pixel) {
            for (s, x) in self.light_data[l..l + n].iter_mut().zip(v) {
                *s += x * scale;
            }
        }
    }

    /// Adds `value * scale` (per bin) to sensor `sensor` (its index in the film's sensor list),
    /// or drops and counts it when a bin is not finite. Ignored for an index past the sensors.
    #[inline]
    pub fn splat_sensor(&mut self, sensor: usize, value: &[f32], scale: f32) {
        if sensor >= self.sensors {
            return;
        }
        if !value
            .iter()
            .fold(true, |ok, x| ok & (x * scale).is_finite())
        {
            self.dropped += 1;
            return;
        }
        let n = self.n;
        for (s, x) in self.sensor_data[sensor * n..sensor * n + n]
            .iter_mut()
            .zip(value)
        {
            *s += x * scale;
        }
    }

    #[inline]
    pub fn slot(&mut self, layer: Layer, pixel: usize) -> &mut [f32] {
        let i = (layer as usize * self.pixels + pixel) * self.n;
        &mut self.data[i..i + self.n]
    }

    /// Start of light `light`'s values at `pixel` in `light_data`, when kept.
    #[inline]
    fn light_slot(&self, light: Option<u32>, pixel: usize) -> Option<usize> {
        let l = light? as usize;
        (l < self.lights).then(|| (l * self.pixels + pixel) * self.n)
    }

    /// Adds `other` elementwise; the order of calls fixes the floating-point result.
    pub fn add(&mut self, other: &PassBuffer) {
        self.dropped += other.dropped;
        for (a, b) in [
            (&mut self.data, &other.data),
            (&mut self.light_data, &other.light_data),
            (&mut self.sensor_data, &other.sensor_data),
            (&mut self.blend, &other.blend),
        ] {
            a.par_chunks_mut(1 << 14)
                .zip(b.par_chunks(1 << 14))
                .for_each(|(a, b)| a.iter_mut().zip(b).for_each(|(x, y)| *x += *y));
        }
    }

    pub fn scale(&mut self, s: f32) {
        for d in [
            &mut self.data,
            &mut self.light_data,
            &mut self.sensor_data,
            &mut self.blend,
        ] {
            d.par_iter_mut().for_each(|x| *x *= s);
        }
    }
}
