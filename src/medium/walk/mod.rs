use super::{Along, Medium, MediumError, MixEval, Mixture, Tracker};
use crate::spectrum::Spectrum;
use rand::Rng;

/// How a camera segment ends (method note 4).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum WalkEnd {
    /// Real extinction at distance `s`, decided as a scattering: multiply the path throughput by
    /// `weight` (per bin `ss_l e^{-st_l s} / Σ_k P_k ss_k e^{-st_k s}`), sample a new direction
    /// from the phase function and start a new segment there, with a new mixture and no sphere at
    /// its start point.
    Scattered { s: f32, weight: Spectrum },
    /// Real extinction at `s` decided as an absorption: the path ends.
    Absorbed { s: f32 },
    /// No extinction in `[0, T]`: multiply the throughput by `weight` (`e^{-st_l T} / Tmix(T)`)
    /// and continue at the segment's end (surface or medium boundary). For `T = +inf` the weight
    /// is nonzero only in bins without extinction.
    Transmitted { weight: Spectrum },
}

impl WalkEnd {
    /// The outcome of a walk made in optical depth `u` (a medium with a density field, see
    /// `medium::density`) with its extinction placed at the distance `s(u)` along the ray,
    /// within the segment's length `len`. Weights are unchanged: in `u` the segment is the
    /// homogeneous medium.
    #[inline]
    pub fn at_distance(self, along: &Along, len: f32) -> Self {
        match self {
            WalkEnd::Scattered { s, weight } => WalkEnd::Scattered {
                s: along.distance(s).min(len),
                weight,
            },
            WalkEnd::Absorbed { s } => WalkEnd::Absorbed {
                s: along.distance(s).min(len),
            },
            WalkEnd::Transmitted { weight } => WalkEnd::Transmitted { weight },
        }
    }
}

/// The camera-side multiple-integration-sphere walk along one medium segment (method note 2).
/// `q = 1` is the single sphere at the first extinction.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MultiSphereWalk {
    q: f32,
    /// Sub-step rate over `st_l0`: `1 / q` (method notes 2-3). Only the test of the paper's
    /// typo builds another.
    rate_scale: f32,
}

impl MultiSphereWalk {
    /// `q` in (0, 1]: the probability that a sub-step ends in a real extinction; the expected
    /// number of spheres per segment is `(1/q) Σ P_l (1 - e^{-st_l T})`.
    pub fn new(q: f32) -> Result<Self, MediumError> {
        if q > 0.0 && q <= 1.0 {
            Ok(Self {
                q,
                rate_scale: 1.0 / q,
            })
        } else {
            Err(MediumError::Q(q))
        }
    }

    /// The paper's colour section as printed (rate `q st`), known to be biased: for the test
    /// that proves it only.
    #[cfg(test)]
    pub(crate) fn paper_typo_biased(q: f32) -> Result<Self, MediumError> {
        Ok(Self {
            rate_scale: q,
            ..Self::new(q)?
        })
    }

    /// The control parameter q.
    pub fn q(&self) -> f32 {
        self.q
    }

    /// Walks one segment of length `seg_len` (may be `+inf`): its optical depth at density 1,
    /// or, with a `track`er (a grey medium tracked by null collisions), its distance. For every sphere, at distance `s`
    /// in `[0, seg_len)`, calls `on_sphere(s, w)` with the per-bin sphere weight
    /// `w_l = q ss_l e^{-st_l s} / pdf_mix(s)`; the engine multiplies it by the path throughput
    /// and by the sphere's reading `f Phi_l / (pi R^2)`. The sphere at a real extinction is
    /// reported (via `on_sphere`) before the extinction outcome is returned.
    #[inline]
    pub fn walk<R, F>(
        &self,
        medium: &Medium,
        (mix, track): (&Mixture, Option<&Tracker>),
        seg_len: f32,
        rng: &mut R,
        mut on_sphere: F,
    ) -> WalkEnd
    where
        R: Rng + ?Sized,
        F: FnMut(f32, &Spectrum),
    {
        self.walk_eval(medium, (mix, track), seg_len, rng, |s, e| {
            let w = medium.sigma_s * e.tr * (self.q / e.pdf);
            on_sphere(s, &w);
        })
    }

