//! `"auto"` settings (`integrator.q`, `forward_rays`, `camera_samples`) chosen from pilot
//! passes.
//!
//! The first passes of the seed's sequence, in a render with an automatic setting, are pilot
//! passes: pairs of passes at a few configurations (every q = 1 and the scene's budgets; each
//! automatic medium alone at q = [`Q_PILOT`]; the forward rays, the camera paths, and both,
//! times [`BUDGET_FACTOR`]). A pair gives an unbiased estimate of the image's variance per pass,
//! `sum over pixels of (x1 - x2)^2 / 2`, and the passes' work counters give their cost; the
//! models of [`model`] turn these into the chosen configuration, which every film pass uses.
//! With automatic budgets the pilots do not join the film (`Renderer::render_pass_until`): at
//! the base budgets one can carry many times a chosen pass's variance, and the film weighs its
//! passes equally. With q alone automatic they sample at the scene's budgets, and are film
//! passes (leaving them out cost fog-cube 13 % of its efficiency in a 20 CPU-s render).
//!
//! Why pilot passes and not a running re-estimate: a pass's configuration must follow from the
//! seed alone, so that a render resumed from a checkpoint, a `--pass-range` part and a merge
//! give the same bits whatever the thread count. The choice depends on the pilot passes only,
//! which every process renders (or has in its film) before it needs the choice; a choice that
//! moved with every pass would make pass 1000 depend on all passes before it. Costs are counted
//! work (camera paths, volumes, forward rays, gather hits, weighed by [`COST_WEIGHTS`]), not
//! measured time, for the same reason.

pub mod blocks;
mod changed;
mod choose;
mod gain;
pub mod model;
mod plan;
mod scattered_radius;
mod work;

use gain::Gain;
pub use gain::Z_SIGNIFICANT;

use super::nest::Nest;
use super::settings::{IntegratorDesc, VolumeKind};
pub use changed::{ChoiceChanged, settings_of};
use plan::PilotPass;
pub use work::{PilotResult, Work, pixel_totals, variant_work};
use work::{average, scaled};

/// The smallest q an automatic choice takes: about 33 spheres per camera segment in thick fog.
pub const Q_MIN: f32 = 0.03;
/// The q of the pilot passes that measure how a medium's variance falls with q.
pub const Q_PILOT: f32 = 0.25;
/// How much the budget pilot multiplies the forward rays (or the camera paths).
pub const BUDGET_FACTOR: u64 = 4;
/// Passes per pilot configuration: two give an unbiased variance per pixel.
pub const REPEATS: u64 = 2;
/// Pilots that are not film passes trace camera paths only in the pixels of every
/// `PILOT_STRIDE`-th row and column, and (with automatic forward rays) `PILOT_STRIDE^2` times
/// fewer forward rays than the base: each pilot costs about `PILOT_STRIDE^2` times less. Their
/// variance and pixel-bound work are scaled back to the whole image (`Tuner::record`); the
/// noise model is exact in its form (`model::NoiseSplit`), so fitting it at fewer rays only
/// makes its estimates noisier. Fog-cube at defaults: the pilots took 4.9 s of a 10 s render
/// before (docs/performance.md).
pub const PILOT_STRIDE: u32 = 2;
/// The budget search's limits: camera paths per pixel, and forward rays per pass.
pub const MAX_CAMERA_SAMPLES: u32 = 16;
pub const RAYS_RANGE: (u64, u64) = (10_000, 4_000_000);

/// Seconds per unit of work (camera path, volume record, forward ray, gather hit), measured
/// with a release build on fog-cube (2 threads; docs/study.md, "Automatic settings"). Only their
/// ratios matter: they weigh the counters into one cost. They are not the machine's true costs
/// any more (a refit to 48 fixed-budget passes on the eight protocol scenes, with the forward
/// segments as a fifth counter, predicts pass times twice as well), but the choices the refit
/// makes (more camera paths) measured 0-3 % worse per pixel and 10-20 % worse on 4x4 bins at
/// equal time: the noise model's camera term is biased high (clipped at 0), and these weights'
/// dearer camera paths offset it (docs/performance.md, "The cost weights, refitted, and not
/// kept").
pub const COST_WEIGHTS: [f64; 4] = [5.0e-6, 8.0e-7, 2.5e-6, 3.0e-7];

