use serde::{Deserialize, Serialize};

use super::{EmissionSample, Light};
use crate::geometry::Geometry;
use crate::spectrum::SpectralGrid;

/// How a light's direct light reaches the image when the integrator uses next-event estimation
/// (`direct` of a light or an emitting shape).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum DirectChoice {
    /// Next-event estimation where it can reach the light (directional, point, spot and area
    /// lights), except spots narrower than the integrator's threshold; forward rays otherwise.
    #[default]
    Auto,
    /// Next-event estimation (not for lasers: no sampled direction can reach a beam).
    Nee,
    /// Forward rays only, as in the paper's pure method.
    Photons,
}

/// All lights, picked for forward rays in proportion to their total power (their bins weighted
/// by width, [`SpectralGrid::weighted_sum`]: a line's narrow bin holds a high density) times
/// their importance (default 1). The pick probability divides the flux a ray carries, so
/// importance changes how many forward rays a light gets, never the expected image.
#[derive(Clone, Debug)]
pub struct LightSet {
    lights: Vec<Light>,
    /// Per light: how its direct light is handled under next-event estimation.
    direct: Vec<DirectChoice>,
    /// Per light: total power (bins weighted by width; 0 when not finite and positive).
    power: Vec<f64>,
    /// Per light: multiplier of its share of forward rays.
    importance: Vec<f32>,
    /// Cumulative pick probabilities.
    cdf: Vec<f32>,
    probs: Vec<f32>,
}

impl LightSet {
    pub fn new(lights: Vec<Light>, geometry: &Geometry, grid: &SpectralGrid) -> LightSet {
        let power: Vec<f64> = lights
            .iter()
            .map(|l| {
                let p = grid.weighted_sum(&l.power(geometry));
                if p.is_finite() && p > 0.0 { p } else { 0.0 }
            })
            .collect();
        let n = lights.len();
        let mut set = LightSet {
            lights,
            direct: vec![DirectChoice::Auto; n],
            power,
            importance: vec![1.0; n],
            cdf: Vec::new(),
            probs: Vec::new(),
        };
        set.pick_table();
        set
    }

    /// Sets each light's importance (`importance` in the order of the lights; values that are
    /// not finite and >= 0 count as 1).
    pub fn with_importance(mut self, importance: Vec<f32>) -> Self {
        if importance.len() == self.lights.len() {
            self.importance = importance
                .into_iter()
                .map(|v| if v.is_finite() && v >= 0.0 { v } else { 1.0 })
                .collect();
            self.pick_table();
        }
        self
    }

    /// Light `i`'s importance.
    pub fn importance(&self, i: usize) -> f32 {
        self.importance.get(i).copied().unwrap_or(1.0)
    }

    fn pick_table(&mut self) {
        let weights: Vec<f64> = self
            .power
            .iter()
            .zip(&self.importance)
            .map(|(p, i)| p * *i as f64)
            .collect();
        let total: f64 = weights.iter().sum();
        self.probs = weights
            .iter()
            .map(|w| if total > 0.0 { (w / total) as f32 } else { 0.0 })
            .collect();
        let mut acc = 0.0f64;
        self.cdf = weights
            .iter()
            .map(|w| {
                acc += w;
                if total > 0.0 {
                    (acc / total) as f32
                } else {
                    0.0
                }
            })
            .collect();
    }

    pub fn lights(&self) -> &[Light] {
        &self.lights
    }

    /// Sets each light's direct-light choice (`choices` in the order of the lights).
    pub fn with_direct(mut self, choices: Vec<DirectChoice>) -> Self {
        if choices.len() == self.lights.len() {
            self.direct = choices;
        }
        self
    }

    /// How light `i`'s direct light is handled under next-event estimation.
    pub fn direct_choice(&self, i: usize) -> DirectChoice {
        self.direct.get(i).copied().unwrap_or_default()
    }

    /// Probability that [`Self::sample`] picks light `i`.
    pub fn pick_probability(&self, i: usize) -> f32 {
        self.probs[i]
    }

    /// Picks a light with `u[0]` and samples a forward ray from it with `u[1..5]`; the flux is
    /// divided by the pick probability. Returns the light's index too. None when no light emits.
    pub fn sample(&self, geometry: &Geometry, u: [f32; 5]) -> Option<(u32, EmissionSample)> {
        let i = self.cdf.partition_point(|&c| c <= u[0]);
        // Past the end only through rounding of the last cdf entry: take the last emitting light.
        let i = if i < self.lights.len() {
            i
        } else {
            self.probs.iter().rposition(|&p| p > 0.0)?
        };
        let p = self.probs[i];
        if p <= 0.0 {
            return None;
        }
        let mut s = self.lights[i].sample_emission(geometry, [u[1], u[2], u[3], u[4]]);
        s.flux /= p;
        Some((i as u32, s))
    }
}
