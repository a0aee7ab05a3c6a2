//! Stratified integration spheres along one camera segment: the walk's mean sphere count and
//! estimate, with the randomness that is not needed taken out.
//!
//! The multiple-sphere walk (method note 2) leaves a random number of spheres (a Poisson
//! count of sub-steps cut short by the extinction coin) at random places, so that even a
//! forward-ray field known exactly would be estimated with noise: on fog-cube at its automatic
//! budgets that placement noise was half the per-pixel variance (docs/performance.md). Here a
//! segment of optical depth `T` (at density 1) gets `K` spheres, `K` the walk's mean count
//! `m = (1 - Tmix(T)) / q` rounded at random to a neighbouring integer (never below 1), at the
//! quantiles `u_k = (k + xi_k) / K` of the truncated exponential of one picked bin `l0`:
//! `s_k = -ln(1 - u_k A_l0) / st_l0` with `A_l = 1 - e^{-st_l T}`.
//!
//! Weight. Given `l0`, sphere `k` is uniform in its stratum of `u`, so the K spheres together
//! have density `K p_l0(s)` on `[0, T)`, `p_l(s) = st_l e^{-st_l s} / A_l`; over the pick, `K
//! p_T(s)` with the truncated mixture `p_T(s) = Σ_l P_l p_l(s)`. Weighting each sphere by
//! `ss_l e^{-st_l s} / (K p_T(s))` (one-sample balance over the bins, method note 3) makes the
//! sum over spheres of weight times reading an unbiased estimate of
//! `∫_0^T ss_l e^{-st_l s} F_l(s) ds` in every bin, for every K >= 1 (so the random rounding
//! keeps it unbiased too). The weight is reported in the walk's factored form `c = 1 / (K
//! p_T(s))`, scaled as `MixEval`, so the gather recomputes it from `s` as it does the walk's.
//!
//! Outcome. The spheres cover the whole segment whatever happens on it, so the path's outcome
//! (extinction or transmission, method note 4) is sampled on its own with `sample_extinction`:
//! the part behind the segment is then estimated exactly as the walk's `Transmitted` weight
//! estimates it, and the two parts add up to the segment's light, each unbiased.
//!
//! Not here: a bin without extinction (its exponential has no quantiles over an endless
//! segment) and tracked media (null collisions give no inverse transmittance); the caller
//! keeps the walk for those (`None`).

use super::{MultiSphereWalk, WalkEnd, sample_extinction};
use crate::medium::{Medium, MixEval, Mixture};
use crate::spectrum::Spectrum;
use rand::Rng;

impl MultiSphereWalk {
    /// Stratified spheres on a segment of optical depth `seg_len` at density 1 (may be
    /// `+inf`), untracked: for each sphere at depth `s` in `[0, seg_len)`, `on_sphere(s, c)`
    /// with the factored weight `c = 1 / (K p_T(s))` (module comment; the per-bin weight is
    /// `sigma_s,l e^{-(st_l - st_min) s} c`), then the independently sampled outcome. None
    /// (and no sphere, no random number) when an active bin has no extinction.
    #[inline]
    pub fn stratified_scaled<R, F>(
        &self,
        medium: &Medium,
        mix: &Mixture,
        seg_len: f32,
        rng: &mut R,
        mut on_sphere: F,
    ) -> Option<WalkEnd>
    where
        R: Rng + ?Sized,
        F: FnMut(f32, f32),
    {
        self.stratified_eval(medium, mix, seg_len, rng, |s, _, c| on_sphere(s, c))
    }

    /// The same spheres (same random numbers) with the per-bin weight
    /// `ss_l e^{-st_l s} / (K p_T(s))` in full, as [`MultiSphereWalk::walk`] reports its own.
    #[inline]
    pub fn stratified<R, F>(
        &self,
        medium: &Medium,
        mix: &Mixture,
        seg_len: f32,
        rng: &mut R,
        mut on_sphere: F,
    ) -> Option<WalkEnd>
    where
        R: Rng + ?Sized,
        F: FnMut(f32, &Spectrum),
    {
        self.stratified_eval(medium, mix, seg_len, rng, |s, e, c| {
            on_sphere(s, &(medium.sigma_s * e.tr * c))
        })
    }

    #[inline]
    fn stratified_eval<R, F>(
        &self,
        medium: &Medium,
        mix: &Mixture,
        seg_len: f32,
        rng: &mut R,
        mut on_sphere: F,
    ) -> Option<WalkEnd>
    where
        R: Rng + ?Sized,
        F: FnMut(f32, &MixEval, f32),
    {
        let n = mix.n();
        let st = &medium.sigma_t;
        // A_l = 1 - e^{-st_l T}: each bin's probability of an extinction on the segment.
        if st.0[..n].iter().any(|&s| s <= 0.0 || s.is_nan()) {
            return None;
        }
        let a = if seg_len.is_finite() {
            st.map_runs(n, |s| -(-s * seg_len).exp_m1())
        } else {
            Spectrum::splat(1.0, n)
        };
        let k = self.sphere_count(mix, seg_len, rng.random());
        let l0 = mix.pick(rng.random());
        let (st0, a0) = (st.0[l0], a.0[l0]);
        let p = mix.probabilities();
        for i in 0..k {
            let u = (i as f32 + rng.random::<f32>()) / k as f32;
            let s = -(-u * a0).ln_1p() / st0;
            if s >= seg_len {
                // Only rounding can put the last quantile at the end: it carries nothing.
                continue;
            }
            let e = mix.eval(s);
            let pdf: f32 = (0..n).map(|l| p.0[l] * st.0[l] * e.tr.0[l] / a.0[l]).sum();
            // pdf can only underflow to 0 at depths of ~100 mean free paths of every bin.
            if pdf > 0.0 {
                on_sphere(s, &e, 1.0 / (k as f32 * pdf));
            }
        }
        Some(sample_extinction(medium, (mix, None), seg_len, rng))
    }

    /// The walk's mean sphere count on the segment, `(1 - Tmix(T)) / q`, rounded up with
    /// probability its fraction and down otherwise (so its mean is kept), and at least 1.
    #[inline]
    fn sphere_count(&self, mix: &Mixture, seg_len: f32, u: f32) -> u32 {
        let m = (1.0 - mix.tmix(seg_len)) / self.q;
        let whole = m.floor();
        let k = whole as u32 + u32::from(u < m - whole);
        k.max(1)
    }
}