/// How one pass samples: q per medium, forward rays, camera paths per pixel.
#[derive(Clone, Debug, PartialEq)]
pub struct PassConfig {
    pub q: Vec<f32>,
    pub forward_rays: u64,
    pub camera_samples: u32,
    /// The radius for scattered light over the pass's radius (`Integrator::radii`): 1, or
    /// `radius::AUTO_INDIRECT_SCALE` where the Radius pilot chose it (`choose_radius`).
    pub indirect_scale: f32,
}

/// What a pilot configuration measures.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Role {
    /// Every automatic q at 1, the scene's (or default) budgets.
    Base,
    /// Medium `m` at `Q_PILOT`.
    Medium(usize),
    /// Forward rays times `BUDGET_FACTOR`.
    Rays,
    /// Camera paths per pixel times `BUDGET_FACTOR`.
    Samples,
    /// Both budgets times `BUDGET_FACTOR` (with both automatic): with Rays and Samples it
    /// splits the noise from the pilots' paired gains alone (`NoiseSplit::from_four`).
    Both,
    /// The Base configuration, rendered before the others to compare the Radius pilot with.
    Narrow,
    /// The radius for scattered light at `radius::AUTO_INDIRECT_SCALE` times the radius (with
    /// `radius` automatic and `radius_indirect = "auto"`).
    Radius,
}

/// Variance (with its standard error) and cost of a pilot configuration.
#[derive(Clone, Copy, Debug)]
struct Measure {
    variance: f64,
    se: f64,
    work: Work,
}

/// The configuration chosen, with the estimates behind it (printed by `brume render -v` and
/// written into the outputs' metadata).
#[derive(Clone, Debug, PartialEq)]
pub struct Choice {
    pub config: PassConfig,
    pub report: Vec<String>,
}

/// Plans the pilot passes and makes the choice from them.
#[derive(Clone, Debug)]
pub struct Tuner {
    /// The scene's configuration: the fixed values, and the fallbacks of the automatic ones.
    base: PassConfig,
    /// The configurations measured (`Role`), in report order; `measures`, `shares` and
    /// `block_shares` follow it.
    pilots: Vec<(Role, PassConfig)>,
    /// The passes rendered to measure them (`plan`).
    passes: Vec<PilotPass>,
    /// Image width and height (for the pilots' pixel lattice).
    resolution: (u32, u32),
    auto_rays: bool,
    auto_samples: bool,
    /// Whether the radius for scattered light is chosen (its pilots are the first passes).
    auto_radius: bool,
    /// Pilot passes recorded so far (always a prefix of the pilot passes).
    recorded: u64,
    /// Per role of the pass being recorded, the first pass's per-pixel totals, block means and
    /// work (empty until its first pass is recorded).
    first: Vec<(Vec<f64>, Vec<f64>, Work)>,
    measures: Vec<Measure>,
    /// Per measured pair, each pixel's `d = (x1 - x2)^2 / 2` times the lattice's scale: the
    /// pixel's share of the variance per pass (`Gain::paired` compares them pixel by pixel).
    shares: Vec<Vec<f64>>,
    /// The same per block of the pair's grid (`blocks`): the low-frequency noise.
    block_shares: Vec<Vec<f64>>,
    choice: Option<Choice>,
    /// What `choose_radius` found, for the choice's report.
    radius_report: Option<String>,
}

