//! The tuner's choice from its measures: q per medium by the time-optimal rule (method note
//! 7), then the budgets that minimise variance x cost per pass, at the per-pixel and the block
//! scale (`blocks`).

use super::model::{self, BudgetSearch, CostSplit, NoiseSplit, QFit};
use super::{
    BUDGET_FACTOR, Gain, MAX_CAMERA_SAMPLES, Measure, PassConfig, Q_PILOT, RAYS_RANGE, Role, Tuner,
    Z_SIGNIFICANT,
};

/// An unresolved term of `NoiseSplit::from_four` (under `Z_SIGNIFICANT` standard errors)
/// counts as 0 when the pilots bound it, its `Z_SIGNIFICANT` standard errors under
/// `BOUND_SHARE` of the resolved terms' sum; one they neither resolve nor bound keeps its
/// estimate. Height-fog's camera term, 3.1e-3 +- 1.9e-3 beside resolved terms of 5.4e-2 on
/// seed 6, is bounded, and with it taken as 0 every seed tried chooses the most forward rays
/// (the fixed budgets' best); with its estimate kept, 5 seeds of 11 chose 46 000-160 000.
/// Fog-room-laser's, 2.3e4 +- 4.3e4 beside 2.4e5 (seed 2; its variance is rare bright
/// samples), is not: taken as 0 it sent the rays to the top of the range, where the cheapest
/// passes are the most efficient (docs/study.md).
const BOUND_SHARE: f64 = 0.25;

/// The terms of `NoiseSplit::from_four` as the choice takes them (`BOUND_SHARE`).
pub(super) fn bounded(terms: [Gain; 3]) -> [f64; 3] {
    let resolved: f64 = terms.iter().filter_map(|g| g.resolved()).sum();
    terms.map(|g| match g.resolved() {
        Some(v) => v,
        None if Z_SIGNIFICANT * g.se < BOUND_SHARE * resolved => 0.0,
        None => g.gain.max(0.0),
    })
}

impl Tuner {
    /// Sets the automatic media's q; returns the predicted variance and cost of a pass.
    pub(super) fn choose_q(
        &self,
        config: &mut PassConfig,
        b: Measure,
        report: &mut Vec<String>,
    ) -> (f64, f64) {
        let q_lo = Q_PILOT as f64;
        let (mut media, mut fits) = (Vec::new(), Vec::new());
        for m in 0..config.q.len() {
            let (Some((_, v)), Some(g)) =
                (self.measure(Role::Medium(m)), self.gain(Role::Medium(m)))
            else {
                continue;
            };
            let gain = g.significant();
            if gain <= 0.0 {
                report.push(format!(
                    "q[{m}] = 1: q = {q_lo} did not lower the variance by {Z_SIGNIFICANT} \
                     standard errors ({:.4e} vs {:.4e}: gain {:.4e} +- {:.1e} pixel by pixel)",
                    v.variance, b.variance, g.gain, g.se
                ));
                continue;
            }
            let (c1, c_lo) = (b.work.cost(), v.work.cost());
            fits.push(QFit::from_passes(
                b.variance,
                b.variance - gain,
                c1,
                c_lo,
                q_lo,
            ));
            media.push(m);
        }
        let (mut variance, mut cost) = (b.variance, b.work.cost());
        if fits.is_empty() {
            return (variance, cost);
        }
        let mut q = model::q_joint(&fits, b.variance, b.work.cost());
        let rest = b.variance - fits.iter().map(|f| f.slope).sum::<f64>();
        // A line through the pilots that falls below 0 (the variance at `Q_PILOT` under a
        // quarter of that at q = 1 for one medium) is no line a variance `S q + I` with I >= 0
        // can follow: the drop is noise or a bright sample at q = 1, and the model's optimum,
        // q -> 0 (`Q_MIN`), is an extrapolation past what the pilots measured. The lowest q
        // measured is kept instead. test_light_trace's spot fog, seed 7 (29.2 at q = 1, 2.02
        // at 0.25; a gain of 2.09 standard errors, where 7 other seeds keep q = 1): q = 0.25
        // renders 3.2x as efficiently as q = 0.03 (and q = 1 2.1x as efficiently again).
        if rest < 0.0 {
            for q in &mut q {
                *q = q.max(Q_PILOT);
            }
            report.push(format!(
                "q: the pilots' line falls below 0 before q = 0 (part not depending on q \
                 {rest:.4e}): q no lower than the pilots' {Q_PILOT}"
            ));
        }
        // With several media, q >= `Q_PILOT` for each can still leave that line below 0, and a
        // negative variance here scales the budgets' noise model negative: its search then
        // takes the costliest pass (the spot fog's seed 7 did, at q = 0.03, before the clamp
        // above). The part not depending on q is at least 0.
        variance = rest.max(0.0);
        for ((m, f), q) in media.iter().zip(&fits).zip(q) {
            config.q[*m] = q;
            variance += f.slope * q as f64;
            cost += f.sphere_cost * (1.0 / q as f64 - 1.0);
            report.push(format!(
                "q[{m}] = {q:.3}: variance per pass V(q) = {:.4e} q + rest (S = (1+eps)A - B), \
                 sphere cost c1 = {:.4e} s/q",
                f.slope, f.sphere_cost
            ));
        }
        report.push(format!(
            "q: variance not depending on q I = {rest:.4e}, base cost c0 = {:.4e} s",
            b.work.cost() - fits.iter().map(|f| f.sphere_cost).sum::<f64>()
        ));
        (variance, cost)
    }

