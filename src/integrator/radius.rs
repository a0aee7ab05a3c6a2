//! The radius of each pass. Three schedules ([`Shrink`]):
//! - fixed: every pass at the starting radius (the paper's setting);
//! - progressive (`integrator.alpha` < 1): `R_{p+1}^2 = R_p^2 (p + 1 + alpha) / (p + 2)` from
//!   pass `p` to pass `p + 1`, passes counted from 0 (the rule `(i + alpha) / (i + 1)` of
//!   Hachisuka & Jensen 2009 with i = p + 1 passes done, applied per pass as in Knaus & Zwicker
//!   2011);
//! - consistent (the default): fixed for the first `integrator.shrink_after` passes, then
//!   `R = R_0 (P_0 / n)^(1/6)` at the n-th pass. A ball's blur is a bias of order R^2, and its
//!   variance per pass of order 1 / R^2: forward rays cross it as lines (track length), so the
//!   chance that one does goes as R^2 and its chord over the ball's volume as 1 / R^2, as with
//!   photons on a surface disc. An average of n passes then has a mean square error
//!   `c R^4 + s / (n R^2)`, least at R ~ n^(-1/6), where bias and noise fall together as
//!   n^(-1/3) (Hachisuka & Jensen's alpha = 2/3 has that rate; docs/media.md, "The radius over
//!   passes"). The wait keeps the renders of a session, whose error is mostly noise, at the
//!   radius the pilots found efficient.
//!
//! Also the starting radius `"auto"` picks.

use crate::camera::Camera;
use crate::geometry::{Aabb, Geometry, Ray, spawn};

/// How the radius changes from pass to pass.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Shrink {
    /// The starting radius for every pass.
    Fixed,
    /// Hachisuka & Jensen's progressive rule, from the first pass.
    Progressive { alpha: f32 },
    /// Fixed for `after` passes, then falling as `n^(-1/6)`.
    Consistent { after: u64 },
}

impl Shrink {
    /// How many passes from the first keep the starting radius: every pass before this index
    /// is rendered alike under any two schedules whose counts reach past it (films that differ
    /// only in their schedules are of one render over those passes: `scene::same_render`).
    pub fn unchanged_passes(&self) -> u64 {
        match *self {
            Shrink::Fixed => u64::MAX,
            Shrink::Progressive { alpha } if alpha >= 1.0 => u64::MAX,
            // Pass 0 has the starting radius; pass 1 already a smaller one.
            Shrink::Progressive { .. } => 1,
            // Pass p is the (p + 1)-th: the starting radius while p + 1 <= after.
            Shrink::Consistent { after } => after,
        }
    }
}

/// The radius of every pass of a render.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RadiusSchedule {
    pub r0: f32,
    pub shrink: Shrink,
}

/// Above this pass index the log-gamma difference below loses digits (lgamma(1e6) is about
/// 1.3e7, so its f64 rounding is 3e-9 of R^2); beyond it the two-term asymptotic expansion of
/// the gamma ratio is accurate to O(1/p^2) instead.
const ASYMPTOTIC_FROM: f64 = 1e6;

/// The consistent schedule's exponent: R ~ n^(-1/6), the rate that balances a ball's R^2 bias
/// against its 1/R^2 variance (module comment).
pub const CONSISTENT_EXPONENT: f64 = 1.0 / 6.0;

impl RadiusSchedule {
    /// Radius of pass `p` (0-based), in closed form, so that a render may start at any pass
    /// (resume, pass ranges) in constant time.
    pub fn at(&self, p: u64) -> f32 {
        match self.shrink {
            Shrink::Fixed => self.r0,
            Shrink::Progressive { alpha } => progressive(self.r0, alpha, p),
            Shrink::Consistent { after } => {
                let n = p.saturating_add(1);
                if n <= after {
                    return self.r0;
                }
                // libm, not the platform's pow: the same bits on every machine.
                let f = libm::pow(after as f64 / n as f64, CONSISTENT_EXPONENT);
                (self.r0 as f64 * f) as f32
            }
        }
    }
}

/// Hachisuka & Jensen's radius at pass `p`:
/// `R_p^2 = R_0^2 prod_{i=1..p} (i + a)/(i + 1) = R_0^2 Γ(p + 1 + a) / (Γ(1 + a) Γ(p + 2))`.
fn progressive(r0: f32, alpha: f32, p: u64) -> f32 {
    let a = alpha as f64;
    if a == 1.0 || p == 0 {
        return r0;
    }
    let x = p as f64 + 1.0;
    // ln Γ(x + a) - ln Γ(x + 1), then the constant -ln Γ(1 + a).
    let ratio = if x < ASYMPTOTIC_FROM {
        libm::lgamma(x + a) - libm::lgamma(x + 1.0)
    } else {
        // Γ(x + a)/Γ(x + b) = x^(a-b) (1 + (a-b)(a+b-1)/(2x) + O(1/x^2)), with b = 1.
        (a - 1.0) * x.ln() + (a - 1.0) * a / (2.0 * x)
    };
    let r2 = (r0 as f64).powi(2) * (ratio - libm::lgamma(1.0 + a)).exp();
    r2.sqrt() as f32
}