impl Tuner {
    /// The tuner of `desc` for a scene of `media` media and an image of `resolution` pixels,
    /// with the base configuration `base` (the fixed values, and the fallbacks of the automatic
    /// ones); None when nothing is automatic (or q is automatic but nothing depends on it).
    pub fn new(
        desc: &IntegratorDesc,
        media: usize,
        base: PassConfig,
        resolution: (u32, u32),
    ) -> Option<Self> {
        let spheres = desc.volume == VolumeKind::Spheres;
        let auto_q = desc.q.value().is_none() && spheres && media > 0;
        let auto_rays = desc.forward_rays.value().is_none();
        let auto_samples = desc.camera_samples.value().is_none();
        if !(auto_q || auto_rays || auto_samples) {
            return None;
        }
        // A second radius for scattered light is measured where the scene asks for it
        // (`radius_indirect = "auto"`: the pilots see noise, not blur), the pilots run anyway
        // and outside the film (automatic budgets: a film pass at another radius would blur the
        // image by a radius it did not choose) and the radius is automatic.
        let auto_radius = (auto_rays || auto_samples)
            && desc.radius.value().is_none()
            && desc.radius_indirect_auto();
        // Pilots outside the film (automatic budgets) sample with fewer forward rays.
        let mut pilot = base.clone();
        if auto_rays {
            let shrink = u64::from(PILOT_STRIDE * PILOT_STRIDE);
            pilot.forward_rays = (base.forward_rays / shrink).max(1);
        }
        let budgets = (auto_rays, auto_samples);
        let (pilots, passes) = plan::plan(&pilot, media, (auto_q, auto_radius), budgets, Q_PILOT);
        let roles = pilots.len();
        Some(Self {
            base,
            pilots,
            passes,
            resolution,
            auto_rays,
            auto_samples,
            auto_radius,
            recorded: 0,
            first: Vec::new(),
            measures: vec![
                Measure {
                    variance: 0.0,
                    se: 0.0,
                    work: Work::default(),
                };
                roles
            ],
            shares: vec![Vec::new(); roles],
            block_shares: vec![Vec::new(); roles],
            choice: None,
            radius_report: None,
        })
    }

    /// Number of pilot passes (the film's first passes).
    pub fn pilot_passes(&self) -> u64 {
        self.passes.len() as u64 * REPEATS
    }

    /// The estimates nested in pilot pass `pass` (`integrator::nest`), if it has any.
    pub fn nest(&self, pass: u64) -> Option<&Nest> {
        self.passes.get((pass / REPEATS) as usize)?.nest.as_ref()
    }

    /// The configurations pilot pass `pass` measures: its own, then each nested estimate's
    /// (in the nest's order).
    pub fn measured_configs(&self, pass: u64) -> Vec<PassConfig> {
        let Some(p) = self.passes.get((pass / REPEATS) as usize) else {
            return Vec::new();
        };
        let mut out = vec![p.config.clone()];
        let mut nested: Vec<(usize, usize)> = p
            .roles
            .iter()
            .filter_map(|(r, v)| v.map(|v| (v, *r)))
            .collect();
        nested.sort_unstable();
        out.extend(nested.into_iter().map(|(_, r)| self.pilots[r].1.clone()));
        out
    }

    /// Whether the pilot passes are film passes: only when the budgets are the scene's (q
    /// alone automatic), so that every pilot samples about as well as a chosen pass. Pilots at
    /// the base budgets are left out (`Renderer::render_pass_until`).
    pub fn pilots_join_film(&self) -> bool {
        !(self.auto_rays || self.auto_samples)
    }

    /// Film pass p is pass `p + film_offset()` of the seed's sequence. Pilots outside the
    /// film draw the first pair's numbers (`random_pass`), and film passes start after one pair
    /// per role: where they started before the budget pilots were nested in one pass, so that
    /// a film an earlier brume began never meets its own passes' numbers again when resumed.
    pub fn film_offset(&self) -> u64 {
        if self.pilots_join_film() {
            0
        } else {
            self.pilots.len() as u64 * REPEATS
        }
    }

    /// The camera pass of pass `pass` traces the pixels of every `stride`-th row and column
    /// (1: every pixel): pilots that are not film passes sample a lattice of the image.
    pub fn pixel_stride(&self, pass: u64) -> u32 {
        if pass < self.pilot_passes() && !self.pilots_join_film() {
            PILOT_STRIDE
        } else {
            1
        }
    }

    /// Pilot passes recorded so far; pass `recorded()` is the next one to record.
    pub fn recorded(&self) -> u64 {
        self.recorded
    }

    /// The configuration of pass `pass`: a pilot's, or the choice (None until it is made).
    pub fn config(&self, pass: u64) -> Option<&PassConfig> {
        match self.passes.get((pass / REPEATS) as usize) {
            Some(p) => Some(&p.config),
            None => self.choice.as_ref().map(|c| &c.config),
        }
    }

