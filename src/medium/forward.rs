use super::{ChannelPick, Medium, Mixture, Tracker};
use crate::spectrum::Spectrum;
use rand::Rng;

/// One free flight of a forward (light) ray through a homogeneous medium segment, sampled with
/// the spectral mixture (bin picked in proportion to the ray's flux, with a uniform floor).
///
/// Usage: [`ForwardFlight::sample`], then gather along `[0, self.end()]` using
/// [`ForwardFlight::flux_at`] for the flux at each gather point, then [`ForwardFlight::finish`]
/// to update the flux for what follows.
///
/// Why `flux_at` and not the flux at the segment start: the segment reaches distance `s` with
/// probability `Tmix(s)`, so for bin `l` to see the uncollided flux `Phi_l e^{-st_l s}` on
/// average the segment must carry `Phi_l e^{-st_l s} / Tmix(s)` at `s`. This is 1 x Phi in
/// monochrome (or when all bins have the same sigma_t) but not in colour.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ForwardFlight {
    mix: Mixture,
    /// Sampled collision distance (may exceed the segment).
    t: f32,
    seg_len: f32,
}

/// What happens to a forward ray at the end of a flight.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum FlightEnd {
    /// Left the segment at `seg_len` with the flux updated by `e^{-st_l T} / Tmix(T)`.
    Escaped,
    /// Collided and scattered at `t` (flux updated by `ss_l e^{-st_l t} / pdf_mix(t)`, absorption
    /// by weight): sample a new direction from the phase function.
    Scattered { t: f32 },
    /// Collided at `t` where the mixture's density underflowed (about 100 mean free paths deep
    /// in every bin): the ray carries nothing on.
    Killed { t: f32 },
}

impl ForwardFlight {
    /// Samples the collision distance for a ray carrying `flux` over a segment of length
    /// `seg_len` (`+inf` allowed).
    #[inline]
    pub fn sample<R: Rng + ?Sized>(
        medium: &Medium,
        flux: &Spectrum,
        floor: f32,
        seg_len: f32,
        rng: &mut R,
    ) -> Self {
        let mix = Mixture::new(ChannelPick::Throughput, flux, medium, floor);
        let t = mix.sample_distance(rng.random(), rng.random());
        Self { mix, t, seg_len }
    }

    /// The same flight in a tracked grey medium (`medium::tracking`): the collision distance
    /// (not depth) by delta tracking along `track` over `seg_len`. Its density is the exact
    /// sampler's, and a grey medium's flux weights do not depend on the depth.
    #[inline]
    pub fn tracked<R: Rng + ?Sized>(
        medium: &Medium,
        flux: &Spectrum,
        floor: f32,
        (seg_len, track): (f32, &Tracker),
        rng: &mut R,
    ) -> Self {
        let mix = Mixture::new(ChannelPick::Throughput, flux, medium, floor);
        let l0 = mix.pick(rng.random());
        let t = track
            .free_flight(0.0, seg_len, mix.rate(l0, 1.0), rng)
            .unwrap_or(f32::INFINITY);
        Self { mix, t, seg_len }
    }

    /// The sampled collision depth (distance in a uniform medium), which may exceed the segment.
    pub fn sampled(&self) -> f32 {
        self.t
    }

    /// The same flight over a segment of length `seg_len` (for a flight sampled before its
    /// segment's depth was known: `sample` with `seg_len = +inf`).
    pub fn within(self, seg_len: f32) -> Self {
        Self { seg_len, ..self }
    }

    /// True if the flight leaves the segment before colliding.
    pub fn escapes(&self) -> bool {
        self.t >= self.seg_len || self.t.is_nan()
    }

    /// Length of the forward segment actually travelled: the collision distance or the segment
    /// length.
    pub fn end(&self) -> f32 {
        self.t.min(self.seg_len)
    }

    /// The flight's spectral mixture (for colour gather weights along the segment).
    pub fn mixture(&self) -> &Mixture {
        &self.mix
    }

    /// Flux per bin at distance `s` in `[0, end()]` along the flight, for gathering.
    #[inline]
    pub fn flux_at(&self, flux: &Spectrum, s: f32) -> Spectrum {
        *flux * self.mix.survival_weight(s)
    }

    /// Applies the end-of-flight update to `flux`. Russian roulette is the caller's (the
    /// forward path's rule, after the event).
    #[inline]
    pub fn finish(&self, medium: &Medium, flux: &mut Spectrum) -> FlightEnd {
        if self.escapes() {
            *flux *= self.mix.survival_weight(self.seg_len);
            return FlightEnd::Escaped;
        }
        let e = self.mix.eval(self.t);
        if e.pdf.is_nan() || e.pdf <= 0.0 {
            return FlightEnd::Killed { t: self.t };
        }
        *flux *= medium.sigma_s * e.tr * (1.0 / e.pdf);
        FlightEnd::Scattered { t: self.t }
    }
}
