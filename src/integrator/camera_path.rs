//! One camera path: its state through the scene and what it records for the pass (gather
//! records, emitters seen, next-event estimates). Pixels and illuminance sensors trace the same
//! paths; a sensor path starts at the sensor with a cosine-distributed direction.

use glam::Vec3;
use rand::Rng as _;

use super::boundary::{Entered, Planes};
use super::by_light::ByLight;
use super::direct::{Part, Segment};
use super::estimator::{CameraSegment, Estimator, VolumeEstimator};
use super::oct::Oct;
use super::path::{MediumStep, PathStep, SurfaceStep};
use super::record::{
    CLASS_ALL, CLASS_C, CameraOutput, DirectRecord, EXTRA, PRIMARY, SegmentRecord, SurfaceRecord,
    VolumeRecord,
};
use super::rng::Rng;
use super::settings::GatherMode;
use super::{Integrator, Radii};
use crate::geometry::{Hit, Ray};
use crate::material::LobeKind;
use crate::medium::{Along, Mixture, Tracker, WalkEnd, sample_extinction, sample_scatter};
use crate::spectrum::Spectrum;
use crate::world::Scene;

/// A pixel's next-event estimates, summed over its camera paths (one record per pixel and
/// light, not per path).
pub struct NeeSums {
    /// Whether the sums are kept per light (light layers).
    pub layers: bool,
    medium: Option<ByLight>,
    surface: Option<ByLight>,
}

impl NeeSums {
    pub fn new(layers: bool) -> Self {
        Self {
            layers,
            medium: None,
            surface: None,
        }
    }

    /// Adds the sums to `out` as `pixel`'s records; `extra`: they are of a pixel's extra
    /// camera paths in a nested pass (`nest`).
    pub fn push_into(self, out: &mut CameraOutput, pixel: u32, extra: bool) {
        for (sum, to) in [
            (self.medium, &mut out.nee_medium),
            (self.surface, &mut out.nee_surface),
        ] {
            for (light, value) in sum.iter().flat_map(ByLight::parts) {
                to.push(DirectRecord {
                    pixel,
                    light,
                    value,
                    extra,
                });
            }
        }
    }
}

/// Adds `v * w * s` to a sum started on first use.
fn add(sum: &mut Option<ByLight>, layers: bool, v: &ByLight, w: &Spectrum, s: f32) {
    sum.get_or_insert_with(|| ByLight::new(layers))
        .add_weighted(v, w, s);
}

/// One camera path: its state, and what it records into the pass's output.
pub struct CameraPath<'a> {
    scene: &'a Scene,
    integrator: &'a Integrator,
    out: &'a mut CameraOutput,
    nee: &'a mut NeeSums,
    pixel: u32,
    n: usize,
    /// Spectral throughput from the camera.
    w: Spectrum,
    /// Whether medium segments still leave integration volumes.
    gathering: bool,
    /// Whether the path still sees emitters directly (false once they are gathered by volumes).
    sees_emitters: bool,
    /// The pass's gather radii.
    pub radii: Radii,
    /// Whether the path has had no scattering and no non-null surface event yet (a camera
    /// path's first volumes and surface spheres; false from the start for sensor paths).
    pub primary: bool,
    /// Whether the path is one of its pixel's extra paths in a nested pass (`nest`): its
    /// records say so.
    pub extra: bool,
    /// Where and with what density the path last left a glossy (non-delta) surface by a BSDF
    /// sample, for the MIS weight of emitters it then hits; None after the camera, a delta
    /// bounce or a medium scattering. A sensor path starts with its sensor and the density of
    /// its cosine-distributed direction.
    pub glossy_from: Option<(Vec3, f32)>,
    /// The surface the path last left or crossed, since the camera or its last medium
    /// scattering: the start plane of its next medium segment (`boundary`).
    entered: Option<Entered>,
}

impl<'a> CameraPath<'a> {
    pub fn new(
        scene: &'a Scene,
        integrator: &'a Integrator,
        pixel: u32,
        out: &'a mut CameraOutput,
        nee: &'a mut NeeSums,
    ) -> Self {
        let n = scene.grid.n;
        Self {
            scene,
            integrator,
            out,
            nee,
            pixel,
            n,
            w: Spectrum::splat(1.0, n),
            gathering: true,
            sees_emitters: true,
            radii: Radii::one(0.0),
            primary: true,
            extra: false,
            glossy_from: None,
            entered: None,
        }
    }

