use std::sync::Arc;

use super::{Density, MediumError, Phase};
use crate::medium::tracking::{Majorant, Tracking, TrackingError};
use crate::spectrum::{MAX_BINS, Spectrum};

/// A medium: per-bin scattering and absorption coefficients in 1/m where its density is 1, a
/// phase function (the same in every bin, or one per bin: see [`Phase`]) and the density field
/// that scales the coefficients in space (`sigma(x) = rho(x) sigma`, uniform by default: the
/// homogeneous medium). `sigma_t = sigma_s + sigma_a`; lanes past `n` are zero.
///
/// Fields are public for reading in hot loops; build it with [`Medium::new`], which
/// validates, so that the invariants hold.
#[derive(Clone, Debug, PartialEq)]
pub struct Medium {
    /// Scattering coefficient per bin (1/m).
    pub sigma_s: Spectrum,
    /// Absorption coefficient per bin (1/m).
    pub sigma_a: Spectrum,
    /// Extinction `sigma_s + sigma_a` per bin (1/m).
    pub sigma_t: Spectrum,
    /// Phase function.
    pub phase: Phase,
    /// Number of active spectral bins.
    pub n: usize,
    /// All active bins share one sigma_t: per-bin exponentials are then all the same number.
    pub grey: bool,
    /// Where the medium is: `rho(x)` (method note 10).
    pub density: Density,
    /// The majorant grid when the medium's transport tracks null collisions (`tracking`),
    /// None for the exact change of variable.
    pub tracking: Option<Arc<Majorant>>,
}

impl Medium {
    /// A Henyey–Greenstein medium: see [`Medium::with_phase`]; |g| < 1.
    pub fn new(
        sigma_s: &Spectrum,
        sigma_a: &Spectrum,
        g: f32,
        n: usize,
    ) -> Result<Self, MediumError> {
        Self::with_phase(sigma_s, sigma_a, Phase::hg(g)?, n)
    }

    /// Validates (`n` in 1..=MAX_BINS, coefficients finite and >= 0 in the first `n` bins, a
    /// per-bin phase with exactly `n` lanes) and zeroes the lanes past `n`.
    pub fn with_phase(
        sigma_s: &Spectrum,
        sigma_a: &Spectrum,
        phase: Phase,
        n: usize,
    ) -> Result<Self, MediumError> {
        if n == 0 || n > MAX_BINS {
            return Err(MediumError::BinCount { n, max: MAX_BINS });
        }
        for (what, s) in [("sigma_s", sigma_s), ("sigma_a", sigma_a)] {
            for (bin, &value) in s.0[..n].iter().enumerate() {
                if !(value.is_finite() && value >= 0.0) {
                    return Err(MediumError::Coefficient { what, bin, value });
                }
            }
        }
        if let Phase::Tabulated(t) = phase
            && t.lanes() > 1
            && t.lanes() != n
        {
            return Err(MediumError::PhaseLanes {
                lanes: t.lanes(),
                n,
            });
        }
        let mut ss = Spectrum::ZERO;
        let mut sa = Spectrum::ZERO;
        ss.0[..n].copy_from_slice(&sigma_s.0[..n]);
        sa.0[..n].copy_from_slice(&sigma_a.0[..n]);
        let st = ss + sa;
        let grey = st.0[..n].iter().all(|&x| x == st.0[0]);
        Ok(Self {
            sigma_s: ss,
            sigma_a: sa,
            sigma_t: st,
            phase,
            n,
            grey,
            density: Density::Uniform,
            tracking: None,
        })
    }

    /// The same medium with `density` (coefficients as given are those at `rho = 1`).
    pub fn with_density(self, density: Density) -> Self {
        Self { density, ..self }
    }

    /// The same medium with its transport by `tracking` (method note 10): delta and ratio
    /// tracking against a majorant of `block`³ samples (the global maximum for
    /// `Tracking::DeltaGlobal`), or the exact change of variable. Needs a grid density and a
    /// grey medium for the tracked kinds (`TrackingError` says which is missing).
    pub fn with_tracking(self, tracking: Tracking, block: usize) -> Result<Self, TrackingError> {
        let block = match tracking {
            Tracking::Exact => {
                return Ok(Self {
                    tracking: None,
                    ..self
                });
            }
            Tracking::Delta => Some(block),
            Tracking::DeltaGlobal => None,
        };
        let Density::Grid(grid) = &self.density else {
            return Err(TrackingError::NotGrid(self.density.describe()));
        };
        if !self.grey {
            return Err(TrackingError::Chromatic);
        }
        let majorant = Arc::new(Majorant::new(grid.clone(), block));
        Ok(Self {
            tracking: Some(majorant),
            ..self
        })
    }

    /// From per-bin extinction (1/m) and single-scattering albedo, the paper's parametrisation:
    /// sigma_s = albedo sigma_t, sigma_a = (1 - albedo) sigma_t. Slices give bins 0..len.
    pub fn from_extinction_albedo(
        sigma_t: &[f32],
        albedo: &[f32],
        g: f32,
    ) -> Result<Self, MediumError> {
        let n = sigma_t.len().min(albedo.len());
        let ss: Vec<f32> = (0..n).map(|l| sigma_t[l] * albedo[l]).collect();
        let sa: Vec<f32> = (0..n).map(|l| sigma_t[l] * (1.0 - albedo[l])).collect();
        Self::new(&Spectrum::from_slice(&ss), &Spectrum::from_slice(&sa), g, n)
    }

    /// Mean cosine of the phase function (of the bins' average for a per-bin phase).
    pub fn g(&self) -> f32 {
        self.phase.g()
    }

    /// The phase function's density in every bin at `cos` (see [`Phase::eval_bins`]).
    #[inline]
    pub fn phase_bins(&self, cos: f32) -> Spectrum {
        self.phase.eval_bins(cos, self.n)
    }

    /// Per-bin single-scattering albedo (0 where sigma_t is 0).
    pub fn albedo(&self) -> Spectrum {
        self.sigma_s.safe_div(&self.sigma_t)
    }
}
