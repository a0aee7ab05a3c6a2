use super::Medium;
use crate::spectrum::Spectrum;

/// How the stepping bin `l0` of a segment is chosen (scene option `channel_pick`:
/// `"throughput"` | `"uniform"`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum ChannelPick {
    /// `P_l ∝ W_l` (the path's throughput or the forward ray's flux), mixed with a uniform floor.
    #[default]
    Throughput,
    /// `P_l = 1/n`.
    Uniform,
}

/// Default share of the uniform distribution mixed into throughput-proportional picks.
pub const DEFAULT_FLOOR: f32 = 0.1;
/// Smallest floor accepted; smaller requests are raised to it so that every `P_l > 0` (the
/// channel-averaged estimator is unbiased only if no bin has zero probability).
pub const MIN_FLOOR: f32 = 1e-3;

/// The one-segment spectral mixture of method note 3: bin `l0` is picked with probability
/// `P_l0`, then a distance is drawn from `st_l0 e^{-st_l0 s}`. Averaged over `l0` the distance
/// density is `pdf_mix(s) = Σ P_l st_l e^{-st_l s}` and the survival `Tmix(s) = Σ P_l e^{-st_l s}`.
///
/// Invariant: `P_l > 0` for every active bin and `Σ P_l = 1`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Mixture {
    p: Spectrum,
    st: Spectrum,
    /// Smallest sigma_t over the active bins: factored out of every exponential so that ratios
    /// stay finite where the exponentials themselves would underflow.
    st_min: f32,
    n: usize,
}

/// The mixture evaluated at one distance `s`, every term scaled by the same factor
/// `e^{st_min s}`. Only ratios of these fields are meaningful; all the estimator weights are
/// such ratios, and the scaling keeps them finite for optically very deep points.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MixEval {
    /// `e^{-st_l s}` per bin (scaled).
    pub tr: Spectrum,
    /// `pdf_mix(s)` (scaled).
    pub pdf: f32,
    /// `Tmix(s)` (scaled).
    pub tmix: f32,
}

/// `st_l - min_k st_k` over the medium's active bins (0 past them): the exponents of
/// [`MixEval::tr`], so that `e^{-x_l s}` recomputes a sphere's scaled per-bin attenuation
/// from its distance alone (see [`MultiSphereWalk::walk_scaled`](super::MultiSphereWalk::walk_scaled);
/// the gather uses a fast exp, equal to the walk's within 3e-7 relative, not bit for bit).
pub fn relative_extinction(medium: &Medium) -> Spectrum {
    let n = medium.n;
    let st = &medium.sigma_t;
    let st_min = st.0[..n].iter().copied().fold(f32::INFINITY, f32::min);
    let mut x = Spectrum::ZERO;
    for l in 0..n {
        x.0[l] = st.0[l] - st_min;
    }
    x
}

/// `e^{-k s}` that is 1 for k = 0 even when s is infinite.
#[inline]
pub(crate) fn atten(k: f32, s: f32) -> f32 {
    if k == 0.0 { 1.0 } else { (-k * s).exp() }
}

/// Bin probabilities over bins `0..n` for the pick `pick` (method note 3): for `Throughput`,
/// `P = (1-d) W/ΣW + d/n` where W's negative or non-finite lanes count as 0 (an all-zero W
/// falls back to uniform); `d` is clamped to `[MIN_FLOOR, 1]`. `Uniform` ignores W. The
/// distance mixture and the per-bin phase mixture (`Phase::sample_bins`) share it.
pub fn channel_probabilities(pick: ChannelPick, w: &Spectrum, n: usize, floor: f32) -> Spectrum {
    let uniform = 1.0 / n as f32;
    let mut p = Spectrum::ZERO;
    let mut total = 0.0;
    if pick == ChannelPick::Throughput {
        for l in 0..n {
            let x = w.0[l];
            p.0[l] = if x.is_finite() && x > 0.0 { x } else { 0.0 };
            total += p.0[l];
        }
    }
    if total > 0.0 && total.is_finite() {
        let d = if floor.is_nan() {
            DEFAULT_FLOOR
        } else {
            floor.clamp(MIN_FLOOR, 1.0)
        };
        let scale = (1.0 - d) / total;
        for l in 0..n {
            p.0[l] = p.0[l] * scale + d * uniform;
        }
    } else {
        p = Spectrum::splat(uniform, n);
    }
    p
}

impl Mixture {
    /// Builds the mixture of `medium` with the probabilities of [`channel_probabilities`].
    pub fn new(pick: ChannelPick, w: &Spectrum, medium: &Medium, floor: f32) -> Self {
        let n = medium.n;
        let p = channel_probabilities(pick, w, n, floor);
        let st = medium.sigma_t;
        let st_min = st.0[..n].iter().copied().fold(f32::INFINITY, f32::min);
        Self { p, st, st_min, n }
    }