/// The two radii of a pass. The gathered part holds two kinds of light: the direct light of
/// lights next-event estimation does not handle (a laser's beam and spot: sharp, dense where it
/// is, and blurred by every millimetre of radius) and light that has scattered at least once
/// (smooth, and sparse: it wants a large radius). A forward ray deposits with `direct` on its
/// first flight from such a light and with `indirect` after its first scattering or non-null
/// surface event (`integrator.radius_indirect`; the same as `direct` unless set).
///
/// With `blend`, scattered light is also estimated at the direct radius, from the same hits
/// (the larger ball holds the smaller), and its difference from the larger radius's estimate
/// kept apart, so that the film can choose between the two (`film::blend`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Radii {
    pub direct: f32,
    pub indirect: f32,
    pub blend: bool,
}

impl Radii {
    /// One radius for both kinds of light.
    pub fn one(r: f32) -> Self {
        Radii {
            direct: r,
            indirect: r,
            blend: false,
        }
    }

    /// The larger radius: what the gather structure's bounds must hold.
    pub fn bound(&self) -> f32 {
        self.direct.max(self.indirect)
    }

    /// The radius of a deposit of direct (`true`) or scattered light.
    #[inline]
    pub fn of(&self, direct: bool) -> f32 {
        if direct { self.direct } else { self.indirect }
    }
}

/// The radius for scattered light that the automatic settings' Radius pilot measures, over the
/// automatic radius (`auto::Tuner::choose_radius`): 3 footprints, the medium's most efficient
/// radius on fog-cube ("Radius of the gathered part" below [`FOOTPRINT_RADII`]).
pub const AUTO_INDIRECT_SCALE: f32 = 2.0;

/// Pixels sampled (per side) to find the footprint of `auto_radius`.
const FOOTPRINT_GRID: u32 = 24;
/// `auto_radius` in pixel footprints. Measured at equal CPU time with next-event estimation
/// (docs/performance.md, "Radius of the gathered part"): 1.5 footprints beat 3 on chromatic-fog
/// (1.46x) and fog-room-laser (6.8x, its laser's direct light gathered on the surfaces), and lost
/// to 3 on fog-cube (0.81x); the surface layer is most efficient at 1 to 1.5 footprints in all
/// three, the medium layer at 3 or more in fog-cube and fog-room-laser.
pub const FOOTPRINT_RADII: f32 = 1.5;

/// `integrator.radius = "auto"`: [`FOOTPRINT_RADII`] times the median pixel footprint
/// ([`pixel_footprint`]; SPPM renderers also start their radius from the pixel footprint,
/// Hachisuka & Jensen 2009).
pub fn auto_radius(camera: &Camera, geometry: &Geometry) -> f32 {
    FOOTPRINT_RADII * pixel_footprint(camera, geometry)
}

/// The median pixel footprint at the camera's first hits of surfaces with a material. The
/// footprint of a pixel is the distance between the rays through its centre and its
/// neighbour's at the hit's depth: the pixel size for an orthographic camera, depth x pixel
/// angle for a perspective one. Rays that hit nothing take the depth where they leave the
/// geometry's bounds. Deterministic (a fixed grid of pixels). With nothing in view, a
/// thousandth of the scene's diagonal (at least 0.1 mm) over [`FOOTPRINT_RADII`] stands
/// in (so that the auto radius is that thousandth).
pub fn pixel_footprint(camera: &Camera, geometry: &Geometry) -> f32 {
    let (w, h) = camera.resolution();
    let bounds = geometry.bounds();
    let mut footprints = Vec::new();
    for i in 0..FOOTPRINT_GRID {
        for j in 0..FOOTPRINT_GRID {
            let x = (w as f32 * (i as f32 + 0.5) / FOOTPRINT_GRID as f32).floor() + 0.5;
            let y = (h as f32 * (j as f32 + 0.5) / FOOTPRINT_GRID as f32).floor() + 0.5;
            let (a, b) = (camera.generate_ray(x, y), camera.generate_ray(x + 1.0, y));
            let Some(depth) = first_surface(geometry, &a).or_else(|| bounds_exit(&bounds, &a))
            else {
                continue;
            };
            let f = a.at(depth).distance(b.at(depth));
            if f.is_finite() && f > 0.0 {
                footprints.push(f);
            }
        }
    }
    if footprints.is_empty() {
        return (1e-3 * bounds.diagonal().length()).max(1e-4) / FOOTPRINT_RADII;
    }
    footprints.sort_by(f32::total_cmp);
    footprints[footprints.len() / 2]
}

