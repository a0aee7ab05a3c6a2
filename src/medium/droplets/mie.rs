//! Lorenz–Mie optics of a droplet size distribution at one wavelength.
//!
//! Each sphere is solved by the `scatrs` crate (Lorenz–Mie coefficients with a validated
//! accuracy; Bohren & Huffman 1983, ch. 4), and the size integral is ours: the trapezoid rule on
//! radii spaced evenly in size parameter, `Δx = 2π Δr / λ`.
//!
//! Why the trapezoid rule: the integrands `n(r) C(r)` vanish with all their derivatives at both
//! ends of the range (the distributions decay faster than any power, see `size::range`), so the
//! Euler–Maclaurin end corrections vanish and the error comes only from what varies faster than
//! the node spacing. What varies fast is the sphere's interference and resonance ("ripple")
//! structure in x, most of all in backscattering (the glory); an adaptive rule would have to
//! chase every resonance, whereas evenly spaced nodes average them. Measured on a lognormal of
//! r_eff = 5 µm, σ_g = 1.5 at 550 nm, against the converged value (scatrs' adaptive ensemble at
//! rtol 1e-4): Δx = 0.05 gives σ_ext and g to 1e-4, the phase at 0°, 30°, 90° and 140° to
//! 0.2% and at 180° to 0.8%; Δx = 0.1 doubles the phase errors (2% at 180°).

use std::f64::consts::PI;

use num_complex::Complex;
use scatrs::mie::{AngularTable, Mie, MieOptions, Normalization, PhaseBuffers, n_terms};

use super::size::SizeDistribution;
use crate::medium::MediumError;

/// Default node spacing in size parameter (see the module notes for its measured accuracy).
pub const DEFAULT_STEP: f64 = 0.05;

/// Distribution-averaged optics of one droplet at one wavelength.
#[derive(Clone, Debug, PartialEq)]
pub struct EnsembleOptics {
    /// Mean extinction, scattering and absorption cross sections per droplet (µm²).
    pub c_ext: f64,
    pub c_sca: f64,
    pub c_abs: f64,
    /// Asymmetry parameter `<C_sca g> / <C_sca>`.
    pub g: f64,
    /// Phase function (per steradian, `∫ p dω = 1`) at the requested cosines.
    pub phase: Vec<f64>,
    /// Number of droplet radii solved.
    pub nodes: usize,
}

fn mie_err(e: scatrs::Error) -> MediumError {
    MediumError::Droplets(format!("Lorenz-Mie solution failed: {e}"))
}

/// Forward of this angle (cos above `FORWARD_MU`) the phase is summed over every
/// `FORWARD_STRIDE`-th node only: there the ensemble converges at 4x the spacing (measured
/// 0.2% at 30°), and the per-angle sums dominate the cost of a node.
const FORWARD_MU: f64 = 0.5;
const FORWARD_STRIDE: usize = 4;

