//! Spectra summed per light, for light layers (`film.light_layers`): next-event estimates pick a
//! light per sample, and each light's layer must hold exactly its part. Without light layers
//! everything goes into one total, added in the order the samples come, so that the image is
//! the same bits as when the estimates were a single sum.

use crate::spectrum::Spectrum;

/// Spectra by the light they came from (its index in the scene's `LightSet`), or one total.
#[derive(Clone, Debug)]
pub struct ByLight {
    layers: bool,
    /// The sum without light layers.
    total: Spectrum,
    /// With light layers: (light, sum) in the order the lights first came.
    lights: Vec<(u32, Spectrum)>,
}

impl ByLight {
    /// An empty sum, split by light when `layers`.
    pub fn new(layers: bool) -> Self {
        Self {
            layers,
            total: Spectrum::ZERO,
            lights: Vec::new(),
        }
    }

    /// Adds `v`, light `light`'s part.
    #[inline]
    pub fn add(&mut self, light: u32, v: Spectrum) {
        if !self.layers {
            self.total += v;
            return;
        }
        match self.lights.iter_mut().find(|(l, _)| *l == light) {
            Some((_, s)) => *s += v,
            None => self.lights.push((light, v)),
        }
    }

    /// Adds `other * w * s`, part by part.
    pub fn add_weighted(&mut self, other: &ByLight, w: &Spectrum, s: f32) {
        if !self.layers {
            self.total += other.total * *w * s;
            return;
        }
        for (l, v) in &other.lights {
            self.add(*l, *v * *w * s);
        }
    }

    /// The parts: (Some(light), sum) with light layers, else (None, total).
    pub fn parts(&self) -> Vec<(Option<u32>, Spectrum)> {
        if !self.layers {
            return vec![(None, self.total)];
        }
        self.lights.iter().map(|(l, v)| (Some(*l), *v)).collect()
    }

    /// The sum over all lights.
    pub fn sum(&self) -> Spectrum {
        self.lights.iter().fold(self.total, |acc, (_, v)| acc + *v)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parts_add_up_and_total_keeps_sample_order() {
        let s = |v: f32| Spectrum::splat(v, 2);
        let mut on = ByLight::new(true);
        let mut off = ByLight::new(false);
        let mut plain = Spectrum::ZERO;
        for (l, v) in [(1, 0.1), (0, 0.7), (1, 0.3)] {
            on.add(l, s(v));
            off.add(l, s(v));
            plain += s(v);
        }
        assert_eq!(off.parts(), vec![(None, plain)]);
        assert_eq!(
            on.parts(),
            vec![(Some(1), s(0.1) + s(0.3)), (Some(0), s(0.7))]
        );
        let w = s(2.0);
        let mut sum = ByLight::new(true);
        sum.add_weighted(&on, &w, 0.5);
        assert_eq!(sum.parts()[0], (Some(1), (s(0.1) + s(0.3)) * w * 0.5));
        assert!((off.sum()[0] - on.sum()[0]).abs() < 1e-6);
    }
}