    /// The choice, once every pilot pass is recorded.
    pub fn choice(&self) -> Option<&Choice> {
        self.choice.as_ref()
    }

    /// Records pass `pass` (its per-pixel totals and work, and its nested estimates') if it is
    /// the next pilot pass. A pilot on a pixel lattice (`pixel_stride`) keeps the lattice's
    /// pixels, and its variance and pixel-bound work (camera paths, volumes, gather hits) are
    /// scaled to the whole image.
    pub fn record(&mut self, pass: u64, result: PilotResult) {
        if pass != self.recorded || pass >= self.pilot_passes() {
            return;
        }
        let roles = self.passes[(pass / REPEATS) as usize].roles.clone();
        let stride = self.pixel_stride(pass);
        let mut firsts = std::mem::take(&mut self.first).into_iter();
        let is_first = firsts.len() == 0;
        for (role, variant) in roles {
            let (totals, work) = match variant.and_then(|v| result.variants.get(v)) {
                Some((t, w)) => (t.as_slice(), *w),
                None => (result.totals.as_slice(), result.work),
            };
            let (totals, k, means) = self.sampled(totals, stride);
            let work = scaled(&work, k);
            if is_first {
                self.first.push((totals, means, work));
            } else if let Some(first) = firsts.next() {
                self.measure_pair(role, first, (&totals, &means, work), k);
            }
        }
        self.recorded += 1;
        if self.auto_radius && self.recorded == scattered_radius::PASSES * REPEATS {
            self.choose_radius();
        }
        if self.recorded == self.pilot_passes() {
            self.choice = Some(self.choose());
        }
    }

    /// A pass's totals on the pixels it traced, the factor from them to the whole image, and
    /// their block means (`blocks`).
    fn sampled(&self, totals: &[f64], stride: u32) -> (Vec<f64>, f64, Vec<f64>) {
        let totals = if stride > 1 {
            self.on_lattice(totals, stride)
        } else {
            totals.to_vec()
        };
        // A lattice of 1/k of the pixels: its sums times k estimate the image's.
        let k = self.pixels() as f64 / totals.len().max(1) as f64;
        let (w, h) = self.resolution;
        let grid = (w.div_ceil(stride) as usize, h.div_ceil(stride) as usize);
        let means = blocks::block_means(&totals, grid.0, grid.1);
        (totals, k, means)
    }

    /// Role `role`'s variance per pass from its pair: the first pass's totals, block means and
    /// work, and the second's, on a sample of 1/k of the pixels.
    fn measure_pair(
        &mut self,
        role: usize,
        (first, first_means, first_work): (Vec<f64>, Vec<f64>, Work),
        (totals, means, work): (&[f64], &[f64], Work),
        k: f64,
    ) {
        // Per pixel d = (x1 - x2)^2 / 2 is sigma^2 chi^2_1: E[d^2] = 3 sigma^4 and
        // Var(d) = 2 sigma^4 = (2/3) E[d^2], which gives the sum's standard error.
        let shares: Vec<f64> = first
            .iter()
            .zip(totals)
            .map(|(a, b)| 0.5 * (a - b) * (a - b) * k)
            .collect();
        let variance = shares.iter().sum();
        let d2 = shares.iter().map(|d| d * d).sum::<f64>();
        self.shares[role] = shares;
        self.block_shares[role] = first_means
            .iter()
            .zip(means)
            .map(|(a, b)| 0.5 * (a - b) * (a - b))
            .collect();
        self.measures[role] = Measure {
            variance,
            se: (2.0 / 3.0 * d2).sqrt(),
            work: average(&first_work, &work),
        };
    }

    fn pixels(&self) -> usize {
        self.resolution.0 as usize * self.resolution.1 as usize
    }

    /// The totals of the pixels on the lattice of every `stride`-th row and column.
    fn on_lattice(&self, totals: &[f64], stride: u32) -> Vec<f64> {
        let (w, h) = self.resolution;
        (0..h)
            .step_by(stride as usize)
            .flat_map(|y| (0..w).step_by(stride as usize).map(move |x| (x, y)))
            .filter_map(|(x, y)| totals.get((y * w + x) as usize).copied())
            .collect()
    }