    fn first_extinction(&self) -> bool {
        self.integrator.settings.mode == GatherMode::FirstExtinction
    }

    /// The mixture of a camera segment in medium `m` with the path's throughput.
    fn mixture(&self, m: u32) -> Mixture {
        let med = &self.scene.media[m as usize];
        self.integrator.settings.channels().mixture(&self.w, med)
    }

    /// Leaves the estimator's volumes on the segment along `ray` in medium `m`. The segment is
    /// recorded with its first volume, so that one that leaves none (transmitted before the
    /// first sub-step of a sphere walk) costs nothing.
    /// `depth` is the segment's length in optical depth at density 1 (`along.depth(len)`, the
    /// length itself in a uniform medium): the estimator walks in it, and each volume is
    /// recorded at its distance along the ray. `end` is the surface the segment ends on.
    #[allow(clippy::too_many_arguments)]
    fn leave_volumes<E: VolumeEstimator>(
        &mut self,
        e: &E,
        m: u32,
        (ray, end): (&Ray, Option<&Hit>),
        (depth, len, along): (f32, f32, &Along),
        (mix, track): (&Mixture, Option<&Tracker>),
        rng: &mut Rng,
    ) -> WalkEnd {
        let classes = if self.first_extinction() {
            CLASS_ALL
        } else {
            CLASS_C
        } | if self.primary { PRIMARY } else { 0 }
            | if self.extra { EXTRA } else { 0 };
        let cam = CameraSegment {
            medium: &self.scene.media[m as usize],
            medium_id: m,
            dir: ray.d,
            radius: self.radii.bound(),
            mix,
            track,
            len: depth,
            along,
            first_extinction: self.first_extinction(),
        };
        let (out, pixel, w, n) = (&mut *self.out, self.pixel, &self.w, self.n);
        let (scene, entered) = (self.scene, self.entered.as_ref());
        let mut segment = None;
        // Whether the segment's planes are in the pass's table yet (`boundary::PlaneTable`).
        let mut tabled = false;
        e.camera_segment(&cam, rng, |s, scale| {
            let (segment, planes) = *segment.get_or_insert_with(|| {
                let throughput = out.throughputs.insert(w.as_slice(n));
                out.segments.push(SegmentRecord {
                    origin: ray.o,
                    pixel,
                    dir: ray.d,
                    throughput,
                    medium: m as u16,
                    classes,
                });
                // Only spheres are cut (cylinders never read the planes, nor pay for them).
                let planes = if E::PIECES {
                    Planes::NONE
                } else {
                    Planes::of_segment(scene, m, ray, (entered, end), cam.radius)
                };
                (out.segments.len() as u32 - 1, planes)
            });
            // Spheres come at their optical depth, cylinder pieces at their distances; a
            // sphere that may reach through a plane of its segment carries its scale negated
            // (`VolumeRecord::near_boundary`) and has the planes tabled.
            let (s, scale) = if E::PIECES {
                (s.min(len), scale)
            } else {
                let s = along.distance(s).min(len);
                if planes.near(s, ray.d, cam.radius) {
                    if !tabled {
                        out.planes.push(segment, planes);
                        tabled = true;
                    }
                    (s, -scale)
                } else {
                    (s, scale)
                }
            };
            out.volumes.push(VolumeRecord { segment, s, scale });
        })
        .at_distance(along, len)
    }

    /// `integrator.expected_transmission`: whatever the walk's outcome, the path goes on past
    /// the segment with throughput times `e^{-st_l len}` per bin. The walk's `Transmitted`
    /// weight `e^{-st_l len} / Tmix(len)` comes with probability `Tmix(len)`, so this is its
    /// expectation: the part behind the segment keeps its mean per bin and loses the coin's
    /// variance, while the segment's volumes (left before the outcome) are unchanged.
    /// In a tracked medium the factor is ratio tracking's estimate of it (`tr`), unbiased per
    /// bin.
    fn expected_transmission(&mut self, m: u32, depth: f32, tr: Option<Spectrum>) -> MediumStep {
        let tr = tr.unwrap_or_else(|| {
            self.scene.media[m as usize]
                .sigma_t
                .transmittance(depth, self.n)
        });
        if tr.is_zero() {
            return MediumStep::Ended;
        }
        self.w *= tr;
        MediumStep::Reached
    }

