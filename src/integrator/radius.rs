//! The progressive radius schedule: `R_{p+1}^2 = R_p^2 (p + 1 + alpha) / (p + 2)` from pass
//! `p` to pass `p + 1`, passes counted from 0 (the rule `(i + alpha) / (i + 1)` of Hachisuka &
//! Jensen 2009 with i = p + 1 passes done, applied per pass as in Knaus & Zwicker 2011). `alpha = 1` keeps
//! the radius fixed (the paper's setting). Also the starting radius `"auto"` picks.

use crate::camera::Camera;
use crate::geometry::{Aabb, Geometry, Ray, spawn};

/// The radius of every pass of a render.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RadiusSchedule {
    pub r0: f32,
    pub alpha: f32,
}

/// Above this pass index the log-gamma difference below loses digits (lgamma(1e6) is about
/// 1.3e7, so its f64 rounding is 3e-9 of R^2); beyond it the two-term asymptotic expansion of
/// the gamma ratio is accurate to O(1/p^2) instead.
const ASYMPTOTIC_FROM: f64 = 1e6;

impl RadiusSchedule {
    /// Radius of pass `p` (0-based), in closed form:
    /// `R_p^2 = R_0^2 prod_{i=1..p} (i + a)/(i + 1) = R_0^2 Γ(p + 1 + a) / (Γ(1 + a) Γ(p + 2))`,
    /// so that a render may start at any pass (resume, pass ranges) in constant time.
    pub fn at(&self, p: u64) -> f32 {
        let a = self.alpha as f64;
        if a == 1.0 || p == 0 {
            return self.r0;
        }
        let x = p as f64 + 1.0;
        // ln Γ(x + a) - ln Γ(x + 1), then the constant -ln Γ(1 + a).
        let ratio = if x < ASYMPTOTIC_FROM {
            libm::lgamma(x + a) - libm::lgamma(x + 1.0)
        } else {
            // Γ(x + a)/Γ(x + b) = x^(a-b) (1 + (a-b)(a+b-1)/(2x) + O(1/x^2)), with b = 1.
            (a - 1.0) * x.ln() + (a - 1.0) * a / (2.0 * x)
        };
        let r2 = (self.r0 as f64).powi(2) * (ratio - libm::lgamma(1.0 + a)).exp();
        r2.sqrt() as f32
    }
}

/// The two radii of a pass. The gathered part holds two kinds of light: the direct light of
/// lights next-event estimation does not handle (a laser's beam and spot: sharp, dense where it
/// is, and blurred by every millimetre of radius) and light that has scattered at least once
/// (smooth, and sparse: it wants a large radius). A forward ray deposits with `direct` on its
/// first flight from such a light and with `indirect` after its first scattering or non-null
/// surface event (`integrator.radius_indirect`; the same as `direct` unless set).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Radii {
    pub direct: f32,
    pub indirect: f32,
}

impl Radii {
    /// One radius for both kinds of light.
    pub fn one(r: f32) -> Self {
        Radii {
            direct: r,
            indirect: r,
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

/// Radius for pass `p` of a schedule starting at `r0` (see [`RadiusSchedule::at`]).
pub fn radius_for_pass(r0: f32, alpha: f32, p: u64) -> f32 {
    RadiusSchedule { r0, alpha }.at(p)
}

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
                alpha: alpha as f32,
            };
            let a = s.alpha as f64;
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
            alpha: 0.5,
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

    /// Huge pass indices (a pass range near 2^53) take constant time and give a finite,
    /// positive radius.
    #[test]
    fn huge_pass_indices_are_instant() {
        let s = RadiusSchedule {
            r0: 0.01,
            alpha: 0.7,
        };
        let r = s.at(9_007_199_254_740_990);
        assert!(r.is_finite() && r > 0.0 && r < 0.01, "{r}");
        assert_eq!(s.at(0), 0.01);
    }
}