    /// The same walk (same random numbers, same outcome) reporting each sphere's weight in
    /// factored form, `on_sphere(s, c)` with `c = q / pdf_mix(s)` scaled as [`MixEval`]: the
    /// sphere weight is `sigma_s,l e^{-(st_l - st_min) s} c`, which
    /// [`relative_extinction`](super::relative_extinction) lets a gather recompute per bin from
    /// `s` alone, so that spheres need not store a spectrum.
    #[inline]
    pub fn walk_scaled<R, F>(
        &self,
        medium: &Medium,
        (mix, track): (&Mixture, Option<&Tracker>),
        seg_len: f32,
        rng: &mut R,
        mut on_sphere: F,
    ) -> WalkEnd
    where
        R: Rng + ?Sized,
        F: FnMut(f32, f32),
    {
        self.walk_eval(medium, (mix, track), seg_len, rng, |s, e| {
            on_sphere(s, self.q / e.pdf)
        })
    }

    #[inline]
    fn walk_eval<R, F>(
        &self,
        medium: &Medium,
        (mix, track): (&Mixture, Option<&Tracker>),
        seg_len: f32,
        rng: &mut R,
        mut on_sphere: F,
    ) -> WalkEnd
    where
        R: Rng + ?Sized,
        F: FnMut(f32, &MixEval),
    {
        let l0 = mix.pick(rng.random());
        let mut s = 0.0f32;
        loop {
            s = match track {
                // Sub-steps at rate `st_l0 / q` in optical depth: exponential steps in `u`.
                None => s + mix.exp_step(l0, self.rate_scale, rng.random()),
                // The same sub-step process by null collisions, in distance (method note 10):
                // a grey medium's weights below do not depend on the depth.
                Some(t) => t
                    .free_flight(s, seg_len, mix.rate(l0, self.rate_scale), rng)
                    .unwrap_or(f32::INFINITY),
            };
            if s >= seg_len || s.is_nan() {
                return transmitted(mix, seg_len);
            }
            let e = mix.eval(s);
            // pdf can only underflow to 0 at depths of ~100 mean free paths of every bin;
            // such a sphere carries nothing.
            if e.pdf > 0.0 {
                on_sphere(s, &e);
            }
            if rng.random::<f32>() < self.q {
                return extinction(medium, mix, &e, s, rng);
            }
        }
    }
}

/// Samples only the real-extinction distance of a segment (density `pdf_mix`), for the truncated
/// cylinder: the cylinder spans `[0, s]` on extinction, `[0, seg_len]` when transmitted. Same
/// outcomes and weights as [`MultiSphereWalk::walk`] with q = 1, without spheres.
#[inline]
pub fn sample_extinction<R: Rng + ?Sized>(
    medium: &Medium,
    (mix, track): (&Mixture, Option<&Tracker>),
    seg_len: f32,
    rng: &mut R,
) -> WalkEnd {
    let s = match track {
        None => mix.sample_distance(rng.random(), rng.random()),
        Some(t) => {
            let l0 = mix.pick(rng.random());
            t.free_flight(0.0, seg_len, mix.rate(l0, 1.0), rng)
                .unwrap_or(f32::INFINITY)
        }
    };
    if s >= seg_len || s.is_nan() {
        return transmitted(mix, seg_len);
    }
    let e = mix.eval(s);
    extinction(medium, mix, &e, s, rng)
}

#[inline]
fn transmitted(mix: &Mixture, seg_len: f32) -> WalkEnd {
    WalkEnd::Transmitted {
        weight: mix.survival_weight(seg_len),
    }
}

/// Scatter/absorb roulette with the mixture-averaged albedo, and the per-bin throughput update
/// that keeps every bin unbiased (method note 4). Using the stepping bin's albedo instead is
/// biased in colour.
#[inline]
fn extinction<R: Rng + ?Sized>(
    medium: &Medium,
    mix: &Mixture,
    e: &MixEval,
    s: f32,
    rng: &mut R,
) -> WalkEnd {
    let sc = medium.sigma_s * e.tr;
    let num: f32 = (0..mix.n())
        .map(|l| mix.probabilities().0[l] * sc.0[l])
        .sum();
    if rng.random::<f32>() * e.pdf < num {
        WalkEnd::Scattered {
            s,
            weight: sc * (1.0 / num),
        }
    } else {
        WalkEnd::Absorbed { s }
    }
}

mod stratified;

#[cfg(test)]
mod tests;