    /// Applies the end of a medium segment to the path (method note 4).
    fn after_walk(&mut self, end: WalkEnd) -> MediumStep {
        match end {
            WalkEnd::Transmitted { weight } => {
                self.w *= weight;
                MediumStep::Reached
            }
            WalkEnd::Absorbed { .. } => MediumStep::Ended,
            WalkEnd::Scattered { s, weight } => {
                if self.first_extinction() {
                    MediumStep::Ended
                } else {
                    self.w *= weight;
                    MediumStep::Scattered(s)
                }
            }
        }
    }
}

impl PathStep for CameraPath<'_> {
    /// One straight camera segment of length `len` inside medium `m` (method notes 2-5).
    fn medium(
        &mut self,
        m: u32,
        ray: &Ray,
        (len, hit): (f32, Option<&Hit>),
        rng: &mut Rng,
    ) -> MediumStep {
        let mix = self.mixture(m);
        let scene = self.scene;
        let med = &scene.media[m as usize];
        // Walks and flights run in optical depth at density 1 (uniform media: the distance),
        // or in distance by null collisions in a tracked medium (method note 10).
        let tracker = med
            .tracking
            .as_deref()
            .map(|t| Tracker::new(t, ray.o, ray.d));
        let track = tracker.as_ref();
        let along = match track {
            None => med.density.along(ray.o, ray.d),
            Some(_) => Along::Identity,
        };
        let depth = along.depth(len);
        if !self.gathering {
            // Free flight without gathering: the continuation of a see-through path (note 4).
            let end = sample_extinction(med, (&mix, track), depth, rng).at_distance(&along, len);
            return self.after_walk(end);
        }
        if !self.first_extinction() {
            // See-through: volumes gather class C on this first medium segment only.
            self.gathering = false;
        }
        let integrator = self.integrator;
        if let Some(direct) = &integrator.direct {
            // Direct light over the whole segment, whatever the walk does on it (note 9).
            let seg = Segment {
                medium: m,
                ray,
                len,
                mix: &mix,
                along: &along,
                track,
            };
            let mut acc = ByLight::new(self.nee.layers);
            direct.medium_segment(self.scene, &seg, rng, &mut acc);
            add(&mut self.nee.medium, self.nee.layers, &acc, &self.w, 1.0);
        }
        let end = match &integrator.estimator {
            Estimator::Spheres(e) => {
                self.leave_volumes(e, m, (ray, hit), (depth, len, &along), (&mix, track), rng)
            }
            Estimator::Cylinder(e) => {
                self.leave_volumes(e, m, (ray, hit), (depth, len, &along), (&mix, track), rng)
            }
            Estimator::TruncatedCylinder(e) => {
                self.leave_volumes(e, m, (ray, hit), (depth, len, &along), (&mix, track), rng)
            }
            Estimator::LongCylinder(e) => {
                self.leave_volumes(e, m, (ray, hit), (depth, len, &along), (&mix, track), rng)
            }
        };
        // An endless segment (a medium without a boundary ahead) keeps the walk's outcome.
        if integrator.settings.expected_transmission() && self.first_extinction() && len.is_finite()
        {
            let tr = track.map(|t| t.transmittance((0.0, len), &med.sigma_t, self.n, rng));
            return self.expected_transmission(m, depth, tr);
        }
        self.after_walk(end)
    }

    fn scatter(&mut self, m: u32, ray: &Ray, t: f32, depth: u32, rng: &mut Rng) -> Option<Ray> {
        // Light reaching the path after a medium scattering is class C light that the volumes
        // already gathered (method note 6).
        self.sees_emitters = false;
        self.glossy_from = None;
        self.primary = false;
        self.entered = None;
        let p = ray.o + ray.d * t;
        let med = &self.scene.media[m as usize];
        let ch = self.integrator.settings.channels();
        let (d, factors) = sample_scatter(med, ray.d, &self.w, ch.pick, ch.floor, rng);
        if let Some(f) = factors {
            self.w *= f;
        }
        self.roulette(depth, rng).then_some(Ray { o: p, d })
    }

    fn vacuum(&mut self, _ray: &Ray, _hit: Option<&Hit>) {}

    /// Emission, gathering on the diffuse part, continuation through the non-diffuse part.
    fn surface(&mut self, hit: &Hit, ray: &Ray, rng: &mut Rng) -> SurfaceStep {
        let scene = self.scene;
        let wo = -ray.d;
        let shape = scene.geometry.shape(hit.shape);
        if let Some(l) = shape.light
            && self.sees_emitters
        {
            let le = scene.lights.lights()[l as usize].radiance(hit, wo);
            if !le.is_zero() {
                let v = match (&self.integrator.direct, self.glossy_from) {
                    (Some(d), Some((from, pdf))) => {
                        le * self.w * d.emission_weight(scene, l, ray, hit, from, pdf)
                    }
                    (Some(_), None) | (None, _) => le * self.w,
                };
                self.out.direct.push(DirectRecord {
                    pixel: self.pixel,
                    light: Some(l),
                    value: v,
                    extra: self.extra,
                });
            }
        }
        let Some(mat_id) = shape.material else {
            self.entered = Some(Entered::new(hit, ray.d, true));
            return SurfaceStep::Null;
        };
        let material = &scene.materials[mat_id as usize];
        let pd = material.diffuse_probability(wo, hit);
        if pd > 0.0 && rng.random::<f32>() < pd {
            self.gather_here(hit, wo, pd);
            if let Some(direct) = &self.integrator.direct {
                let mut v = ByLight::new(self.nee.layers);
                direct.reflected(scene, hit, wo, material, Part::Diffuse, rng, &mut v);
                add(
                    &mut self.nee.surface,
                    self.nee.layers,
                    &v,
                    &self.w,
                    1.0 / pd,
                );
            }
            return SurfaceStep::Stop;
        }
        if let Some(direct) = &self.integrator.direct
            && material.has_glossy()
        {
            let mut v = ByLight::new(self.nee.layers);
            direct.reflected(scene, hit, wo, material, Part::Glossy, rng, &mut v);
            add(
                &mut self.nee.surface,
                self.nee.layers,
                &v,
                &self.w,
                1.0 / (1.0 - pd),
            );
        }
        let u = Vec3::new(rng.random(), rng.random(), rng.random());
        let Some(s) = material.sample_nondiffuse(wo, hit, u) else {
            return SurfaceStep::Stop;
        };
        self.glossy_from = match s.kind {
            LobeKind::Glossy => Some((hit.p, material.pdf_nondiffuse(wo, s.wi, hit))),
            LobeKind::Specular | LobeKind::Diffuse => None,
        };
        self.w *= s.weight * (1.0 / (1.0 - pd));
        if self.w.is_zero() {
            return SurfaceStep::Stop;
        }
        self.primary = false;
        self.entered = Some(Entered::new(hit, s.wi, false));
        SurfaceStep::Scattered(s.wi)
    }

    /// Camera throughput starts at 1 and only falls through events: after the first three
    /// bounces (which carry most of the image, so they are never cut) the path survives with
    /// probability `max_l W_l` (at most 1) and is reweighted by its inverse.
    fn roulette(&mut self, depth: u32, rng: &mut Rng) -> bool {
        if depth < 3 {
            return true;
        }
        let p = self.w.max_value().min(1.0);
        if p <= 0.0 || rng.random::<f32>() >= p {
            return false;
        }
        self.w *= 1.0 / p;
        true
    }
}

