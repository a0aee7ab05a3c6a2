//! The forward tracer's gathering into integration volumes: a forward segment, in a medium or
//! outside (open media), against the volumes of the image's and the sensor paths' gather
//! structures, with the render's estimator.

use super::ForwardTracer;
use crate::film::{BlendRadius, Layer};
use crate::geometry::Ray;
use crate::integrator::estimator::{Estimator, ForwardSegment, VolumeEstimator};
use crate::integrator::gather::Gather;
use crate::integrator::nest::{self, Deposit};
use crate::integrator::record::{EXTRA, PRIMARY};
use crate::integrator::target::Target;
use crate::medium::{Along, ForwardFlight};

/// The change of variable outside media.
static IDENTITY: Along = Along::Identity;

impl ForwardTracer<'_> {
    /// Gathers the forward segment `ray` up to `len`, in medium `m` (None: outside media), into
    /// the volumes it meets (the image's, then the sensor paths'); `flight` is the segment's
    /// flight in a medium, with the medium's change of variable along the ray.
    pub(super) fn gather_volumes(
        &mut self,
        m: Option<u32>,
        ray: &Ray,
        len: f32,
        flight: Option<(&ForwardFlight, &Along)>,
    ) {
        let image = Target::Image { light: self.light };
        self.gather_volumes_in((self.gather, image), m, ray, len, flight);
        if let Some(s) = self.sensors {
            let target = Target::Sensors {
                scale: s.path_scale,
            };
            self.gather_volumes_in((&s.gather, target), m, ray, len, flight);
        }
    }

    fn gather_volumes_in(
        &mut self,
        into: (&Gather, Target),
        m: Option<u32>,
        ray: &Ray,
        len: f32,
        flight: Option<(&ForwardFlight, &Along)>,
    ) {
        let integrator = self.integrator;
        match &integrator.estimator {
            Estimator::Spheres(e) => self.gather_with(e, into, m, ray, len, flight),
            Estimator::Cylinder(e) => self.gather_with(e, into, m, ray, len, flight),
            Estimator::TruncatedCylinder(e) => self.gather_with(e, into, m, ray, len, flight),
            Estimator::LongCylinder(e) => self.gather_with(e, into, m, ray, len, flight),
        }
    }

    /// `gather_volumes_in` for one estimator. Volumes of another medium count too when their
    /// medium is bounded only by index-matched boundaries, across which the radiance field is
    /// continuous (method note 8).
    ///
    /// This, the gather's traversal and batch, the estimator's hit and the chunk's splat are
    /// all `#[inline(always)]`: one function with no calls between them is 3.4 % faster on
    /// fog-cube, the same bits (docs/performance.md, "Three speed-ups with the same bits").
    #[inline(always)]
    fn gather_with<E: VolumeEstimator>(
        &mut self,
        e: &E,
        (gather, target): (&Gather, Target),
        m: Option<u32>,
        ray: &Ray,
        len: f32,
        flight: Option<(&ForwardFlight, &Along)>,
    ) {
        let scene = self.scene;
        let n = scene.grid.n;
        let radius = gather.radii.of(self.first_flight);
        let (blend, small) = (self.blends(gather, target), gather.radii.direct);
        let (norm, class) = (self.norm, self.class);
        let nest = self.nested(target);
        let skip_primary = if self.skips_primary(target) {
            PRIMARY
        } else {
            0
        };
        let buf = &mut *self.buf;
        let seg_medium = m.map_or(u16::MAX, |m| m as u16);
        // A grey flight's flux does not change along the segment: skip its survival weights.
        let fwd = ForwardSegment {
            o: ray.o,
            d: ray.d,
            len,
            flux: &self.flux,
            flight: flight
                .map(|(f, _)| f)
                .filter(|f| f.mixture().sigma_t_span() > 0.0),
            along: flight.map_or(&IDENTITY, |(_, along)| along),
        };
        let mut hits = 0u64;
        let mut first_paths_hits = 0u64;
        let planes = &gather.planes;
        gather.volumes_along(ray.o, ray.d, len, |seg, rec| {
            hits += 1;
            first_paths_hits += u64::from(seg.classes & EXTRA == 0);
            if seg.classes & class == 0 || seg.classes & skip_primary != 0 {
                return;
            }
            let same = seg.medium == seg_medium;
            if !same && (E::WHOLE_FORWARD_SEGMENT || !scene.open_medium(seg.medium as u32)) {
                return;
            }
            // The record's own medium scatters the light towards the camera.
            let med = &scene.media[seg.medium as usize];
            let w = gather.throughput(seg.throughput);
            if let Some(factor) = e.contribution(&fwd, (seg, planes), rec, w, med, radius) {
                let (pixel, f) = (seg.pixel, &factor.0[..n]);
                if blend {
                    // The smaller ball lies inside the larger: only its hits add to it.
                    let at = (BlendRadius::Large, Layer::Medium);
                    buf.splat_blend(at, pixel as usize, w, f, norm);
                    let large = (radius, &factor);
                    let seg = (seg, planes);
                    if let Some(inner) =
                        e.contribution_within(&fwd, seg, rec, (w, med), large, small)
                    {
                        let at = (BlendRadius::Small, Layer::Medium);
                        buf.splat_blend(at, pixel as usize, w, &inner.0[..n], norm);
                    }
                } else {
                    target.splat(buf, Layer::Medium, pixel, w, f, norm);
                }
                let deposit = Deposit::Gathered {
                    extra_path: seg.classes & EXTRA != 0,
                };
                nest::add(buf, nest, deposit, pixel, (w, &factor.0[..n], norm));
            }
        });
        self.hits += hits;
        self.first_paths_hits += first_paths_hits;
    }
}