    /// The automatic budgets when neither budget pilot bought a measurable gain, over every
    /// pixel or in the bulk (`Gain::resolved_or_bulk`): the variance is then ruled by rare
    /// bright samples (fog-room-laser: the laser's light gathered on surfaces) that two passes
    /// cannot measure, and the cheapest passes win, the most of them
    /// per second (fog-room-laser at 96 x 72: 10 000 forward rays and 1 camera path per pass,
    /// 2.7x the efficiency of 50 000 and 1; docs/study.md). Keeping the base, as an earlier
    /// version did, kept paying for rays that bought nothing.
    pub(super) fn cheapest(&self, config: &mut PassConfig, report: &mut Vec<String>) {
        let f = BUDGET_FACTOR * BUDGET_FACTOR;
        if self.auto_samples {
            config.camera_samples = 1;
        }
        if self.auto_rays {
            config.forward_rays = RAYS_RANGE.0.max(self.base.forward_rays / f);
        }
        report.push(format!(
            "budgets: the cheapest, camera paths {} and forward rays {}: more of either did \
             not lower the variance by {Z_SIGNIFICANT} standard errors, over every pixel or \
             without the largest {}% of differences",
            config.camera_samples,
            config.forward_rays,
            super::gain::TAIL_SHARE * 100.0
        ));
    }

    /// The noise model `a/s + b/N + c/(sN)` at the pilots' budgets `(s, n)` from the Base
    /// pilot's variance `v`, the Rays and Samples pilots' gains over it (None: not significant)
    /// and the terms measured from the four pilots' paired differences (`NoiseSplit::from_four`,
    /// its terms as `bounded` takes them), which exist whenever both gains do: the Both pilot
    /// is rendered whenever both budgets are automatic, and only an automatic budget has a
    /// gain. None when neither gain is significant.
    fn split(
        s: f64,
        n: f64,
        v: f64,
        gains: [Option<f64>; 2],
        terms: Option<[Gain; 3]>,
    ) -> Option<NoiseSplit> {
        let k = BUDGET_FACTOR as f64;
        match gains {
            [Some(_), Some(_)] => terms.map(|t| NoiseSplit::from_four(s, n, k, bounded(t))),
            [Some(gr), None] => Some(NoiseSplit::from_forward_rays(s, n, v, k, v - gr)),
            [None, Some(gs)] => Some(NoiseSplit::from_camera_samples(s, n, v, k, v - gs)),
            [None, None] => None,
        }
    }

    /// The per-pixel noise model at the pilots' budgets and, where the blocks resolve it, the
    /// block model (`blocks`); None when neither more forward rays nor more camera paths
    /// lowered the per-pixel variance significantly. A budget whose pilot did not lower the
    /// variance significantly stays as it is: the pilots say nothing about it; the block model
    /// uses a budget only where the per-pixel pilots resolved it.
    pub(super) fn noise_splits(&self, b: &Measure) -> Option<(NoiseSplit, Option<NoiseSplit>)> {
        let base = &self.pilots.first()?.1;
        let (s, n) = (base.camera_samples as f64, base.forward_rays as f64);
        let roles = [Role::Rays, Role::Samples];
        let gains = roles.map(|r| self.gain(r).and_then(Gain::resolved_or_bulk));
        let terms = self.four_terms_in(&self.shares);
        let split = Self::split(s, n, b.variance, gains, terms)?;
        let block_split = self.block_variance().and_then(|v| {
            let mut blocks = roles.map(|r| self.block_gain(r).and_then(Gain::resolved_or_bulk));
            for (g, p) in blocks.iter_mut().zip(&gains) {
                *g = g.filter(|_| p.is_some());
            }
            let terms = self.four_terms_in(&self.block_shares);
            Self::split(s, n, v, blocks, terms)
        });
        Some((split, block_split))
    }

