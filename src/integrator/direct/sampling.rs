//! Distance samplers along a camera segment for next-event estimation, each with its exact
//! density: the truncated exponential (the product of the camera's and the light's
//! transmittance for a parallel light), equiangular sampling about a point (Kulla and Fajardo
//! 2012, "Importance Sampling Techniques for Path Tracing in Participating Media"), and the
//! part of a segment inside a spot light's cone.

use glam::Vec3;

use crate::spectrum::{MAX_BINS, Spectrum};

/// Density `k e^{-k t} / (1 - e^{-k d})` on `[0, d]` (any sign of `k`; uniform as `k d -> 0`).
#[derive(Clone, Copy, Debug)]
pub struct TruncatedExp {
    k: f32,
    d: f32,
    /// `1 - e^{-k d}`, or 0 when `|k d|` is too small to matter (then uniform).
    mass: f32,
}

/// Below this `|k d|` the exponential is uniform to within 1e-5 of its density.
const FLAT: f32 = 1e-5;

impl TruncatedExp {
    pub fn new(k: f32, d: f32) -> Self {
        let x = k * d;
        let mass = if x.abs() < FLAT || !x.is_finite() {
            0.0
        } else {
            -(-x).exp_m1()
        };
        Self { k, d, mass }
    }

    #[inline]
    pub fn sample(&self, u: f32) -> f32 {
        let t = if self.mass == 0.0 {
            u * self.d
        } else {
            -(-u * self.mass).ln_1p() / self.k
        };
        t.clamp(0.0, self.d)
    }

    #[inline]
    pub fn pdf(&self, t: f32) -> f32 {
        if self.mass == 0.0 {
            1.0 / self.d
        } else {
            self.k * (-self.k * t).exp() / self.mass
        }
    }
}

/// A mixture of truncated exponentials on `[0, d]`, one per spectral bin with probability
/// `p_l` (the camera segment's channel mixture, method note 3): its density is shared by all
/// bins, and it follows every bin's own integrand, not just an average one.
#[derive(Clone, Debug)]
pub struct ExpMixture {
    parts: [TruncatedExp; MAX_BINS],
    p: Spectrum,
    n: usize,
}

impl ExpMixture {
    /// `rates[l]` per bin, mixed with probabilities `p` (summing to 1 over the `n` bins).
    /// Equal rates in every bin (a grey medium) make one part: the same density, without a
    /// mixture to build, pick from and sum (an exp per bin each, a sixth of a camera path's
    /// time in a grey fog).
    pub fn new(rates: &Spectrum, p: &Spectrum, n: usize, d: f32) -> Self {
        let rates_n = &rates.0[..n];
        if n > 0 && rates_n.iter().all(|&k| k == rates_n[0]) {
            let one = Spectrum::single(0, 1.0);
            let mut parts = [TruncatedExp::new(0.0, d); MAX_BINS];
            parts[0] = TruncatedExp::new(rates_n[0], d);
            return Self {
                parts,
                p: one,
                n: 1,
            };
        }
        let mut parts = [TruncatedExp::new(0.0, d); MAX_BINS];
        for (part, &k) in parts.iter_mut().zip(&rates.0[..n]) {
            *part = TruncatedExp::new(k, d);
        }
        Self { parts, p: *p, n }
    }

    /// A distance from two uniforms (bin pick, then distance).
    #[inline]
    pub fn sample(&self, u_pick: f32, u: f32) -> f32 {
        let mut acc = 0.0;
        let mut pick = self.n - 1;
        for l in 0..self.n {
            acc += self.p.0[l];
            if u_pick < acc {
                pick = l;
                break;
            }
        }
        self.parts[pick].sample(u)
    }

    #[inline]
    pub fn pdf(&self, t: f32) -> f32 {
        (0..self.n)
            .map(|l| self.p.0[l] * self.parts[l].pdf(t))
            .sum()
    }
}

/// Equiangular sampling of `t` in `[a, b]` about a point `c`, for the ray `o + u t`: density
/// `D / ((th_b - th_a) (D² + (t - delta)²))`, `delta` the foot of the perpendicular from `c`
/// and `D` its length. Proportional to the inverse squared distance to `c`.
#[derive(Clone, Copy, Debug)]
pub struct Equiangular {
    delta: f32,
    dist: f32,
    th_a: f32,
    th_b: f32,
}

/// Perpendicular distances below this (in metres) are raised to it: a segment through the
/// light itself then still has a finite, normalised density.
const MIN_DIST: f32 = 1e-6;

impl Equiangular {
    pub fn new(o: Vec3, u: Vec3, c: Vec3, a: f32, b: f32) -> Self {
        let delta = (c - o).dot(u);
        let dist = (c - (o + u * delta)).length().max(MIN_DIST);
        Self {
            delta,
            dist,
            th_a: ((a - delta) / dist).atan(),
            th_b: ((b - delta) / dist).atan(),
        }
    }

