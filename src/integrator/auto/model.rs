//! The variance and cost models behind the automatic settings, and their optima.
//!
//! q (method note, section 7; Ershov, Zhdanov and Voloboy 2019 leave q to the user): per
//! camera ray the medium estimate Z_q of multiple spheres has the second moment
//! `E[Z_q^2] = q (1 + eps) A + (1 - q) B`, where A is the second moment of the one-sphere
//! (collision) estimator, eps the relative variance forward-ray hits add per sphere, and B the
//! second moment of the track-length estimator q -> 0 tends to. So the variance is linear in q,
//! `V(q) = S q + I` with `S = (1 + eps) A - B` and `I = B - mu^2`, while the cost per ray is
//! `c0 + c1 / q` (spheres and their hits grow as 1/q). The product V C is least at
//! `q* = sqrt(I c1 / (S c0))` (d/dq of (S q + I)(c0 + c1/q) = S c0 - I c1 / q^2), clipped to
//! [`Q_MIN`, 1]: q = 1 when S <= 0 (smaller q cannot lower the variance).
//!
//! Budgets: a pass of s camera paths per pixel and N forward rays has variance
//! `a / s + b / N` (camera-side and forward-ray noise) and cost `cs s + cn N + cg s N` (camera
//! paths, forward rays, and their hits, which grow with both); for each s the best N is
//! `sqrt(b cs s^2 / (a (cn + cg s)))` (from d/dN of the product), and s is searched over whole
//! numbers.

use super::Q_MIN;

/// The linear variance model of one medium's q, fitted from passes at q = 1 and q = `q_lo`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct QFit {
    /// Slope S of the variance in q (`(1 + eps) A - B`).
    pub slope: f64,
    /// Cost c1 of the medium's spheres at q = 1 (the cost grows by c1 (1/q - 1)).
    pub sphere_cost: f64,
}

impl QFit {
    /// The fit from the variance and cost of passes at q = 1 and at `q_lo` (other media fixed).
    pub fn from_passes(v1: f64, v_lo: f64, c1: f64, c_lo: f64, q_lo: f64) -> Self {
        Self {
            slope: (v1 - v_lo) / (1.0 - q_lo),
            sphere_cost: ((c_lo - c1) / (1.0 / q_lo - 1.0)).max(0.0),
        }
    }
}

/// Second moments of the one-sphere and track-length estimators recovered from the second
/// moments of a medium estimate at q = 1 (`m1`) and at `q_lo` (`m_lo`):
/// `((1 + eps) A, B)`. Only their difference and `B - mu^2` enter q*, so eps and A are one
/// number here.
pub fn moments(m1: f64, m_lo: f64, q_lo: f64) -> (f64, f64) {
    let b = (m_lo - q_lo * m1) / (1.0 - q_lo);
    (m1, b)
}

/// Method note 7's time-optimal q for one medium: variance `slope q + rest`, cost
/// `c0 + c1 / q`, clipped to [`Q_MIN`, 1].
pub fn q_star(slope: f64, rest: f64, c0: f64, c1: f64) -> f32 {
    if slope <= 0.0 || !slope.is_finite() {
        return 1.0;
    }
    if rest <= 0.0 || c0 <= 0.0 {
        return Q_MIN;
    }
    ((rest * c1.max(0.0) / (slope * c0)).sqrt() as f32).clamp(Q_MIN, 1.0)
}

/// The q of each medium minimising `(I + sum_m S_m q_m) (c0 + sum_m c_m / q_m)` when the
/// media add their variances and costs. `base_variance` and `base_cost` are the variance and
/// cost of a pass with every q = 1. Each q_m satisfies `q_m^2 = V c_m / (S_m C)` at the optimum;
/// the fixed point is found by iteration (for one medium it is [`q_star`]).
pub fn q_joint(fits: &[QFit], base_variance: f64, base_cost: f64) -> Vec<f32> {
    let slopes: f64 = fits.iter().map(|f| f.slope).sum();
    let spheres: f64 = fits.iter().map(|f| f.sphere_cost).sum();
    let rest = base_variance - slopes;
    let c0 = base_cost - spheres;
    if let [f] = fits {
        return vec![q_star(f.slope, rest, c0, f.sphere_cost)];
    }
    let mut q = vec![1.0f64; fits.len()];
    for _ in 0..200 {
        let v = rest + fits.iter().zip(&q).map(|(f, q)| f.slope * q).sum::<f64>();
        let c = c0
            + fits
                .iter()
                .zip(&q)
                .map(|(f, q)| f.sphere_cost / q)
                .sum::<f64>();
        for (qm, f) in q.iter_mut().zip(fits) {
            *qm = q_star(
                f.slope,
                v - f.slope * *qm,
                c - f.sphere_cost / *qm,
                f.sphere_cost,
            ) as f64;
        }
    }
    q.into_iter().map(|q| q as f32).collect()
}