    /// Sets the automatic budgets for a pass whose variance is `scale` times the base pilot's
    /// and whose cost is `cost`. The models are fitted at the pilots' budgets (`config`'s on
    /// entry); the search's range and the budgets the pilots say nothing about are the scene's.
    /// The budgets minimise the product of the per-pixel and the block variance (`blocks`)
    /// times the cost squared: each scale's efficiency counts alike. Without a significant
    /// block gain the per-pixel model decides alone.
    pub(super) fn choose_budgets(
        &self,
        config: &mut PassConfig,
        b: Measure,
        scale: f64,
        cost: f64,
        report: &mut Vec<String>,
    ) {
        let (s, n) = (config.camera_samples as f64, config.forward_rays as f64);
        let Some((split, block_split)) = self.noise_splits(&b) else {
            return self.cheapest(config, report);
        };
        let resolved = |r| self.gain(r).and_then(Gain::resolved_or_bulk).is_some();
        let (rays_gain, samples_gain) = (resolved(Role::Rays), resolved(Role::Samples));
        let noise = split.scaled(scale);
        // The base pass's cost parts, rescaled to the chosen q's cost.
        let [paths, volumes, rays, hits] = b.work.parts();
        let r = cost / b.work.cost().max(f64::MIN_POSITIVE);
        let costs = CostSplit {
            per_sample: (paths + volumes) * r / s,
            per_ray: rays * r / n,
            per_pair: hits * r / (s * n),
        };
        // The models are fitted near the pilots: search within a factor BUDGET_FACTOR^2 of
        // the scene's budgets, not far beyond; forward rays no further up than the Rays pilot
        // measured (BUDGET_FACTOR times the base). When the camera paths' own noise is small
        // (stratified spheres) variance x cost keeps falling slowly with the rays, and the
        // search ran to the range's top: on fog-cube 16 times the base, 3.3 s passes that
        // made a 10 s render take 13 s, chosen from a model extrapolated 4x past its pilots.
        let f = BUDGET_FACTOR * BUDGET_FACTOR;
        let base = &self.base;
        let search = BudgetSearch {
            samples: (!samples_gain).then_some(base.camera_samples),
            max_samples: MAX_CAMERA_SAMPLES.min(base.camera_samples * f as u32),
            rays: (!rays_gain).then_some(base.forward_rays),
            rays_range: (
                RAYS_RANGE.0.max(base.forward_rays / f),
                RAYS_RANGE.1.min(base.forward_rays * BUDGET_FACTOR),
            ),
        };
        let noises: Vec<NoiseSplit> = std::iter::once(noise).chain(block_split).collect();
        (config.camera_samples, config.forward_rays) = model::budgets(&noises, &costs, &search);
        if let Some([a, f, p]) = self.four_terms_in(&self.shares) {
            report.push(format!(
                "budgets, the four pilots' terms at their budgets (acted on beyond \
                 {Z_SIGNIFICANT} standard errors): camera {:.3e} +- {:.1e}, forward rays \
                 {:.3e} +- {:.1e}, pair {:.3e} +- {:.1e}",
                a.gain, a.se, f.gain, f.se, p.gain, p.se
            ));
        }
        if let Some(bs) = block_split {
            report.push(format!(
                "budgets, blocks of {k} x {k} pilot points: variance per pass = {:.4e}/paths + \
                 {:.4e}/rays + {:.4e}/(paths x rays)",
                bs.camera,
                bs.forward,
                bs.pair,
                k = super::blocks::BLOCK
            ));
        }
        report.push(format!(
            "budgets: camera paths {} and forward rays {}: variance per pass = {:.4e}/paths + \
             {:.4e}/rays + {:.4e}/(paths x rays), cost = {:.4e} paths + {:.4e} rays + {:.4e} \
             paths x rays s",
            config.camera_samples,
            config.forward_rays,
            noise.camera,
            noise.forward,
            noise.pair,
            costs.per_sample,
            costs.per_ray,
            costs.per_pair
        ));
    }
}
