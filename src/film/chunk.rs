//! What one chunk of forward rays adds to a pass.
//!
//! A chunk keeps its splats as a log (slot index + values) while the log is smaller than a
//! dense pass buffer, and switches to a dense buffer once it would not be. Small images and
//! sparse chunks then cost memory in proportion to what they splat, not to the image size,
//! and the tracing thread writes sequentially instead of scattering over megabytes of film.
//! Draining chunks into the pass in chunk order makes the pass's floating-point sums depend
//! only on the chunk boundaries, never on which thread traced which chunk.

use super::PassBuffer;
use super::layer::{LAYERS, Layer, products_finite};
use super::pass::BlendRadius;

pub struct ChunkSplats {
    pixels: usize,
    n: usize,
    /// Light layers and sensors of the pass this chunk joins.
    lights: usize,
    sensors: usize,
    /// Whether the pass keeps the difference layers of `film::blend`.
    blend: bool,
    /// Slot of each logged splat: `layer * pixels + pixel` for the image, then
    /// `LAYERS * pixels + light * pixels + pixel` for a light layer, then the difference
    /// layers' `layer * pixels + pixel` when kept, then one slot per sensor.
    slots: Vec<u32>,
    /// `n` values per logged splat.
    values: Vec<f32>,
    /// The dense sums over every slot once the log outgrew them (kept for reuse, zeroed).
    dense: Vec<f32>,
    is_dense: bool,
    dropped: u64,
    /// Nested estimates' additions (`PassBuffer::variants`): slot `variant * pixels + pixel`
    /// and value, always a log (a pass has them only as pilots on a lattice of pixels).
    variant_log: Vec<(u32, f32)>,
}

impl ChunkSplats {
    /// A log for a pass without light layers or sensors.
    pub fn new(pixels: usize, n: usize) -> Self {
        Self::with_extras(pixels, n, 0, 0)
    }

    /// An empty log of the shape of `buf`, for a chunk of forward rays.
    pub fn for_buffer(buf: &PassBuffer) -> Self {
        let mut c = Self::with_extras(buf.pixels, buf.n, buf.lights, buf.sensors);
        c.blend = !buf.blend.is_empty();
        c
    }

    /// An empty log of this one's shape.
    pub fn empty_like(&self) -> Self {
        let mut c = Self::with_extras(self.pixels, self.n, self.lights, self.sensors);
        c.blend = self.blend;
        c
    }

    /// A log for a pass with `lights` light layers and `sensors` sensors.
    pub fn with_extras(pixels: usize, n: usize, lights: usize, sensors: usize) -> Self {
        Self {
            pixels,
            n,
            lights,
            sensors,
            blend: false,
            slots: Vec::new(),
            values: Vec::new(),
            dense: Vec::new(),
            is_dense: false,
            dropped: 0,
            variant_log: Vec::new(),
        }
    }

    /// Where the sensors' slots start.
    fn sensors_at(&self) -> usize {
        (LAYERS + self.lights + if self.blend { 2 * LAYERS } else { 0 }) * self.pixels
    }

    fn slot_count(&self) -> usize {
        self.sensors_at() + self.sensors
    }

    /// Whether the pass keeps the difference layers (`film::blend`).
    #[inline(always)]
    pub fn keeps_blend(&self) -> bool {
        self.blend
    }

    /// Adds `w * f * scale` to layer `layer` of a pixel at radius `radius` of the pass's two
    /// for scattered light (`PassBuffer::blend`); ignored when the pass has no blend. A sample
    /// with a non-finite bin is left out and counted, as [`Self::splat`] does.
    #[inline(always)]
    pub fn splat_blend(
        &mut self,
        (radius, layer): (BlendRadius, Layer),
        pixel: usize,
        w: &[f32],
        f: &[f32],
        scale: f32,
    ) {
        if !self.blend {
            return;
        }
        let n = self.n;
        let (w, f) = (&w[..n], &f[..n]);
        if !products_finite(w, f, scale) {
            self.dropped += 1;
            return;
        }
        let group = radius as usize * LAYERS;
        let slot = (LAYERS + self.lights + group + layer as usize) * self.pixels + pixel;
        self.add_values(slot, w.iter().zip(f).map(|(w, f)| w * f * scale));
    }

