use std::f64::consts::PI;
use std::fmt;
use std::sync::Mutex;

use crate::medium::MediumError;
use crate::spectrum::{MAX_BINS, Spectrum};

/// A tabulated phase function: the density is piecewise linear in `mu = cos θ` between the
/// nodes, one table ("lane") per spectral bin or one for all bins. Each lane is normalised
/// exactly (the trapezoid rule is exact on a linear segment), and its CDF is piecewise
/// quadratic, so sampling inverts it in closed form: evaluation and sampling agree to
/// rounding, with no binning error of their own.
#[derive(Clone, PartialEq)]
pub struct PhaseTable {
    /// Node cosines, strictly increasing from -1 to 1.
    mu: Vec<f64>,
    /// One lane per bin, or a single lane shared by every bin.
    lanes: Vec<Lane>,
    /// The average of the lanes (equal to the only lane when there is one): the phase of light
    /// whose bins are equally weighted, used by the bin-independent interface.
    mean: Lane,
    /// Where the table came from, for messages.
    source: String,
}

#[derive(Clone, PartialEq)]
struct Lane {
    /// Density per steradian at the nodes.
    p: Vec<f32>,
    /// `2π ∫_{-1}^{mu_i} p dmu` at each node (0 at the first, 1 at the last).
    cdf: Vec<f64>,
    /// Mean cosine (exact for the piecewise-linear density).
    g: f32,
}

impl fmt::Debug for PhaseTable {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "PhaseTable({}, {} nodes, {} lanes)",
            self.source,
            self.mu.len(),
            self.lanes.len()
        )
    }
}

impl Lane {
    /// Normalises `values` (>= 0, not all 0) over the sphere and builds the CDF.
    fn new(mu: &[f64], values: &[f64]) -> Result<Self, MediumError> {
        let mut cdf = vec![0.0; mu.len()];
        let mut first_moment = 0.0;
        for i in 1..mu.len() {
            let (a, b) = (values[i - 1], values[i]);
            let h = mu[i] - mu[i - 1];
            cdf[i] = cdf[i - 1] + 2.0 * PI * 0.5 * h * (a + b);
            // ∫ mu p dmu over a linear segment, exactly (Simpson is exact for the quadratic).
            let (m0, m1) = (mu[i - 1], mu[i]);
            let mid = 0.5 * (m0 + m1) * 0.5 * (a + b);
            first_moment += 2.0 * PI * h / 6.0 * (m0 * a + 4.0 * mid + m1 * b);
        }
        let total = cdf[mu.len() - 1];
        if !(total.is_finite() && total > 0.0) {
            return Err(MediumError::PhaseTable(
                "the phase function is zero everywhere".into(),
            ));
        }
        for c in &mut cdf {
            *c /= total;
        }
        Ok(Self {
            p: values.iter().map(|v| (v / total) as f32).collect(),
            cdf,
            g: (first_moment / total) as f32,
        })
    }
}

impl PhaseTable {
    /// A table from node cosines (strictly increasing, -1 first and 1 last) and one or more
    /// lanes of non-negative values at those nodes (at most `MAX_BINS`); each lane is
    /// normalised here.
    pub fn new(mu: Vec<f64>, lanes: &[Vec<f64>], source: String) -> Result<Self, MediumError> {
        let bad = |m: String| Err(MediumError::PhaseTable(m));
        if mu.len() < 2 {
            return bad(format!("needs at least two angles, got {}", mu.len()));
        }
        if mu[0] != -1.0 || mu[mu.len() - 1] != 1.0 || mu.windows(2).any(|w| w[0] >= w[1]) {
            return bad("cosines must increase strictly from -1 to 1".into());
        }
        if lanes.is_empty() || lanes.len() > MAX_BINS {
            return bad(format!("needs 1..={MAX_BINS} lanes, got {}", lanes.len()));
        }
        for lane in lanes {
            if lane.len() != mu.len() || lane.iter().any(|v| !(v.is_finite() && *v >= 0.0)) {
                return bad("every value must be finite and >= 0, one per angle".into());
            }
        }
        let built = lanes
            .iter()
            .map(|v| Lane::new(&mu, v))
            .collect::<Result<Vec<_>, _>>()?;
        // Every lane integrates to 1, so their plain average does too.
        let avg: Vec<f64> = (0..mu.len())
            .map(|i| built.iter().map(|l| l.p[i] as f64).sum::<f64>() / built.len() as f64)
            .collect();
        let mean = Lane::new(&mu, &avg)?;
        Ok(Self {
            mu,
            lanes: built,
            mean,
            source,
        })
    }

