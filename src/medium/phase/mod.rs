//! Phase functions: a closed set, each exactly evaluated and exactly sampled.
//!
//! Convention (all variants): `cos` is the cosine between the *propagation* directions of
//! light before and after scattering, densities are per steradian and integrate to 1 over the
//! sphere. A camera ray of direction `u` gathering light that travels along `v` uses
//! `eval(-u.dot(v))`.
//!
//! Bin-independent phases (every variant but a multi-lane `tabulated`) serve every spectral bin
//! with one value: `eval`, `sample_cos`, `sample_dir`. Phases that vary per bin are used
//! through the per-bin interface: `eval_bins` (one density per bin) and `sample_bins`, which
//! samples the mixture `p_mix = Σ_l P_l p_l` of the bins' phases for probabilities `P` the
//! caller chooses (e.g. from the ray's spectral weights) and returns the per-bin weights
//! `p_l / p_mix` that keep every bin unbiased. For bin-independent phases `sample_bins` returns
//! exactly `sample_dir`'s direction (same random numbers) with all weights 1.

mod desc;
mod draine;
mod hg;
mod hg_draine;
mod rayleigh;
mod table_csv;
mod tabulated;
mod two_term_hg;

use glam::Vec3;
use std::f32::consts::PI;

use crate::spectrum::Spectrum;

pub use desc::PhaseDesc;
pub use draine::Draine;
pub use hg::HenyeyGreenstein;
pub use hg_draine::{HgDraine, MAX_DIAMETER, fit as hg_draine_fit};
pub use rayleigh::Rayleigh;
pub use table_csv::PhaseCsv;
pub use tabulated::{PhaseTable, intern};
pub use two_term_hg::TwoTermHg;

/// Every phase function brume knows (scene key `phase.type`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Phase {
    /// `hg`: Henyey–Greenstein (also what the short form `g = ...` means).
    Hg(HenyeyGreenstein),
    /// `two-term-hg`: a mixture of two HG lobes.
    TwoTermHg(TwoTermHg),
    /// `rayleigh`: small particles, `3 (1 + cos²) / 16π`.
    Rayleigh(Rayleigh),
    /// `draine`: Draine's generalisation of HG.
    Draine(Draine),
    /// `hg-draine`: Jendersie & d'Eon's droplet fit by diameter.
    HgDraine(HgDraine),
    /// `tabulated`: a table in cos θ, one lane per bin or one for all (also the per-bin Lorenz–
    /// Mie phase of `[media.NAME.droplets]`).
    Tabulated(&'static PhaseTable),
}

/// A direction sampled from a phase mixture, with the per-bin weights `p_l / p_mix`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PhaseSample {
    /// The new propagation direction (unit).
    pub dir: Vec3,
    /// Per bin `p_l(cos) / p_mix(cos)` (0 past the active bins); all 1 for a phase that is the
    /// same in every bin.
    pub weight: Spectrum,
}

impl Phase {
    /// Henyey–Greenstein with asymmetry `g`.
    pub fn hg(g: f32) -> Result<Self, crate::medium::MediumError> {
        HenyeyGreenstein::new(g).map(Phase::Hg)
    }

    /// Whether the density differs between spectral bins (a multi-lane table).
    pub fn varies_per_bin(&self) -> bool {
        match self {
            Phase::Tabulated(t) => t.lanes() > 1,
            Phase::Hg(_)
            | Phase::TwoTermHg(_)
            | Phase::Rayleigh(_)
            | Phase::Draine(_)
            | Phase::HgDraine(_) => false,
        }
    }