    fn dense_len(&self) -> usize {
        self.slot_count() * self.n
    }

    /// Adds the sample `w * f * scale` (per bin) to a pixel; a sample with a non-finite bin is
    /// dropped whole and counted, as in [`PassBuffer::splat`].
    #[inline]
    pub fn splat(&mut self, layer: Layer, pixel: usize, w: &[f32], f: &[f32], scale: f32) {
        self.splat_from(layer, pixel, None, w, f, scale);
    }

    /// [`Self::splat`] of light from light `light`, also added to its light layer when the
    /// pass keeps light layers (as [`PassBuffer::splat_from`]).
    #[inline(always)]
    pub fn splat_from(
        &mut self,
        layer: Layer,
        pixel: usize,
        light: Option<u32>,
        w: &[f32],
        f: &[f32],
        scale: f32,
    ) {
        let n = self.n;
        let (w, f) = (&w[..n], &f[..n]);
        if !products_finite(w, f, scale) {
            self.dropped += 1;
            return;
        }
        let slot = layer as usize * self.pixels + pixel;
        let light_slot = light
            .map(|l| l as usize)
            .filter(|&l| l < self.lights)
            .map(|l| (LAYERS + l) * self.pixels + pixel);
        for s in std::iter::once(slot).chain(light_slot) {
            self.add_values(s, w.iter().zip(f).map(|(w, f)| w * f * scale));
        }
    }

    /// Adds `factor * sum(w * f * scale)` to the total of `pixel` in each variant `v` whose
    /// `factors[v]` is Some (`integrator::nest`); a sample with a non-finite bin is left out,
    /// as [`Self::splat`] leaves it out of the image (and counts it there).
    pub fn add_to_variants(
        &mut self,
        pixel: usize,
        (w, f, scale): (&[f32], &[f32], f32),
        factors: &[Option<f32>],
    ) {
        let n = self.n;
        let (w, f) = (&w[..n], &f[..n]);
        if !products_finite(w, f, scale) {
            return;
        }
        let total: f32 = w.iter().zip(f).map(|(w, f)| w * f * scale).sum();
        for (v, factor) in factors.iter().enumerate() {
            if let Some(k) = factor {
                let slot = (v * self.pixels + pixel) as u32;
                self.variant_log.push((slot, total * k));
            }
        }
    }

    /// Adds `value * scale` (per bin) to sensor `sensor` (as [`PassBuffer::splat_sensor`]).
    #[inline]
    pub fn splat_sensor(&mut self, sensor: usize, value: &[f32], scale: f32) {
        if sensor >= self.sensors {
            return;
        }
        let value = &value[..self.n];
        if !value
            .iter()
            .fold(true, |ok, x| ok & (x * scale).is_finite())
        {
            self.dropped += 1;
            return;
        }
        let slot = self.sensors_at() + sensor;
        self.add_values(slot, value.iter().map(|x| x * scale));
    }

    /// Logs (or adds to the dense buffer) the `n` values of one splat into `slot`.
    #[inline(always)]
    fn add_values(&mut self, slot: usize, values: impl Iterator<Item = f32>) {
        let n = self.n;
        if self.is_dense {
            let d = &mut self.dense[slot * n..slot * n + n];
            for (d, v) in d.iter_mut().zip(values) {
                *d += v;
            }
            return;
        }
        if self.values.len() + n > self.dense_len() {
            self.go_dense();
            return self.add_values(slot, values);
        }
        self.slots.push(slot as u32);
        self.values.extend(values);
    }

    /// Replays the log into the dense buffer; later splats go there directly.
    fn go_dense(&mut self) {
        let n = self.n;
        let len = self.dense_len();
        if self.dense.len() != len {
            self.dense = vec![0.0; len];
        }
        for (slot, v) in self.slots.iter().zip(self.values.chunks_exact(n)) {
            let i = *slot as usize * n;
            for (d, v) in self.dense[i..i + n].iter_mut().zip(v) {
                *d += *v;
            }
        }
        self.slots.clear();
        self.values.clear();
        self.is_dense = true;
    }