    /// Number of lanes: 1 when the phase is the same in every bin.
    pub fn lanes(&self) -> usize {
        self.lanes.len()
    }

    pub fn source(&self) -> &str {
        &self.source
    }

    pub fn nodes(&self) -> usize {
        self.mu.len()
    }

    /// Mean cosine of the lane-averaged phase.
    pub fn g(&self) -> f32 {
        self.mean.g
    }

    /// Mean cosine of lane `l`.
    pub fn g_lane(&self, l: usize) -> f32 {
        self.lanes[l.min(self.lanes.len() - 1)].g
    }

    /// Interval `k` (nodes k-1, k) holding `mu`, and the position in it in [0, 1].
    #[inline]
    fn locate(&self, mu: f64) -> (usize, f64) {
        let m = &self.mu;
        let k = m.partition_point(|&x| x <= mu).clamp(1, m.len() - 1);
        let t = ((mu - m[k - 1]) / (m[k] - m[k - 1])).clamp(0.0, 1.0);
        (k, t)
    }

    #[inline]
    fn lane_eval(lane: &Lane, k: usize, t: f64) -> f32 {
        let (a, b) = (lane.p[k - 1], lane.p[k]);
        a + (b - a) * t as f32
    }

    /// The lane-averaged density at `cos`.
    #[inline]
    pub fn eval(&self, cos: f32) -> f32 {
        let (k, t) = self.locate(cos as f64);
        Self::lane_eval(&self.mean, k, t)
    }

    /// Density of lane `l` at `cos`.
    pub fn eval_lane(&self, l: usize, cos: f32) -> f32 {
        let (k, t) = self.locate(cos as f64);
        Self::lane_eval(&self.lanes[l.min(self.lanes.len() - 1)], k, t)
    }

    /// Every bin's density at `cos` (bins `0..n`; a single lane is repeated).
    pub fn eval_bins(&self, cos: f32, n: usize) -> Spectrum {
        let (k, t) = self.locate(cos as f64);
        let mut s = Spectrum::ZERO;
        for (l, v) in s.0.iter_mut().enumerate().take(n) {
            *v = Self::lane_eval(&self.lanes[l.min(self.lanes.len() - 1)], k, t);
        }
        s
    }

    /// Samples a cosine of the lane-averaged phase.
    #[inline]
    pub fn sample_cos(&self, xi: f32) -> f32 {
        self.sample_in(&self.mean, xi)
    }

    /// Samples a cosine of lane `l`.
    pub fn sample_lane(&self, l: usize, xi: f32) -> f32 {
        self.sample_in(&self.lanes[l.min(self.lanes.len() - 1)], xi)
    }

    /// Exact inverse of the piecewise-quadratic CDF: find the segment, then solve
    /// `2π (p0 t + s t²/2) = r` for the offset t (s the segment's slope), in the form
    /// `t = 2r / (2π p0 + sqrt((2π p0)² + 4π s r))`, which does not cancel and holds for
    /// flat, rising and falling segments alike.
    fn sample_in(&self, lane: &Lane, xi: f32) -> f32 {
        let target = xi as f64;
        let c = &lane.cdf;
        let k = c.partition_point(|&x| x <= target).clamp(1, c.len() - 1);
        let (m0, m1) = (self.mu[k - 1], self.mu[k]);
        let h = m1 - m0;
        let (p0, p1) = (lane.p[k - 1] as f64, lane.p[k] as f64);
        let s = (p1 - p0) / h;
        let r = (target - c[k - 1]).max(0.0);
        let a = 2.0 * PI * p0;
        let disc = (a * a + 4.0 * PI * s * r).max(0.0);
        let denom = a + disc.sqrt();
        let t = if denom > 0.0 { 2.0 * r / denom } else { 0.0 };
        (m0 + t.clamp(0.0, h)).clamp(-1.0, 1.0) as f32
    }
}

/// Tables live for the whole process so that a medium holding one stays `Copy` (the renderer
/// copies media freely); identical tables (the same file or droplet fog loaded again, as a
/// study does for each variant) are stored once, so memory stays bounded by the number of
/// distinct tables a process ever loads.
static INTERNED: Mutex<Vec<&'static PhaseTable>> = Mutex::new(Vec::new());

/// The process-wide copy of `table`.
pub fn intern(table: PhaseTable) -> &'static PhaseTable {
    let mut all = INTERNED.lock().unwrap_or_else(|e| e.into_inner());
    if let Some(t) = all.iter().find(|t| ***t == table) {
        return t;
    }
    let t: &'static PhaseTable = Box::leak(Box::new(table));
    all.push(t);
    t
}