impl CameraPath<'_> {
    /// Leaves a surface sphere on the diffuse part chosen with probability `pd`. Near an edge
    /// of its surface the sphere's weight is divided by the fraction of its disc on the surface
    /// (`Geometry::disc_fraction`), so that it estimates the mean over the part that can be hit.
    fn gather_here(&mut self, hit: &Hit, wo: Vec3, pd: f32) {
        let n = if hit.ns.dot(wo) >= 0.0 {
            hit.ns
        } else {
            -hit.ns
        };
        let throughput = self.out.throughputs.insert(self.w.as_slice(self.n));
        let geometry = &self.scene.geometry;
        let fraction = |r: f32| geometry.disc_fraction(hit.shape, hit.p, r);
        let direct = fraction(self.radii.direct);
        let indirect = if self.radii.indirect == self.radii.direct {
            direct
        } else {
            fraction(self.radii.indirect)
        };
        self.out.surfaces.push(SurfaceRecord {
            p: hit.p,
            pixel: self.pixel,
            n: Oct::encode(n),
            wo: Oct::encode(wo),
            shape: hit.shape,
            uv: hit.uv,
            throughput,
            scale: 1.0 / (pd * direct),
            scale_indirect: 1.0 / (pd * indirect),
            primary: self.primary,
            extra: self.extra,
        });
    }
}