/// The weights of the variances of the (s, n), (s, k n), (k s, n) and (k s, k n) passes in
/// each of `NoiseSplit::from_four`'s terms (camera, forward, pair), for `k` =
/// `BUDGET_FACTOR`.
pub fn four_terms(k: f64) -> [[f64; 4]; 3] {
    [
        [-1.0 / k, 1.0, 1.0 / k, -1.0],
        [-1.0 / k, 1.0 / k, 1.0, -1.0],
        [1.0, -1.0, -1.0, 1.0],
    ]
}

/// Variance `a / s + b / N + c / (s N)` of a pass: noise of the camera paths alone, of the
/// forward rays alone (shared by every camera path of a pixel), and of their meeting (each
/// camera path's volumes see their own forward-ray hits).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NoiseSplit {
    pub camera: f64,
    pub forward: f64,
    pub pair: f64,
}

impl NoiseSplit {
    /// From passes at (s, n), (s, k n), (k s, n) and (k s, k n) of variances `V0`, `Vr`, `Vs`
    /// and `Vb` that draw the same random numbers (`Tuner::random_pass`), given as each term's
    /// combination of them at (s, n), with `e = 1 - 1/k`:
    /// `e^2 a/s = Vr - Vb - (V0 - Vs)/k`, `e^2 b/n = Vs - Vb - (V0 - Vr)/k` and
    /// `e^2 c/(sn) = V0 - Vr - Vs + Vb` (`four_terms`). No term needs a variance on its own: at
    /// the pilots' budgets the base pass's variance is mostly the forward rays' noise, and a
    /// camera term taken as what is left of it, `s (v - X / n)` (the three-pilot split this
    /// replaced), was the small difference of two large noisy numbers; each combination here
    /// is of paired differences, whose shared noise cancels.
    pub fn from_four(s: f64, n: f64, k: f64, [camera, forward, pair]: [f64; 3]) -> Self {
        let e2 = (1.0 - 1.0 / k).powi(2);
        Self {
            camera: (camera * s / e2).max(0.0),
            forward: (forward * n / e2).max(0.0),
            pair: (pair * s * n / e2).max(0.0),
        }
    }

    /// From passes at (s, n) and (s, k n): the camera paths stay fixed, so the pair term is
    /// counted with the forward rays' (`b + c / s`).
    pub fn from_forward_rays(s: f64, n: f64, v: f64, k: f64, v_k: f64) -> Self {
        let forward = ((v - v_k) * n * k / (k - 1.0)).max(0.0);
        let camera = (s * (v - forward / n)).max(0.0);
        Self {
            camera,
            forward,
            pair: 0.0,
        }
    }

    /// From passes at (s, n) and (k s, n): the forward rays stay fixed, so the pair term is
    /// counted with the camera paths' (`a + c / n`).
    pub fn from_camera_samples(s: f64, n: f64, v: f64, k: f64, v_k: f64) -> Self {
        let camera = ((v - v_k) * s * k / (k - 1.0)).max(0.0);
        let forward = (n * (v - camera / s)).max(0.0);
        Self {
            camera,
            forward,
            pair: 0.0,
        }
    }

    pub fn variance(&self, s: f64, n: f64) -> f64 {
        self.camera / s + self.forward / n + self.pair / (s * n)
    }

    /// The same split for a pass whose variance is `f` times as large.
    pub fn scaled(&self, f: f64) -> Self {
        Self {
            camera: self.camera * f,
            forward: self.forward * f,
            pair: self.pair * f,
        }
    }
}

/// Cost `per_sample s + per_ray N + per_pair s N` of a pass.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CostSplit {
    pub per_sample: f64,
    pub per_ray: f64,
    pub per_pair: f64,
}

impl CostSplit {
    pub fn cost(&self, s: f64, n: f64) -> f64 {
        self.per_sample * s + self.per_ray * n + self.per_pair * s * n
    }
}

/// Which budgets the search may change, with their limits.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BudgetSearch {
    /// Camera paths per pixel: fixed, or searched in 1..=`max_samples`.
    pub samples: Option<u32>,
    pub max_samples: u32,
    /// Forward rays: fixed, or searched in `rays_range` (steps of 2 %).
    pub rays: Option<u64>,
    pub rays_range: (u64, u64),
}