    /// The values of slot `slot` in `buf` (image, light layers, difference layers, sensors).
    fn target<'a>(&self, buf: &'a mut PassBuffer, slot: usize) -> &'a mut [f32] {
        let (n, image) = (self.n, LAYERS * self.pixels);
        let lights = image + self.lights * self.pixels;
        let sensors = self.sensors_at();
        let (data, i) = if slot < image {
            (&mut buf.data, slot)
        } else if slot < lights {
            (&mut buf.light_data, slot - image)
        } else if slot < sensors {
            (&mut buf.blend, slot - lights)
        } else {
            (&mut buf.sensor_data, slot - sensors)
        };
        &mut data[i * n..i * n + n]
    }

    /// Adds everything into `buf` and empties the chunk (keeping its allocations for the next).
    pub fn drain_into(&mut self, buf: &mut PassBuffer) {
        let n = self.n;
        debug_assert_eq!(
            (
                buf.pixels,
                buf.n,
                buf.lights,
                buf.sensors,
                !buf.blend.is_empty()
            ),
            (self.pixels, n, self.lights, self.sensors, self.blend)
        );
        buf.dropped += std::mem::take(&mut self.dropped);
        for (slot, v) in self.variant_log.drain(..) {
            if let Some(t) = buf.variants.get_mut(slot as usize) {
                *t += f64::from(v);
            }
        }
        if self.is_dense {
            let dense = std::mem::take(&mut self.dense);
            for (slot, d) in dense.chunks_exact(n).enumerate() {
                for (b, d) in self.target(buf, slot).iter_mut().zip(d) {
                    *b += *d;
                }
            }
            self.dense = dense;
            self.dense.iter_mut().for_each(|d| *d = 0.0);
            self.is_dense = false;
            return;
        }
        let (slots, values) = (
            std::mem::take(&mut self.slots),
            std::mem::take(&mut self.values),
        );
        for (slot, v) in slots.iter().zip(values.chunks_exact(n)) {
            for (b, v) in self.target(buf, *slot as usize).iter_mut().zip(v) {
                *b += *v;
            }
        }
        (self.slots, self.values) = (slots, values);
        self.slots.clear();
        self.values.clear();
    }

    /// Bytes held (log and dense buffer), for memory reports.
    pub fn bytes(&self) -> usize {
        self.slots.capacity() * 4
            + self.values.capacity() * 4
            + self.dense.capacity() * 4
            + self.variant_log.capacity() * 8
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Log and dense modes add exactly what direct splats into a pass buffer add, in the
    /// same per-slot order, so draining reproduces the direct result bit for bit.
    #[test]
    fn log_and_dense_match_direct_splats() {
        let (pixels, n) = (5, 3);
        let mut direct = PassBuffer::new(pixels, n);
        let mut chunk = ChunkSplats::new(pixels, n);
        let mut via_chunk = PassBuffer::new(pixels, n);
        let mut x = 0.37f32;
        // 40 splats of 3 values: more than the 30 dense values, so the chunk goes dense.
        for k in 0..40 {
            x = (x * 7.13 + 0.11).fract();
            let w = [x, 1.0 - x, 0.5];
            let f = [2.0, x * 3.0, 1.5];
            let layer = if k % 3 == 0 {
                Layer::Surface
            } else {
                Layer::Medium
            };
            let pixel = k % pixels;
            direct.splat(layer, pixel, &w, &f, 0.25);
            chunk.splat(layer, pixel, &w, &f, 0.25);
            if k == 7 {
                assert!(!chunk.is_dense);
            }
        }
        assert!(chunk.is_dense);
        chunk.splat(Layer::Medium, 0, &[f32::NAN, 1.0, 1.0], &[1.0; 3], 1.0);
        chunk.drain_into(&mut via_chunk);
        assert_eq!(via_chunk.dropped, 1);
        assert_eq!(direct.data, via_chunk.data);
        // Drained and reset: a second use in log mode starts from zero.
        assert!(chunk.dense.iter().all(|d| *d == 0.0));
        let mut again = PassBuffer::new(pixels, n);
        chunk.splat(Layer::Medium, 2, &[1.0; 3], &[2.0; 3], 1.0);
        chunk.drain_into(&mut again);
        assert_eq!(again.slot(Layer::Medium, 2), &[2.0, 2.0, 2.0]);
        assert_eq!(again.data.iter().filter(|v| **v != 0.0).count(), 3);
    }
}