    /// A one-line description for `brume info`.
    pub fn describe(&self) -> String {
        match self {
            Phase::Hg(p) => format!("hg, g = {}", p.g()),
            Phase::TwoTermHg(p) => format!("two-term-hg, mean cosine {:.4}", p.g()),
            Phase::Rayleigh(_) => "rayleigh".into(),
            Phase::Draine(p) => format!("draine, mean cosine {:.4}", p.g()),
            Phase::HgDraine(p) => {
                let (hg, d, w) = p.parts();
                format!(
                    "hg-draine for {} µm droplets: (1 - {w:.4}) HG({:.4}) + {w:.4} Draine({:.4}, \
                     alpha {:.2})",
                    p.diameter(),
                    hg.g(),
                    d.g_param(),
                    d.alpha()
                )
            }
            Phase::Tabulated(t) => format!(
                "tabulated ({}; {} angles, {})",
                t.source(),
                t.nodes(),
                if t.lanes() > 1 {
                    "one lane per bin"
                } else {
                    "the same in every bin"
                }
            ),
        }
    }

    /// Mean cosine; for a per-bin phase, that of the bins' average phase.
    pub fn g(&self) -> f32 {
        match self {
            Phase::Hg(p) => p.g(),
            Phase::TwoTermHg(p) => p.g(),
            Phase::Rayleigh(_) => 0.0,
            Phase::Draine(p) => p.g(),
            Phase::HgDraine(p) => p.g(),
            Phase::Tabulated(t) => t.g(),
        }
    }

    /// Mean cosine per bin (bins `0..n`).
    pub fn g_bins(&self, n: usize) -> Spectrum {
        match self {
            Phase::Tabulated(t) if t.lanes() > 1 => {
                let mut s = Spectrum::ZERO;
                for (l, v) in s.0.iter_mut().enumerate().take(n) {
                    *v = t.g_lane(l);
                }
                s
            }
            Phase::Tabulated(_)
            | Phase::Hg(_)
            | Phase::TwoTermHg(_)
            | Phase::Rayleigh(_)
            | Phase::Draine(_)
            | Phase::HgDraine(_) => Spectrum::splat(self.g(), n),
        }
    }

    /// Density per steradian at `cos` (a per-bin phase gives its bins' average, which is
    /// right only for light whose bins are equally weighted: use `eval_bins` for those).
    #[inline]
    pub fn eval(&self, cos: f32) -> f32 {
        match self {
            Phase::Hg(p) => p.eval(cos),
            Phase::TwoTermHg(p) => p.eval(cos),
            Phase::Rayleigh(p) => p.eval(cos),
            Phase::Draine(p) => p.eval(cos),
            Phase::HgDraine(p) => p.eval(cos),
            Phase::Tabulated(t) => t.eval(cos),
        }
    }

    /// Value for a camera ray of direction `u` gathering light that travels along `v`.
    #[inline]
    pub fn eval_uv(&self, u: Vec3, v: Vec3) -> f32 {
        self.eval(-u.dot(v))
    }

    /// Density of every bin at `cos` (bins `0..n`, zero past them).
    #[inline]
    pub fn eval_bins(&self, cos: f32, n: usize) -> Spectrum {
        match self {
            Phase::Tabulated(t) if t.lanes() > 1 => t.eval_bins(cos, n),
            Phase::Tabulated(_)
            | Phase::Hg(_)
            | Phase::TwoTermHg(_)
            | Phase::Rayleigh(_)
            | Phase::Draine(_)
            | Phase::HgDraine(_) => Spectrum::splat(self.eval(cos), n),
        }
    }

    /// Samples a cosine from one uniform `xi` in [0, 1) by the exact inverse CDF (of the bins'
    /// average for a per-bin phase); its density is `2π eval(cos)`.
    #[inline]
    pub fn sample_cos(&self, xi: f32) -> f32 {
        match self {
            Phase::Hg(p) => p.sample_cos(xi),
            Phase::TwoTermHg(p) => p.sample_cos(xi),
            Phase::Rayleigh(p) => p.sample_cos(xi),
            Phase::Draine(p) => p.sample_cos(xi),
            Phase::HgDraine(p) => p.sample_cos(xi),
            Phase::Tabulated(t) => t.sample_cos(xi),
        }
    }