/// Averages over `dist` at wavelength `lambda_um` (µm) for refractive index `m` (n + ik,
/// k >= 0 absorbing), with the phase function at the cosines `mu`, nodes `step` apart in x.
pub fn ensemble(
    dist: &SizeDistribution,
    lambda_um: f64,
    m: Complex<f64>,
    mu: &[f64],
    step: f64,
) -> Result<EnsembleOptics, MediumError> {
    let k = 2.0 * PI / lambda_um;
    let (r_lo, r_hi) = dist.range();
    let dr = step / k;
    let nodes = ((r_hi - r_lo) / dr).ceil().max(2.0) as usize;
    if nodes > 2_000_000 {
        return Err(MediumError::Droplets(format!(
            "droplets up to {r_hi:.3e} µm at {lambda_um} µm need {nodes} Lorenz-Mie solutions per \
             wavelength; use a narrower distribution or a larger quadrature step"
        )));
    }
    let opts = MieOptions::new();
    let n_max = n_terms(k * r_hi, m, &opts).map_err(mie_err)?;
    // Two angle sets: all nodes for side and back scattering, every FORWARD_STRIDE-th for the
    // forward cone (see FORWARD_MU).
    let (fwd, rest): (Vec<usize>, Vec<usize>) = (0..mu.len()).partition(|&j| mu[j] > FORWARD_MU);
    let mut sets = [Angles::new(mu, fwd, n_max)?, Angles::new(mu, rest, n_max)?];
    let mut mie = Mie::<f64>::new();
    let (mut count, mut ext, mut sca, mut abs, mut sca_g) = (0.0, 0.0, 0.0, 0.0, 0.0);
    // Normalise n(r) at its peak so that the weights stay O(1).
    let peak = (0..=nodes)
        .map(|i| dist.ln_density(r_lo + i as f64 * dr))
        .fold(f64::NEG_INFINITY, f64::max);
    for i in 0..=nodes {
        let r = r_lo + i as f64 * dr;
        // Trapezoid weights; the end weights are 1/2 (their integrand is ~1e-5 of the peak).
        let end = if i == 0 || i == nodes { 0.5 } else { 1.0 };
        let w = end * (dist.ln_density(r) - peak).exp();
        let sphere = mie.compute(k * r, m, &opts).map_err(mie_err)?;
        let q = sphere.efficiencies();
        let wa = w * PI * r * r;
        count += w;
        ext += wa * q.q_ext;
        sca += wa * q.q_sca;
        abs += wa * q.q_abs;
        sca_g += wa * q.q_sca * q.g;
        if i % FORWARD_STRIDE == 0 {
            sets[0].add(&sphere, wa * FORWARD_STRIDE as f64)?;
        }
        sets[1].add(&sphere, wa)?;
    }
    if !(sca > 0.0 && count > 0.0) {
        return Err(MediumError::Droplets(
            "the droplets scatter no light at this wavelength".into(),
        ));
    }
    let mut phase = vec![0.0; mu.len()];
    for set in &sets {
        for (&j, f) in set.index.iter().zip(&set.sum) {
            // ½∫F dmu = 1 after dividing by <C_sca>; per steradian p = F / 4π.
            phase[j] = f / sca / (4.0 * PI);
        }
    }
    Ok(EnsembleOptics {
        c_ext: ext / count,
        c_sca: sca / count,
        c_abs: abs / count,
        g: sca_g / sca,
        phase,
        nodes: nodes + 1,
    })
}

/// A subset of the requested angles with its precomputed angular functions and running sums
/// of `w C_sca F11` (F11 normalised to ½∫F11 dmu = 1).
struct Angles {
    index: Vec<usize>,
    table: Option<AngularTable<f64>>,
    sum: Vec<f64>,
    buf: [Vec<f64>; 4],
}

impl Angles {
    fn new(mu: &[f64], index: Vec<usize>, n_max: usize) -> Result<Self, MediumError> {
        let sub: Vec<f64> = index.iter().map(|&j| mu[j]).collect();
        let table = if sub.is_empty() {
            None
        } else {
            Some(AngularTable::new(&sub, n_max).map_err(mie_err)?)
        };
        Ok(Self {
            sum: vec![0.0; sub.len()],
            buf: std::array::from_fn(|_| vec![0.0; sub.len()]),
            index,
            table,
        })
    }

    /// Adds `weight` x the sphere's unnormalised F11 (Q_sca times the normalised phase, so
    /// that `weight = w π r²` makes the sum `<C_sca F>`).
    fn add(
        &mut self,
        sphere: &scatrs::mie::MieSolution<'_, f64>,
        weight: f64,
    ) -> Result<(), MediumError> {
        let Some(table) = &self.table else {
            return Ok(());
        };
        let [f11, f12, f33, f34] = &mut self.buf;
        sphere
            .phase_matrix_from_table(
                table,
                Normalization::Unnormalized,
                PhaseBuffers { f11, f12, f33, f34 },
            )
            .map_err(mie_err)?;
        for (s, f) in self.sum.iter_mut().zip(f11.iter()) {
            *s += weight * f;
        }
        Ok(())
    }
}
