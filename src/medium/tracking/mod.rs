//! Null-collision transport in a grid density (method note 10; docs/media.md, "Delta
//! tracking"): the alternative to the exact change of variable (`density::Along`) that never
//! integrates the field along a ray. Tentative collisions are drawn at the majorant's rate
//! (`majorant.rs`, a block grid walked by DDA); at a tentative point `x` the collision is real
//! with probability `rho(x) / rho_bar`.
//!
//! - Free flights (delta tracking): the first real collision of a medium of extinction
//!   `rho(x) sigma` has the density `rho(s) sigma e^{-sigma D(s)}`, the same as the exact
//!   sampler's, so every estimator built on that density is unchanged.
//! - Transmittance (ratio tracking): the product over tentative points of
//!   `1 - rho(x) st_l / (rho_bar st_max)` has the mean `e^{-st_l D}` in every bin.
//!
//! A medium uses it when its `tracking` key says `"delta"` (majorant blocks) or
//! `"delta-global"` (one block: the cost baseline). Only grey media (one `sigma_t` for every
//! bin): in a chromatic medium the channel mixture's weights need `D(s)` at each sphere, which
//! is what tracking avoids computing (spectral tracking would replace them; not built).

mod majorant;

use glam::{DVec3, Vec3};
use rand::Rng;

pub use majorant::{DEFAULT_BLOCK, Majorant};

use crate::spectrum::Spectrum;

/// How a medium's transport integrates its density (scene key `media.X.tracking`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Tracking {
    /// The exact change of variable `u = D(s)` (every density kind).
    #[default]
    Exact,
    /// Delta and ratio tracking against a majorant grid (grid and noise densities).
    Delta,
    /// Delta and ratio tracking against the grid's global maximum: the cost baseline.
    DeltaGlobal,
}

/// Why a medium cannot be tracked.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum TrackingError {
    #[error(
        "delta tracking needs a grid or noise density; this medium's is {0}, whose optical \
         depth is exact in closed form (use tracking = \"exact\")"
    )]
    NotGrid(String),
    #[error(
        "delta tracking needs a grey medium (one sigma_t in every bin): in a chromatic medium \
         the channel mixture's weights need the optical depth at every sphere, which tracking \
         does not compute (use tracking = \"exact\", which is exact in colour)"
    )]
    Chromatic,
}

/// One ray `o + d s` through a tracked medium.
#[derive(Clone, Copy, Debug)]
pub struct Tracker<'a> {
    majorant: &'a Majorant,
    ray: (DVec3, DVec3),
}

/// An exponential step of rate `rate` from a uniform `u` in [0, 1).
#[inline]
fn exp_step(rate: f64, u: f32) -> f64 {
    -(1.0 - u as f64).ln() / rate
}

impl<'a> Tracker<'a> {
    pub fn new(majorant: &'a Majorant, o: Vec3, d: Vec3) -> Self {
        Self {
            majorant,
            ray: majorant.grid().ray_in_index(o, d),
        }
    }

    /// The density at distance `s`.
    #[inline]
    pub fn rho(&self, s: f32) -> f32 {
        let (a, b) = self.ray;
        self.majorant.grid().at_index_in_box(a + b * s as f64) as f32
    }

    /// Delta tracking: the distance of the first real collision in `(from, to)` of a medium
    /// whose extinction is `rho(x) sigma`, or None when there is none.
    pub fn free_flight<R: Rng + ?Sized>(
        &self,
        from: f32,
        to: f32,
        sigma: f32,
        rng: &mut R,
    ) -> Option<f32> {
        let mut hit = None;
        if sigma.is_nan() || sigma <= 0.0 {
            return None;
        }
        self.tentative((from, to), sigma, rng, |rng, t, rho, m| {
            if (rng.random::<f32>() as f64) * (m as f64) < rho {
                hit = Some(t as f32);
                return false;
            }
            true
        });
        // A collision rounded to the segment's end in f32 stays inside it.
        hit.filter(|&t| t < to)
    }

    /// Ratio tracking: per bin, an unbiased estimate of `e^{-st_l ∫_from^to rho}` for the
    /// medium's extinction `st` over its `n` bins.
    pub fn transmittance<R: Rng + ?Sized>(
        &self,
        (from, to): (f32, f32),
        st: &Spectrum,
        n: usize,
        rng: &mut R,
    ) -> Spectrum {
        let mut tr = Spectrum::splat(1.0, n);
        let st_max = st.0[..n].iter().copied().fold(0.0f32, f32::max);
        if st_max.is_nan() || st_max <= 0.0 {
            return tr;
        }
        self.tentative((from, to), st_max, rng, |_, _, rho, m| {
            let r = (rho / (m as f64 * st_max as f64)) as f32;
            for l in 0..n {
                tr.0[l] *= (1.0 - r * st.0[l]).max(0.0);
            }
            tr.0[..n].iter().any(|&x| x != 0.0)
        });
        tr
    }

    /// Tentative collisions over `[from, to]` at each block's majorant times `sigma`
    /// (exponential steps restarted at every block face, as memorylessness allows), calling
    /// `at(rng, t, rho(t), majorant)` at each until it returns false. Shared by delta and
    /// ratio tracking.
    fn tentative<R: Rng + ?Sized>(
        &self,
        (from, to): (f32, f32),
        sigma: f32,
        rng: &mut R,
        mut at: impl FnMut(&mut R, f64, f64, f32) -> bool,
    ) {
        let (a, b) = self.ray;
        self.majorant
            .segments(self.ray, from as f64, to as f64, |t0, t1, m| {
                if m <= 0.0 {
                    return true;
                }
                let rate = m as f64 * sigma as f64;
                let mut t = t0;
                loop {
                    t += exp_step(rate, rng.random());
                    if t >= t1 {
                        return true;
                    }
                    let rho = self.majorant.grid().at_index_in_box(a + b * t);
                    if !at(rng, t, rho, m) {
                        return false;
                    }
                }
            });
    }
}

#[cfg(test)]
mod tests;