    /// The configuration role `role` measures.
    #[cfg(test)]
    fn role_config(&self, role: Role) -> Option<&PassConfig> {
        self.pilots.iter().find(|(r, _)| *r == role).map(|(_, c)| c)
    }

    fn measure(&self, role: Role) -> Option<(&PassConfig, Measure)> {
        let i = self.pilots.iter().position(|(r, _)| *r == role)?;
        Some((&self.pilots[i].1, *self.measures.get(i)?))
    }

    /// How much pilot `role` lowered the variance below the Base pilot's, pixel by pixel
    /// (`Gain`); None when it was not measured.
    fn gain(&self, role: Role) -> Option<Gain> {
        self.gain_in(&self.shares, role)
    }

    /// The same for the block variance (`blocks`).
    fn block_gain(&self, role: Role) -> Option<Gain> {
        self.gain_in(&self.block_shares, role)
    }

    /// The Base pilot's block variance per pass.
    fn block_variance(&self) -> Option<f64> {
        self.block_variance_of(Role::Base)
    }

    fn gain_in(&self, shares: &[Vec<f64>], role: Role) -> Option<Gain> {
        self.gain_between(shares, Role::Base, role)
    }

    /// Pilot `role`'s per-pixel (or per-block) shares among `shares`.
    fn shares_of<'a>(&self, shares: &'a [Vec<f64>], role: Role) -> Option<&'a [f64]> {
        let i = self.pilots.iter().position(|(p, _)| *p == role)?;
        shares.get(i).map(Vec::as_slice)
    }

    /// The terms of `NoiseSplit::from_four` (camera, forward, pair), each a sum over pixels (or
    /// blocks) of `shares` with its standard error; None without the Both pilot.
    fn four_terms_in(&self, shares: &[Vec<f64>]) -> Option<[Gain; 3]> {
        let of = |r| self.shares_of(shares, r);
        let d = [
            of(Role::Base)?,
            of(Role::Rays)?,
            of(Role::Samples)?,
            of(Role::Both)?,
        ];
        let weights = model::four_terms(BUDGET_FACTOR as f64);
        Some(weights.map(|w| {
            let terms: Vec<(&[f64], f64)> = d.iter().copied().zip(w).collect();
            Gain::combined(&terms)
        }))
    }

    /// The pass of the seed's sequence whose random numbers pass `pass` draws (film passes
    /// draw their own). Pilots outside the film repeat the first pair's numbers in every
    /// configuration, so that their variances differ by what the configuration changes and not
    /// by their noise (`Gain`); the two passes of a pair stay independent. Film pilots (q alone
    /// automatic) are passes of the image and keep their own numbers: the film's passes must
    /// be independent.
    pub fn random_pass(&self, pass: u64) -> u64 {
        if pass < self.pilot_passes() && !self.pilots_join_film() {
            pass % REPEATS
        } else {
            pass
        }
    }

    fn choose(&self) -> Choice {
        let mut report = Vec::new();
        let Some((base, b)) = self.measure(Role::Base) else {
            return Choice {
                config: self.pilots[0].1.clone(),
                report,
            };
        };
        for ((role, c), m) in self.pilots.iter().zip(&self.measures) {
            report.push(format!(
                "pilot {role:?} (q {:?}, forward rays {}, camera paths {}{}): variance per pass \
                 {:.4e} +- {:.1e}, cost {:.4e} s",
                c.q,
                c.forward_rays,
                c.camera_samples,
                if c.indirect_scale == 1.0 {
                    String::new()
                } else {
                    format!(", radius for scattered light x {}", c.indirect_scale)
                },
                m.variance,
                m.se,
                m.work.cost()
            ));
        }
        let mut config = base.clone();
        let (variance, cost) = self.choose_q(&mut config, b, &mut report);
        if self.auto_rays || self.auto_samples {
            self.choose_budgets(&mut config, b, variance / b.variance, cost, &mut report);
        }
        report.extend(self.radius_report.iter().cloned());
        report.insert(
            0,
            format!(
                "chosen from {}: {}",
                self.pilots_said(),
                settings_of(&config)
            ),
        );
        Choice { config, report }
    }
}

#[cfg(test)]
mod tests;