/// Distance to the first surface with a material along `ray` (null boundaries passed).
fn first_surface(geometry: &Geometry, ray: &Ray) -> Option<f32> {
    let mut r = *ray;
    let mut travelled = 0.0;
    for _ in 0..64 {
        let hit = geometry.intersect(&r, f32::INFINITY)?;
        travelled += hit.t;
        if geometry.shape(hit.shape).material.is_some() {
            return Some(travelled);
        }
        r = spawn(hit.p, hit.ng, r.d);
    }
    None
}

/// Where `ray` leaves the box `b`, if it meets it.
fn bounds_exit(b: &Aabb, ray: &Ray) -> Option<f32> {
    let inv = ray.d.recip();
    let (t0, t1) = ((b.min - ray.o) * inv, (b.max - ray.o) * inv);
    let far = t0.max(t1).min_element();
    (far.is_finite() && far > 0.0).then_some(far)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The closed form equals the recurrence it solves, pass by pass, for several alphas, and
    /// stays continuous across the switch to the asymptotic form. An off-by-one in the pass
    /// index (the radius of pass p + 1 for pass p) fails by far more than the bound.
    #[test]
    fn closed_form_matches_the_recurrence() {
        for alpha in [0.2f64, 0.5, 2.0 / 3.0, 0.9, 1.0] {
            let s = RadiusSchedule {
                r0: 0.01,
                shrink: Shrink::Progressive {
                    alpha: alpha as f32,
                },
            };
            let a = alpha as f32 as f64;
            let mut r2 = (s.r0 as f64).powi(2);
            for p in 0..5000u64 {
                if p > 0 {
                    r2 *= (p as f64 + a) / (p as f64 + 1.0);
                }
                let got = s.at(p) as f64;
                let rel = (got - r2.sqrt()).abs() / r2.sqrt();
                assert!(rel < 2e-6, "alpha {alpha} pass {p}: {got} vs {}", r2.sqrt());
            }
        }
        // R_p ~ p^((a-1)/2): compare the two forms on either side of the switch.
        let s = RadiusSchedule {
            r0: 1.0,
            shrink: Shrink::Progressive { alpha: 0.5 },
        };
        let below = s.at(999_998) as f64;
        let above = s.at(1_000_001) as f64;
        let expect = (1_000_001.0f64 / 999_998.0).powf(-0.25);
        assert!(((above / below) / expect - 1.0).abs() < 1e-5);
    }

    const ORTHO: &str = "[camera]\ntype = \"orthographic\"\nwidth = 100\nheight = 100\n\
        position = [0.0, 0.0, 2.0]\nlook_at = [0.0, 0.0, 0.0]\nview_width = 1.0\nview_height = 1.0";

    fn built(camera: &str) -> crate::world::Scene {
        built_with(camera, "").1
    }

    fn built_with(camera: &str, integrator: &str) -> (f32, crate::world::Scene) {
        let text = format!(
            "{camera}\n[materials.w]\ntype = \"lambert\"\nalbedo = 0.5\n\
             [[shapes]]\ntype = \"quad\"\nsize = [4.0, 4.0]\nmaterial = \"w\"\n\
             [[lights]]\ntype = \"directional\"\ndirection = [0.0, 0.0, -1.0]\n\
             irradiance = 1.0\n[integrator]\nradius = \"auto\"\n{integrator}"
        );
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/test.toml");
        let loaded = crate::scene::load_str(&text, &dir, &[]).unwrap();
        let scene = crate::scene::build(&loaded).unwrap();
        let r0 = crate::scene::build_integrator(&loaded, &scene)
            .unwrap()
            .radius
            .r0;
        (r0, scene)
    }

    /// The auto rule: 1.5 pixel footprints, also as the integrator resolves `radius = "auto"`
    /// (under either direct mode). Orthographic: 1 m over 100 pixels is a 1 cm footprint, so
    /// 1.5 cm; perspective: a wall 2 m away, normal to the view, fov 40 degrees over 100
    /// pixels, footprint 2 x 2 tan(20 deg) / 100 = 1.456 cm at the centre and a little less at
    /// the median pixel (x cos of the angle off axis: the depth grows as 1 / cos, the angle
    /// between neighbouring rays shrinks as cos^2; measured 1.435 cm). A changed multiplier or a
    /// footprint measured at the wrong depth fails.
    #[test]
    fn auto_radius_is_one_and_a_half_footprints() {
        let ortho = built(ORTHO);
        let f = pixel_footprint(&ortho.camera, &ortho.geometry);
        assert!((f - 0.01).abs() < 1e-5, "orthographic footprint {f}");
        let r = auto_radius(&ortho.camera, &ortho.geometry);
        assert!((r - 0.015).abs() < 2e-5, "orthographic auto radius {r}");
        for direct in ["nee", "photons"] {
            let (r0, _) = built_with(ORTHO, &format!("direct = \"{direct}\"\n"));
            assert!(
                (r0 - 0.015).abs() < 2e-5,
                "integrator's auto radius ({direct}) {r0}"
            );
        }

        let persp = built(
            "[camera]\ntype = \"perspective\"\nwidth = 100\nheight = 100\n\
             position = [0.0, 0.0, 2.0]\nlook_at = [0.0, 0.0, 0.0]\nfov = 40.0",
        );
        let centre = 2.0 * 2.0 * 20f32.to_radians().tan() / 100.0;
        let f = pixel_footprint(&persp.camera, &persp.geometry);
        assert!(
            f <= centre && f > 0.95 * centre,
            "perspective footprint {f} vs {centre}"
        );
        let r = auto_radius(&persp.camera, &persp.geometry);
        assert!(
            (r / f - 1.5).abs() < 1e-5,
            "perspective auto radius {r} = {} footprints",
            r / f
        );
    }

    /// `unchanged_passes` is where each schedule first leaves the starting radius, read off
    /// `at` itself: one pass too many or too few fails.
    #[test]
    fn unchanged_passes_are_those_at_the_starting_radius() {
        for shrink in [
            Shrink::Progressive { alpha: 0.7 },
            Shrink::Consistent { after: 1 },
            Shrink::Consistent { after: 5 },
            Shrink::Consistent { after: 256 },
        ] {
            let s = RadiusSchedule { r0: 0.02, shrink };
            let n = shrink.unchanged_passes();
            assert!((0..n).all(|p| s.at(p) == 0.02), "{shrink:?}");
            assert!(s.at(n) < 0.02, "{shrink:?}");
        }
        for shrink in [Shrink::Fixed, Shrink::Progressive { alpha: 1.0 }] {
            let s = RadiusSchedule { r0: 0.02, shrink };
            assert_eq!(shrink.unchanged_passes(), u64::MAX);
            assert_eq!(s.at(1 << 40), 0.02);
        }
    }

    /// Huge pass indices (a pass range near 2^53) take constant time and give a finite,
    /// positive radius.
    #[test]
    fn huge_pass_indices_are_instant() {
        for shrink in [
            Shrink::Progressive { alpha: 0.7 },
            Shrink::Consistent { after: 256 },
        ] {
            let s = RadiusSchedule { r0: 0.01, shrink };
            let r = s.at(9_007_199_254_740_990);
            assert!(r.is_finite() && r > 0.0 && r < 0.01, "{shrink:?}: {r}");
            assert_eq!(s.at(0), 0.01);
        }
        let s = RadiusSchedule {
            r0: 0.01,
            shrink: Shrink::Consistent { after: 256 },
        };
        assert!(s.at(u64::MAX) > 0.0);
    }

    /// The consistent schedule: the starting radius for the first `after` passes, then
    /// `R_0 (after / n)^(1/6)` at the n-th pass, continuous where it starts to shrink, and
    /// halving the radius takes 2^6 = 64 times the passes. Against the formula evaluated
    /// independently (f64 powf): an off-by-one in the pass count (pass p as the p-th instead of
    /// the (p+1)-th) or another exponent fails.
    #[test]
    fn the_consistent_schedule_waits_then_falls_as_n_to_the_minus_one_sixth() {
        let after = 256u64;
        let s = RadiusSchedule {
            r0: 0.03,
            shrink: Shrink::Consistent { after },
        };
        for p in 0..after {
            assert_eq!(s.at(p), 0.03, "pass {p}");
        }
        for p in [256u64, 257, 300, 1000, 4095, 100_000, 1 << 40] {
            let want = 0.03 * (after as f64 / (p + 1) as f64).powf(1.0 / 6.0);
            let got = s.at(p) as f64;
            assert!((got / want - 1.0).abs() < 1e-6, "pass {p}: {got} vs {want}");
        }
        // The n-th pass is the (p + 1)-th: pass 255 is the last at R_0, pass 256 the first below.
        assert!(s.at(256) < 0.03 && s.at(256) > 0.03 * 0.999);
        let (a, b) = (s.at(1023) as f64, s.at(64 * 1024 - 1) as f64);
        assert!((a / b / 2.0 - 1.0).abs() < 1e-6, "{a} / {b}");
    }

    /// Fixed is fixed, whatever the pass.
    #[test]
    fn the_fixed_schedule_never_changes() {
        let s = RadiusSchedule {
            r0: 0.02,
            shrink: Shrink::Fixed,
        };
        for p in [0u64, 1, 255, 256, 1 << 20, u64::MAX] {
            assert_eq!(s.at(p), 0.02);
        }
    }
}
