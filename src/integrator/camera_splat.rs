//! Light tracing to the camera (`integrator.splat_to_camera`): while a forward ray carries
//! direct light (its first flight, from a light that is not next-event estimated) or caustic
//! light (after specular reflections and refractions only), it is connected to the camera and
//! splatted into the pixel that sees it, instead of being gathered by the camera paths' first
//! integration volumes and surface spheres: at its first diffuse surface hit, and at one point
//! of each of its flights through a medium (single scattering towards the camera).
//!
//! Why: a gathered surface sphere spreads each forward ray's light over a disc of the gather
//! radius (about a pixel footprint), and a tiny bright spot (a 2 mm laser on a wall) is then
//! blurred over the pixels within a radius and seen only by the camera samples that land near
//! it. Connected to the camera, every forward ray that reaches the spot adds its light to the
//! pixel that truly sees it: no blur, and no camera-sample noise.
//!
//! The two strategies split the light without overlap (as bidirectional path tracing's
//! strategies do, here without weights): light that reached a surface through specular events
//! only (or none) and leaves it straight to the camera (through index-matched boundaries and
//! media only) is the splat's, as is such light scattered once in a medium straight to the
//! camera; the
//! surface spheres of the camera paths' *first* non-null surface event
//! (`SurfaceRecord::primary`) and the volumes of their segments before it (`record::PRIMARY`)
//! skip it, and gather everything else.
//!
//! The estimate (a box-filtered pixel's measurement, derived at `Camera::project`): a
//! forward ray of flux `Phi` arriving at `x` adds `f_d(w_c, w_i) Phi T(x, camera)
//! |cos theta_x| W(x)` to its pixel per forward ray, with `f_d` the material's diffuse part, `T`
//! the transmittance to the camera and `W` the pixel importance. In a medium, a point `s`
//! drawn uniformly on the flight `[0, e]` (the forward flight's sampled extent, whose
//! `flux_at` is the unbiased uncollided flux along it) adds `e sigma_s(x) p(cos) flux_at(s)
//! T(x, camera) W(x)`: the single-scattered intensity towards the camera, `W` taking it to the
//! pixel (a point seen by the camera has no surface cosine).

use glam::Vec3;

use crate::film::{ChunkSplats, Layer};
use crate::geometry::{Hit, Ray, spawn};
use crate::medium::{Along, ForwardFlight};
use crate::spectrum::Spectrum;
use crate::world::Scene;

use super::direct::shadow;
use super::estimator::times_phase;

/// The pixel and value (per forward ray, before the pass's `1 / forward rays`) of forward
/// flux `flux` arriving along `dir` at the surface `hit` with material `mat`, seen from the
/// camera; None when the camera does not see `hit` (outside the image, behind the surface or
/// blocked by a surface with a material).
pub fn connect(
    scene: &Scene,
    hit: &Hit,
    dir: Vec3,
    mat: u32,
    flux: &Spectrum,
) -> Option<(u32, Spectrum)> {
    let pr = scene.camera.project(hit.p)?;
    let wc = pr.to_camera;
    let wi = -dir;
    // The camera must be on the side the light arrived from (as the surface spheres require
    // of the camera path's own side).
    let (cos_c, cos_i) = (hit.ng.dot(wc), hit.ng.dot(wi));
    if cos_c * cos_i <= 0.0 {
        return None;
    }
    let n = if hit.ns.dot(wc) >= 0.0 {
        hit.ns
    } else {
        -hit.ns
    };
    let at = Hit {
        ng: n,
        ns: n,
        ..*hit
    };
    let f = scene.materials[mat as usize].eval_diffuse(wc, wi, &at);
    if f.is_zero() {
        return None;
    }
    let ray = spawn(hit.p, hit.ng, wc);
    let medium = scene.geometry.medium_after(hit, wc);
    let tau = shadow::optical_depth(scene, medium, ray, pr.dist)?;
    let t = shadow::transmittance(&tau, scene.grid.n);
    Some((pr.pixel, f * *flux * t * (cos_c.abs() * pr.importance)))
}

/// The pixel and value (per forward ray) of the flight `flight` of a ray carrying
/// `flux` from `ray.o` along `ray.d` in medium `m`, scattered once towards the camera at the
/// point `u * flight.end()`; None when the camera does not see that point.
pub fn connect_medium(
    scene: &Scene,
    (m, ray): (u32, &Ray),
    (flight, along): (&ForwardFlight, &Along),
    flux: &Spectrum,
    u: f32,
) -> Option<(u32, Spectrum)> {
    // The flight ran in optical depth at density 1; the point is drawn on its distance.
    let e = along.distance(flight.end());
    if !(e > 0.0 && e.is_finite()) {
        return None;
    }
    let s = u * e;
    let x = ray.o + ray.d * s;
    let pr = scene.camera.project(x)?;
    let to_camera = Ray {
        o: x,
        d: pr.to_camera,
    };
    let tau = shadow::optical_depth(scene, Some(m), to_camera, pr.dist)?;
    let t = shadow::transmittance(&tau, scene.grid.n);
    let med = &scene.media[m as usize];
    // A tracked medium's flight ran in distance (an identity `along`): its density is the
    // field's at the point (1 in a uniform medium, as the identity's).
    let rho = if along.is_identity() {
        med.density.at(x)
    } else {
        along.rho(s)
    };
    let j = flight.flux_at(flux, along.depth(s)) * med.sigma_s * (e * pr.importance * rho);
    Some((pr.pixel, times_phase(j * t, med, ray.d.dot(pr.to_camera))))
}

/// Adds a connection's value `(pixel, v)` times `norm` (1 / forward rays) to `layer` of its
/// pixel and to the layer of `light`.
pub fn put(
    buf: &mut ChunkSplats,
    layer: Layer,
    (pixel, v): (u32, Spectrum),
    light: u32,
    n: usize,
    norm: f32,
) {
    let one = Spectrum::splat(1.0, n);
    buf.splat_from(
        layer,
        pixel as usize,
        Some(light),
        &v.0[..n],
        &one.0[..n],
        norm,
    );
}