/// The (camera paths per pixel, forward rays) minimising the product of the `noises`'
/// variances times the cost to the power of their number, by search: with one model, variance
/// x cost; with two (per pixel and per block, `auto::blocks`), the product of the two scales'
/// inverse efficiencies, so that a per cent of either counts alike.
pub fn budgets(noises: &[NoiseSplit], cost: &CostSplit, search: &BudgetSearch) -> (u32, u64) {
    let samples: Vec<u32> = match search.samples {
        Some(s) => vec![s],
        None => (1..=search.max_samples.max(1)).collect(),
    };
    let rays: Vec<u64> = match search.rays {
        Some(n) => vec![n],
        None => {
            let (lo, hi) = (search.rays_range.0.max(1), search.rays_range.1);
            std::iter::successors(Some(lo as f64), |n| Some(n * 1.02))
                .take_while(|n| *n <= hi as f64)
                .map(|n| n.round() as u64)
                .collect()
        }
    };
    let mut best = (f64::INFINITY, samples[0], rays[0]);
    for &s in &samples {
        for &n in &rays {
            let (sf, nf) = (s as f64, n as f64);
            let c = cost.cost(sf, nf);
            let score: f64 = noises.iter().map(|v| v.variance(sf, nf) * c).product();
            if score < best.0 {
                best = (score, s, n);
            }
        }
    }
    (best.1, best.2)
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};
    use rand_pcg::Pcg64Mcg;

    /// A medium estimate with known moments, made as multiple spheres make it: with probability
    /// q the collision estimator (second moment (1 + eps) A, hit noise included), else the
    /// track-length estimator (second moment B), both of mean mu. Its second moment is then
    /// q (1 + eps) A + (1 - q) B, the law of method note 7.
    fn sample(rng: &mut Pcg64Mcg, q: f64, mu: f64, a: f64, eps: f64, b: f64) -> f64 {
        if rng.random::<f64>() < q {
            // Exponential collision value of mean mu, times unit-mean gamma hit noise: second
            // moment 2 mu^2 (1 + eps); `a` is chosen as 2 mu^2.
            debug_assert!((a - 2.0 * mu * mu).abs() < 1e-12);
            let x = -mu * (1.0 - rng.random::<f64>()).ln();
            let k = 1.0 / eps;
            x * gamma(rng, k) / k
        } else {
            // Two-point track-length value: mu +- sqrt(B - mu^2).
            let d = (b - mu * mu).sqrt();
            if rng.random::<bool>() { mu + d } else { mu - d }
        }
    }

    /// Gamma(k, 1) for integer k (sum of exponentials).
    fn gamma(rng: &mut Pcg64Mcg, k: f64) -> f64 {
        (0..k as u32)
            .map(|_| -(1.0 - rng.random::<f64>()).ln())
            .sum()
    }

    /// Synthetic samples with known A, B, eps and costs c0, c1: the moments and q* the
    /// estimator recovers agree with method note 7's formula within the sampling error.
    #[test]
    fn q_star_from_synthetic_samples_matches_the_formula() {
        let mut rng = Pcg64Mcg::seed_from_u64(18);
        let (mu, eps, b) = (1.0f64, 0.25, 1.5);
        let a = 2.0 * mu * mu;
        let (c0, c1, q_lo) = (3.0, 0.5, 0.25);
        let n = 400_000;
        let second = |rng: &mut Pcg64Mcg, q| {
            (0..n)
                .map(|_| sample(rng, q, mu, a, eps, b).powi(2))
                .sum::<f64>()
                / n as f64
        };
        let (m1, m_lo) = (second(&mut rng, 1.0), second(&mut rng, q_lo));
        let (collision, track) = moments(m1, m_lo, q_lo);
        // (1 + eps) A = 2.5 and B = 1.5; their sampling errors are about 0.5 % and 0.7 %, so the
        // bounds are about 4 standard errors.
        assert!(
            (collision / ((1.0 + eps) * a) - 1.0).abs() < 0.02,
            "{collision}"
        );
        assert!((track / b - 1.0).abs() < 0.03, "{track}");
        let formula = ((b - mu * mu) * c1 / (((1.0 + eps) * a - b) * c0)).sqrt();
        // The fit through variances and costs of passes at q = 1 and q_lo.
        let (v1, v_lo) = (m1 - mu * mu, m_lo - mu * mu);
        let fit = QFit::from_passes(v1, v_lo, c0 + c1, c0 + c1 / q_lo, q_lo);
        let q = q_joint(&[fit], v1, c0 + c1)[0] as f64;
        assert!((formula - 0.2887).abs() < 1e-3, "{formula}");
        // q* carries about 1.3 % of error from the moments.
        assert!(
            (q / formula - 1.0).abs() < 0.05,
            "q {q} vs formula {formula}"
        );
        assert!((fit.sphere_cost - c1).abs() < 1e-12);
    }

    #[test]
    fn q_star_is_one_without_gain_and_clipped_below() {
        assert_eq!(q_star(-1.0, 1.0, 1.0, 1.0), 1.0);
        assert_eq!(q_star(1.0, -1.0, 1.0, 1.0), Q_MIN);
        assert_eq!(q_star(1e6, 1.0, 1.0, 1.0), Q_MIN.max(1e-3));
        assert_eq!(q_star(1.0, 1e6, 1.0, 1.0), 1.0);
        assert!((q_star(4.0, 1.0, 1.0, 1.0) - 0.5).abs() < 1e-7);
    }

    /// Two media: the joint fixed point beats every point of a grid of (q1, q2).
    #[test]
    fn joint_q_minimises_variance_times_cost() {
        let fits = [
            QFit {
                slope: 2.0,
                sphere_cost: 0.3,
            },
            QFit {
                slope: 0.5,
                sphere_cost: 0.8,
            },
        ];
        let (v_base, c_base) = (4.0, 3.0);
        let score = |q: &[f64]| {
            let v = v_base - 2.5 + 2.0 * q[0] + 0.5 * q[1];
            let c = c_base - 1.1 + 0.3 / q[0] + 0.8 / q[1];
            v * c
        };
        let q: Vec<f64> = q_joint(&fits, v_base, c_base)
            .iter()
            .map(|&q| q as f64)
            .collect();
        let best = score(&q);
        for i in 1..=100 {
            for j in 1..=100 {
                let g = [i as f64 / 100.0, j as f64 / 100.0];
                if g[0] >= Q_MIN as f64 && g[1] >= Q_MIN as f64 {
                    assert!(best <= score(&g) * (1.0 + 1e-6), "{q:?} vs {g:?}");
                }
            }
        }
    }

    /// The budget search finds the grid optimum of (a/s + b/N)(cs s + cn N + cg s N), and a
    /// noise split recovered from two passes reproduces the model.
    #[test]
    fn budgets_minimise_variance_times_cost() {
        let noise = NoiseSplit {
            camera: 2.0,
            forward: 3.0e5,
            pair: 4.0e4,
        };
        let cost = CostSplit {
            per_sample: 1.0,
            per_ray: 2e-5,
            per_pair: 1e-6,
        };
        let search = BudgetSearch {
            samples: None,
            max_samples: 32,
            rays: None,
            rays_range: (1000, 10_000_000),
        };
        let (s, n) = budgets(&[noise], &cost, &search);
        let score = |s: f64, n: f64| noise.variance(s, n) * cost.cost(s, n);
        let best = score(s as f64, n as f64);
        for si in 1..=32 {
            for k in 0..200 {
                let ni = 1000.0 * 1.05f64.powi(k);
                if ni <= 1e7 {
                    // The search's 2 % steps in N cost at most ~1e-4 of the optimum.
                    assert!(
                        best <= score(si as f64, ni) * (1.0 + 1e-3),
                        "{s} {n} vs {si} {ni}"
                    );
                }
            }
        }
        let (s0, n0, k) = (4.0, 5e4, 4.0);
        let v = noise.variance(s0, n0);
        // The four-pass split from the gains alone, (s, k n), (k s, n) and (k s, k n) over
        // (s, n).
        let vs = [v, noise.variance(s0, k * n0), noise.variance(k * s0, n0)];
        let vs = [vs[0], vs[1], vs[2], noise.variance(k * s0, k * n0)];
        let terms = four_terms(k).map(|w| w.iter().zip(&vs).map(|(w, v)| w * v).sum());
        let four = NoiseSplit::from_four(s0, n0, k, terms);
        for (got, want) in [
            (four.camera, noise.camera),
            (four.forward, noise.forward),
            (four.pair, noise.pair),
        ] {
            assert!((got / want - 1.0).abs() < 1e-9, "{four:?}");
        }
        // With one budget fixed, the two-pass fits predict the variance along the other.
        let rays = NoiseSplit::from_forward_rays(s0, n0, v, k, noise.variance(s0, k * n0));
        let samples = NoiseSplit::from_camera_samples(s0, n0, v, k, noise.variance(k * s0, n0));
        for f in [0.5, 2.0, 7.0] {
            let (vr, vs) = (noise.variance(s0, f * n0), noise.variance(f * s0, n0));
            assert!((rays.variance(s0, f * n0) / vr - 1.0).abs() < 1e-9);
            assert!((samples.variance(f * s0, n0) / vs - 1.0).abs() < 1e-9);
        }
    }
}