    /// The pick probabilities `P_l` (zero past the active bins).
    pub fn probabilities(&self) -> &Spectrum {
        &self.p
    }

    /// `max_l st_l - min_l st_l`: how fast the per-bin survival ratios vary with distance
    /// (0 for a grey medium, where every ratio is 1).
    pub fn sigma_t_span(&self) -> f32 {
        self.st.0[..self.n].iter().copied().fold(0.0, f32::max) - self.st_min
    }

    /// Number of active bins.
    pub fn n(&self) -> usize {
        self.n
    }

    /// Picks `l0` from a uniform `u` in [0, 1).
    #[inline]
    pub fn pick(&self, u: f32) -> usize {
        let mut acc = 0.0;
        for l in 0..self.n {
            acc += self.p.0[l];
            if u < acc {
                return l;
            }
        }
        self.n - 1
    }

    /// Distance to the next extinction for bin `l0` from a uniform `u` in [0, 1) (`+inf` if the
    /// bin has no extinction).
    #[inline]
    pub fn exp_step(&self, l0: usize, rate_scale: f32, u: f32) -> f32 {
        let alpha = self.st.0[l0] * rate_scale;
        if alpha > 0.0 {
            -(1.0 - u).ln() / alpha
        } else {
            f32::INFINITY
        }
    }

    /// The extinction of bin `l0` times `rate_scale` (the rate of [`Mixture::exp_step`]).
    #[inline]
    pub fn rate(&self, l0: usize, rate_scale: f32) -> f32 {
        self.st.0[l0] * rate_scale
    }

    /// Samples a distance with density `pdf_mix` (two uniforms: bin pick, then exponential).
    #[inline]
    pub fn sample_distance(&self, u_pick: f32, u_dist: f32) -> f32 {
        self.exp_step(self.pick(u_pick), 1.0, u_dist)
    }

    /// Unscaled `pdf_mix(s) = Σ P_l st_l e^{-st_l s}` (may underflow to 0 deep inside).
    pub fn pdf_mix(&self, s: f32) -> f32 {
        (0..self.n)
            .map(|l| self.p.0[l] * self.st.0[l] * atten(self.st.0[l], s))
            .sum()
    }

    /// Unscaled `Tmix(s) = Σ P_l e^{-st_l s}`.
    pub fn tmix(&self, s: f32) -> f32 {
        (0..self.n)
            .map(|l| self.p.0[l] * atten(self.st.0[l], s))
            .sum()
    }

    /// All per-bin exponentials and both mixture sums at `s`, sharing one exp per bin.
    #[inline]
    pub fn eval(&self, s: f32) -> MixEval {
        let mut tr = Spectrum::ZERO;
        let mut pdf = 0.0;
        let mut tmix = 0.0;
        for l in 0..self.n {
            let e = atten(self.st.0[l] - self.st_min, s);
            tr.0[l] = e;
            pdf += self.p.0[l] * self.st.0[l] * e;
            tmix += self.p.0[l] * e;
        }
        MixEval { tr, pdf, tmix }
    }

    /// `e^{-st_l s} / Tmix(s)` per bin: the weight that makes a quantity carried past distance
    /// `s` unbiased per bin when the segment survives to `s` with probability `Tmix(s)`. This is
    /// the transmitted-camera-ray weight, the truncated-cylinder `Tr_l`, and the factor a forward
    /// segment's flux gets at a gather point `s` along it.
    #[inline]
    pub fn survival_weight(&self, s: f32) -> Spectrum {
        let e = self.eval(s);
        e.tr * (1.0 / e.tmix)
    }
}

/// The direction after a scattering in `medium` of a path travelling along `w` whose per-bin
/// weights (throughput or flux) are `weights`, and the per-bin factors the weights must be
/// multiplied by. For a phase function that is the same in every bin: its own exact sample
/// from two uniforms, no factors. For one that varies per bin (droplet fog): the mixture of the
/// bins' phases with the channel probabilities of `weights` (three uniforms), and factors
/// `p_l / p_mix` that keep every bin unbiased (`Phase::sample_bins`).
#[inline]
pub fn sample_scatter<R: rand::Rng + ?Sized>(
    medium: &Medium,
    w: glam::Vec3,
    weights: &Spectrum,
    pick: ChannelPick,
    floor: f32,
    rng: &mut R,
) -> (glam::Vec3, Option<Spectrum>) {
    if !medium.phase.varies_per_bin() {
        return (medium.phase.sample_dir(w, rng.random(), rng.random()), None);
    }
    let n = medium.n;
    let p = channel_probabilities(pick, weights, n, floor);
    let s = medium
        .phase
        .sample_bins(w, &p, n, [rng.random(), rng.random(), rng.random()]);
    (s.dir, Some(s.weight))
}
