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
//! structure in x, most of all in backscattering (the glory): an adaptive rule chases every
//! resonance (scatrs' own ensemble needed ~1000 Gauss–Kronrod panels per wavelength for this),
//! whereas evenly spaced nodes fine enough to sample the ripple average it. Measured on a
//! lognormal water fog (r_eff = 5 µm, σ_g = 1.5) at 450 and 550 nm against a 4x finer
//! integration (tests/python/test_mie.py): with the default Δx = 0.02, σ_ext and g agree to
//! 1e-4, the phase at 0°, 30°, 90° and 140° to 0.3% and at 180° to 0.7%; Δx = 0.05 leaves
//! 1-1.5% at 180°.

use std::f64::consts::PI;

use num_complex::Complex;
use scatrs::mie::{AngularTable, Mie, MieOptions, Normalization, PhaseBuffers, n_terms};

use super::size::SizeDistribution;
use crate::medium::MediumError;

/// Default node spacing in size parameter (see the module notes for its measured accuracy).
pub const DEFAULT_STEP: f64 = 0.02;

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

/// The per-angle sums dominate a node's cost, and how finely the size integral must be
/// sampled depends on the angle: the forward cone converges at 4x the base spacing (measured
/// 0.2% at 30°), side scattering at 2x, while the glory (backscattering) needs the base
/// spacing to average its resonances. So angles go into three tiers, each summed over every
/// `stride`-th node: (smallest cosine of the tier, stride).
const TIERS: [(f64, usize); 3] = [(0.5, 4), (-0.984_807_753_012_208, 2), (-2.0, 1)];

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
    let (r_lo, dr, nodes) = nodes(dist, k, step);
    if nodes > 2_000_000 {
        let r_hi = r_lo + nodes as f64 * dr;
        return Err(MediumError::Droplets(format!(
            "droplets up to {r_hi:.3e} µm at {lambda_um} µm need {nodes} Lorenz-Mie solutions per \
             wavelength; use a narrower distribution or a larger quadrature step"
        )));
    }
    let opts = MieOptions::new();
    // The last node, not the range's end: it may lie up to one spacing beyond it.
    let n_max = n_terms(k * (r_lo + nodes as f64 * dr), m, &opts).map_err(mie_err)?;
    let mut tiers = Vec::new();
    let mut upper = f64::INFINITY;
    for (lowest, stride) in TIERS {
        let index = (0..mu.len())
            .filter(|&j| mu[j] > lowest && mu[j] <= upper)
            .collect();
        tiers.push((Angles::new(mu, index, n_max)?, stride));
        upper = lowest;
    }
    let mut mie = Mie::<f64>::new();
    let (mut ext, mut sca, mut abs, mut sca_g) = (0.0, 0.0, 0.0, 0.0);
    // Normalise n(r) at its peak so that the weights stay O(1).
    let peak = (0..=nodes)
        .map(|i| dist.ln_density(r_lo + i as f64 * dr))
        .fold(f64::NEG_INFINITY, f64::max);
    // The number of droplets in the same units as the weights' sum (∫ n dr = dr Σ w), over
    // all radii: see `SizeDistribution::ln_count`.
    let count = (dist.ln_count() - peak).exp() / dr;
    for i in 0..=nodes {
        let r = r_lo + i as f64 * dr;
        // Trapezoid weights; the end weights are 1/2 (their integrand is ~1e-5 of the peak).
        let end = if i == 0 || i == nodes { 0.5 } else { 1.0 };
        let w = end * (dist.ln_density(r) - peak).exp();
        let sphere = mie.compute(k * r, m, &opts).map_err(mie_err)?;
        let q = sphere.efficiencies();
        let wa = w * PI * r * r;
        ext += wa * q.q_ext;
        sca += wa * q.q_sca;
        abs += wa * q.q_abs;
        sca_g += wa * q.q_sca * q.g;
        for (set, stride) in &mut tiers {
            if i % *stride == 0 {
                set.add(&sphere, wa * *stride as f64)?;
            }
        }
    }
    if !(sca > 0.0 && count > 0.0) {
        return Err(MediumError::Droplets(
            "the droplets scatter no light at this wavelength".into(),
        ));
    }
    let mut phase = vec![0.0; mu.len()];
    for (set, _) in &tiers {
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

/// Fewest radii in a size integral: a narrow distribution of small droplets spans less than
/// a few node spacings in size parameter, and a handful of trapezoid nodes would not resolve
/// its shape.
const MIN_NODES: f64 = 64.0;

/// The size integral's first radius (µm), node spacing (µm) and number of intervals at
/// wavenumber `k` (1/µm): `step / k` apart over `dist.range()`, or closer for a range
/// narrower than `MIN_NODES` such spacings.
fn nodes(dist: &SizeDistribution, k: f64, step: f64) -> (f64, f64, usize) {
    let (r_lo, r_hi) = dist.range();
    let dr = (step / k).min((r_hi - r_lo) / MIN_NODES);
    (r_lo, dr, ((r_hi - r_lo) / dr).ceil().max(2.0) as usize)
}

/// About how many Lorenz-Mie terms (series orders, ~x + 4 x^(1/3) + 2 per radius) [`ensemble`]
/// sums for `dist` at `lambda_um` (µm) with node spacing `step`: what its time is proportional
/// to, as each term also enters the phase-function sums. Evaluated at the middle radius (exact
/// for the linear part, which dominates).
pub fn terms(dist: &SizeDistribution, lambda_um: f64, step: f64) -> f64 {
    let k = 2.0 * PI / lambda_um;
    let (r_lo, dr, nodes) = nodes(dist, k, step);
    let x = k * (r_lo + 0.5 * nodes as f64 * dr);
    (nodes + 1) as f64 * (x + 4.0 * x.cbrt() + 2.0)
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