    /// Samples a new propagation direction given the incoming propagation direction `w`
    /// (unit); the result's density is `eval(w.dot(result))`. Camera paths pass the camera
    /// ray's direction: every phase here depends on the angle only, so reversing both
    /// directions leaves it unchanged.
    #[inline]
    pub fn sample_dir(&self, w: Vec3, xi1: f32, xi2: f32) -> Vec3 {
        match self {
            // HG keeps its own routine so that HG media render bit for bit as before.
            Phase::Hg(p) => p.sample_dir(w, xi1, xi2),
            Phase::TwoTermHg(_)
            | Phase::Rayleigh(_)
            | Phase::Draine(_)
            | Phase::HgDraine(_)
            | Phase::Tabulated(_) => around(w, self.sample_cos(xi1), xi2),
        }
    }

    /// Samples the mixture `Σ_l P_l p_l` of the bins' phases (`pick` = P over bins `0..n`,
    /// non-negative, summing to 1, and positive wherever a bin's light matters) and returns
    /// the direction with the per-bin weights `p_l / p_mix`. `xi[0]` picks the bin, `xi[1]`
    /// and `xi[2]` sample its phase. Unbiased per bin: E[weight_l g(dir)] = ∫ p_l g for every
    /// g, whatever P, as long as P_l > 0 where p_l > 0. Bounded by `1 / P_l`.
    pub fn sample_bins(&self, w: Vec3, pick: &Spectrum, n: usize, xi: [f32; 3]) -> PhaseSample {
        let Phase::Tabulated(t) = self else {
            return PhaseSample {
                dir: self.sample_dir(w, xi[1], xi[2]),
                weight: Spectrum::splat(1.0, n),
            };
        };
        if t.lanes() == 1 {
            return PhaseSample {
                dir: self.sample_dir(w, xi[1], xi[2]),
                weight: Spectrum::splat(1.0, n),
            };
        }
        let lane = pick_bin(pick, n, xi[0]);
        let cos = t.sample_lane(lane, xi[1]);
        let dir = around(w, cos, xi[2]);
        // Evaluate at the direction actually returned (after normalisation in f32).
        let c = w.dot(dir).clamp(-1.0, 1.0);
        PhaseSample {
            dir,
            weight: self.mixture_weights(c, pick, n),
        }
    }

    /// `p_mix(cos) = Σ_l P_l p_l(cos)`: the density of `sample_bins`' directions.
    pub fn pdf_mix(&self, cos: f32, pick: &Spectrum, n: usize) -> f32 {
        let p = self.eval_bins(cos, n);
        (0..n).map(|l| pick.0[l] * p.0[l]).sum()
    }

    /// Per bin `p_l(cos) / p_mix(cos)` (0 where p_mix is 0).
    pub fn mixture_weights(&self, cos: f32, pick: &Spectrum, n: usize) -> Spectrum {
        let p = self.eval_bins(cos, n);
        let mix: f32 = (0..n).map(|l| pick.0[l] * p.0[l]).sum();
        if mix > 0.0 {
            p * (1.0 / mix)
        } else {
            Spectrum::ZERO
        }
    }
}

/// Bin `l` with probability `pick[l]` (bins `0..n`) by the cumulative sum.
fn pick_bin(pick: &Spectrum, n: usize, xi: f32) -> usize {
    let mut acc = 0.0;
    for l in 0..n {
        acc += pick.0[l];
        if xi < acc {
            return l;
        }
    }
    // Rounding left xi above the last partial sum: the last bin with any probability.
    (0..n).rev().find(|&l| pick.0[l] > 0.0).unwrap_or(0)
}

/// The unit direction at cosine `cos` from `w` and azimuth `2π xi`.
#[inline]
fn around(w: Vec3, cos: f32, xi: f32) -> Vec3 {
    let sin = (1.0 - cos * cos).max(0.0).sqrt();
    let (a, b) = w.any_orthonormal_pair();
    let (sp, cp) = (2.0 * PI * xi).sin_cos();
    (w * cos + a * (sin * cp) + b * (sin * sp)).normalize()
}
