use super::draine::Draine;
use super::hg::HenyeyGreenstein;
use super::two_term_hg::split;
use crate::medium::MediumError;

/// The fog and cloud droplet phase function of Jendersie & d'Eon 2023 ("An Approximate Mie
/// Scattering Function for Fog and Cloud Rendering", SIGGRAPH 2023 Talks):
/// `(1 - w_D) HG(g_HG) + w_D Draine(g_D, α)`, whose four parameters are fitted functions of the
/// water droplet diameter `d` (µm), for Mie phase functions averaged over the visible
/// spectrum and a narrow size distribution. The HG lobe carries the diffraction peak, the
/// Draine lobe the side and back scattering (fog bow and glory are smoothed out).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HgDraine {
    hg: HenyeyGreenstein,
    draine: Draine,
    w_draine: f32,
    diameter: f32,
}

/// The fit's parameters at diameter `d` in µm: (g_HG, g_D, α, w_D). Four diameter ranges,
/// each with its own fitted expressions (the paper's equations for d <= 0.1, 0.1 < d < 1.5,
/// 1.5 <= d < 5 and 5 <= d <= 50 µm).
pub fn fit(d: f64) -> (f64, f64, f64, f64) {
    let l = d.ln();
    if d <= 0.1 {
        (
            13.8 * d * d,
            1.1456 * d * (9.29044 * d).sin(),
            250.0,
            0.252977 - 312.983 * d.powf(4.3),
        )
    } else if d < 1.5 {
        let inner = (l - 0.238604) * (l + 1.00667) / (0.507522 - 0.15677 * l);
        (
            0.862 - 0.143 * l * l,
            0.379685 * (1.19692 * inner.cos() + 1.37932 * l + 0.0625835).cos() + 0.344213,
            250.0,
            0.146209 * (3.38707 * l + 2.11193).cos() + 0.316072 + 0.0778917 * l,
        )
    } else if d < 5.0 {
        let ll = l.ln();
        (
            0.0604931 * ll + 0.940256,
            0.500411 - 0.081287 / (-2.0 * l + l.tan() + 1.27551),
            7.30354 * l + 6.31675,
            0.026914 * (l - (5.68947 * (ll - 0.0292149)).cos()) + 0.376475,
        )
    } else {
        (
            (-0.0990567 / (d - 1.67154)).exp(),
            (-2.20679 / (d + 3.91029) - 0.428934).exp(),
            (3.62489 - 8.29288 / (d + 5.52825)).exp(),
            (-0.599085 / (d - 0.641583) - 0.665888).exp(),
        )
    }
}

/// Largest diameter the fit covers (µm).
pub const MAX_DIAMETER: f32 = 50.0;

impl HgDraine {
    /// Droplet diameter in µm, in (0, 50].
    pub fn new(diameter: f32) -> Result<Self, MediumError> {
        if !(diameter.is_finite() && diameter > 0.0 && diameter <= MAX_DIAMETER) {
            return Err(MediumError::PhaseParameter {
                what: "diameter",
                value: diameter,
                range: "(0, 50] µm",
            });
        }
        let (g_hg, g_d, alpha, w_d) = fit(diameter as f64);
        let w_draine = w_d.clamp(0.0, 1.0) as f32;
        Ok(Self {
            hg: HenyeyGreenstein::new(g_hg as f32)?,
            draine: Draine::new(g_d as f32, alpha as f32)?,
            w_draine,
            diameter,
        })
    }

    pub fn diameter(&self) -> f32 {
        self.diameter
    }

    /// The fit's HG part, Draine part and Draine weight.
    pub fn parts(&self) -> (HenyeyGreenstein, Draine, f32) {
        (self.hg, self.draine, self.w_draine)
    }

    pub fn g(&self) -> f32 {
        (1.0 - self.w_draine) * self.hg.g() + self.w_draine * self.draine.g()
    }

    /// Evaluated in f64: the HG lobe reaches g = 0.998 at 50 µm, where f32 arithmetic would
    /// lose the top of its peak.
    #[inline]
    pub fn eval(&self, cos: f32) -> f32 {
        let (mu, w) = (cos as f64, self.w_draine as f64);
        ((1.0 - w) * self.hg.eval64(mu) + w * self.draine.eval64(mu)) as f32
    }

    /// One random number picks the lobe and, rescaled, samples it exactly.
    #[inline]
    pub fn sample_cos(&self, xi: f32) -> f32 {
        let (draine, xi) = split(xi, self.w_draine);
        if draine {
            self.draine.sample_cos(xi)
        } else {
            self.hg.sample_cos64(xi as f64) as f32
        }
    }
}