    #[inline]
    pub fn sample(&self, u: f32) -> f32 {
        let th = self.th_a + u * (self.th_b - self.th_a);
        self.delta + self.dist * th.tan()
    }

    #[inline]
    pub fn pdf(&self, t: f32) -> f32 {
        let x = t - self.delta;
        self.dist / ((self.th_b - self.th_a) * (self.dist * self.dist + x * x))
    }

    /// Whether the interval has any measure.
    pub fn is_empty(&self) -> bool {
        self.th_b.partial_cmp(&self.th_a) != Some(std::cmp::Ordering::Greater)
    }
}

/// The part `[lo, hi]` of `o + u t`, `t in [a, b]`, inside the convex cone of apex `c`, unit
/// axis `n` and half-angle `acos(cos_edge)` (below 90 degrees: the cone is convex, so the part
/// is one interval), or None when the segment misses it.
pub fn cone_interval(
    o: Vec3,
    u: Vec3,
    a: f32,
    b: f32,
    c: Vec3,
    n: Vec3,
    cos_edge: f32,
) -> Option<(f32, f32)> {
    let inside = |t: f32| {
        let v = o + u * t - c;
        let along = v.dot(n);
        along > 0.0 && along * along >= cos_edge * cos_edge * v.length_squared()
    };
    // Where the segment can enter or leave the cone: the roots of
    // (v.n)² - cos² |v|² = 0 and of v.n = 0, with v = o - c + u t.
    let v0 = o - c;
    let (un, vn) = (u.dot(n), v0.dot(n));
    let c2 = cos_edge * cos_edge;
    let qa = un * un - c2;
    let qb = vn * un - c2 * v0.dot(u);
    let qc = vn * vn - c2 * v0.length_squared();
    // At most five cuts: the ends, two roots, the apex plane (NaN marks an unused slot).
    let mut cuts = [a, b, f32::NAN, f32::NAN, f32::NAN];
    if qa.abs() > 1e-12 {
        let disc = qb * qb - qa * qc;
        if disc >= 0.0 {
            let r = disc.sqrt();
            cuts[2] = (-qb - r) / qa;
            cuts[3] = (-qb + r) / qa;
        }
    } else if qb.abs() > 1e-12 {
        cuts[2] = -qc / (2.0 * qb);
    }
    if un.abs() > 1e-12 {
        cuts[4] = -vn / un;
    }
    for t in &mut cuts {
        if !(*t >= a && *t <= b) {
            *t = f32::NAN;
        }
    }
    // NaNs sort last under the total order (they are positive NaNs): drop them.
    cuts.sort_by(f32::total_cmp);
    let valid = cuts.iter().take_while(|t| !t.is_nan()).count();
    let mut lo = f32::INFINITY;
    let mut hi = f32::NEG_INFINITY;
    for w in cuts[..valid].windows(2) {
        if w[1] > w[0] && inside(0.5 * (w[0] + w[1])) {
            lo = lo.min(w[0]);
            hi = hi.max(w[1]);
        }
    }
    (hi > lo).then_some((lo, hi))
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};
    use rand_pcg::Pcg64Mcg;

    /// Pearson chi-square of `n` samples in `bins` equal-width bins of `[a, b]` against the
    /// density `pdf` integrated per bin by Simpson's rule; returns (chi², degrees of freedom).
    fn chi_square(
        a: f32,
        b: f32,
        n: usize,
        mut sample: impl FnMut(f32) -> f32,
        pdf: impl Fn(f32) -> f32,
    ) -> (f64, usize) {
        let bins = 40;
        let mut counts = vec![0u64; bins];
        let mut rng = Pcg64Mcg::seed_from_u64(77);
        for _ in 0..n {
            let t = sample(rng.random());
            assert!((a..=b).contains(&t), "{t} outside [{a}, {b}]");
            let i = (((t - a) / (b - a)) * bins as f32) as usize;
            counts[i.min(bins - 1)] += 1;
        }
        let h = (b - a) as f64 / bins as f64;
        let mut chi2 = 0.0;
        let mut total_p = 0.0;
        for (i, &c) in counts.iter().enumerate() {
            let lo = a as f64 + i as f64 * h;
            let p = crate::test_stats::simpson(lo, lo + h, 32, |t| pdf(t as f32) as f64);
            total_p += p;
            let e = p * n as f64;
            chi2 += (c as f64 - e).powi(2) / e;
        }
        assert!(
            (total_p - 1.0).abs() < 1e-4,
            "density integrates to {total_p}"
        );
        (chi2, bins - 1)
    }

    /// chi² of 39 degrees of freedom stays below 80 with probability 1 - 1e-4; a wrong
    /// density (e.g. the exponential's rate off by 10 %) gives thousands at 200 000 samples.
    const CHI2_BOUND: f64 = 80.0;

    #[test]
    fn truncated_exponential_samples_its_density() {
        for (k, d) in [(2.0f32, 1.5f32), (-3.0, 0.7), (1e-7, 2.0), (40.0, 0.3)] {
            let e = TruncatedExp::new(k, d);
            let (chi2, dof) = chi_square(0.0, d, 200_000, |u| e.sample(u), |t| e.pdf(t));
            eprintln!("truncated exp k={k} d={d}: chi2 {chi2:.1} ({dof} dof)");
            assert!(chi2 < CHI2_BOUND, "k={k}: chi2 {chi2}");
        }
    }

    #[test]
    fn exponential_mixture_samples_its_density() {
        let rates = Spectrum::from_slice(&[0.5, 6.0, -2.0, 20.0]);
        let p = Spectrum::from_slice(&[0.1, 0.4, 0.3, 0.2]);
        let m = ExpMixture::new(&rates, &p, 4, 1.2);
        let mut rng = Pcg64Mcg::seed_from_u64(9);
        let (chi2, dof) = chi_square(
            0.0,
            1.2,
            200_000,
            |u| m.sample(rng.random(), u),
            |t| m.pdf(t),
        );
        eprintln!("exponential mixture: chi2 {chi2:.1} ({dof} dof)");
        assert!(chi2 < CHI2_BOUND, "chi2 {chi2}");
    }

    /// Equal rates collapse to one part with the single exponential's density and samples.
    #[test]
    fn grey_mixture_is_one_exponential() {
        let rates = Spectrum::from_slice(&[1.7; 8]);
        let p = Spectrum::from_slice(&[0.125; 8]);
        let m = ExpMixture::new(&rates, &p, 8, 0.9);
        let e = TruncatedExp::new(1.7, 0.9);
        for t in [0.0f32, 0.2, 0.45, 0.9] {
            assert!((m.pdf(t) - e.pdf(t)).abs() <= 1e-6 * e.pdf(t), "t={t}");
        }
        let mut rng = Pcg64Mcg::seed_from_u64(11);
        let (chi2, dof) = chi_square(
            0.0,
            0.9,
            200_000,
            |u| m.sample(rng.random(), u),
            |t| e.pdf(t),
        );
        eprintln!("grey mixture: chi2 {chi2:.1} ({dof} dof)");
        assert!(chi2 < CHI2_BOUND, "chi2 {chi2}");
    }

    #[test]
    fn equiangular_samples_its_density() {
        let o = Vec3::new(0.0, 0.0, 0.0);
        let u = Vec3::new(0.0, 0.0, 1.0);
        for (c, a, b) in [
            (Vec3::new(0.3, 0.0, 0.5), 0.0f32, 2.0f32),
            (Vec3::new(0.0, 0.05, 1.8), 0.2, 1.0),
            (Vec3::new(1.0, 1.0, -1.0), 0.0, 3.0),
        ] {
            let e = Equiangular::new(o, u, c, a, b);
            let (chi2, dof) = chi_square(a, b, 200_000, |x| e.sample(x), |t| e.pdf(t));
            eprintln!("equiangular c={c} [{a}, {b}]: chi2 {chi2:.1} ({dof} dof)");
            assert!(chi2 < CHI2_BOUND, "chi2 {chi2}");
        }
    }

    /// The cone interval equals the set of segment points inside the cone, found by fine
    /// stepping, for random segments about random cones.
    #[test]
    fn cone_interval_matches_brute_force() {
        let mut rng = Pcg64Mcg::seed_from_u64(5);
        let mut hits = 0;
        for _ in 0..2000 {
            let r = |rng: &mut Pcg64Mcg| Vec3::new(rng.random(), rng.random(), rng.random());
            let c = r(&mut rng) * 2.0 - Vec3::ONE;
            let n = (r(&mut rng) * 2.0 - Vec3::ONE).normalize();
            let cos_edge = rng.random_range(0.05f32..0.999);
            let o = r(&mut rng) * 4.0 - Vec3::splat(2.0);
            let u = (r(&mut rng) * 2.0 - Vec3::ONE).normalize();
            let (a, b) = (0.0, 4.0);
            let got = cone_interval(o, u, a, b, c, n, cos_edge);
            let inside = |t: f32| {
                let v = o + u * t - c;
                v.dot(n) > 0.0 && v.dot(n) >= cos_edge * v.length()
            };
            let steps = 4000;
            let (mut lo, mut hi) = (f32::INFINITY, f32::NEG_INFINITY);
            for i in 0..=steps {
                let t = a + (b - a) * i as f32 / steps as f32;
                if inside(t) {
                    lo = lo.min(t);
                    hi = hi.max(t);
                }
            }
            let step = (b - a) / steps as f32;
            match got {
                Some((l, h)) => {
                    hits += 1;
                    assert!(hi >= lo - step, "found [{l}, {h}], brute force empty");
                    assert!((l - lo).abs() <= 2.0 * step && (h - hi).abs() <= 2.0 * step);
                }
                None => assert!(hi < lo || hi - lo <= 2.0 * step, "missed [{lo}, {hi}]"),
            }
        }
        assert!(hits > 200, "{hits} segments met their cone");
    }
}
