//! Building the geometry: each shape's primitives (triangles or one analytic primitive), areas
//! and area samplers, checked, then the BVH over all of them.

use std::time::Duration;

use obvhs::{
    BvhBuildParams,
    aabb::Aabb as BvhAabb,
    cwbvh::{CwBvh, builder::build_cwbvh},
};

use super::{AreaSampler, bvh_pad};
use crate::geometry::analytic::{Analytic, AnalyticKind};
use crate::geometry::limits::{collapsed_at, out_of_range};
use crate::geometry::tessellate::{WorldTri, tessellate};
use crate::geometry::{Aabb, GeometryError, ShapeDesc, ShapeKind};

/// The primitives of the shapes added so far: world triangles, analytic shapes, and each
/// shape's area and area sampler.
#[derive(Default)]
pub(super) struct Parts {
    pub world: Vec<WorldTri>,
    pub tri_shape: Vec<u32>,
    pub analytic: Vec<Analytic>,
    pub areas: Vec<f32>,
    pub samplers: Vec<AreaSampler>,
}

impl Parts {
    /// Adds shape `i`, checking its parameters.
    pub fn add(&mut self, i: usize, desc: &ShapeDesc) -> Result<(), GeometryError> {
        let bad = |message: &str| GeometryError::InvalidShape {
            shape: i,
            message: message.into(),
        };
        if !desc.transform.is_valid() {
            return Err(bad("transform is singular or not finite"));
        }
        let positive = |v: &[f32]| v.iter().all(|x| *x > 0.0 && x.is_finite());
        let analytic = match desc.kind {
            ShapeKind::Sphere { radius } => Some(AnalyticKind::Sphere { radius }),
            ShapeKind::Disc { radius } => Some(AnalyticKind::Disc { radius }),
            ShapeKind::Quad { size } if !positive(&size.to_array()) => {
                return Err(bad("size must be positive and finite"));
            }
            ShapeKind::Box { size } if !positive(&size.to_array()) => {
                return Err(bad("size must be positive and finite"));
            }
            ShapeKind::Box { size } => {
                let a = Analytic::cuboid(size, desc.transform, i as u32);
                return self.push_analytic(a).map_err(|m| bad(&m));
            }
            ShapeKind::Quad { .. } | ShapeKind::Mesh { .. } => None,
        };
        match analytic {
            Some(kind) => self.add_analytic(i, desc, kind).map_err(|m| bad(&m)),
            None => self.add_triangles(i, desc),
        }
    }

    fn add_analytic(
        &mut self,
        i: usize,
        desc: &ShapeDesc,
        kind: AnalyticKind,
    ) -> Result<(), String> {
        let radius = match kind {
            AnalyticKind::Sphere { radius } | AnalyticKind::Disc { radius } => radius,
            AnalyticKind::Box { half, .. } => half.min_element(),
        };
        if !(radius > 0.0 && radius.is_finite()) {
            return Err("radius must be positive".into());
        }
        self.push_analytic(Analytic {
            kind,
            transform: desc.transform,
            shape: i as u32,
        })
    }

    /// Adds an analytic primitive (its parameters checked) once its bounds are in range.
    fn push_analytic(&mut self, a: Analytic) -> Result<(), String> {
        let (lo, hi) = a.bounds();
        if let Some(why) = out_of_range(lo).or_else(|| out_of_range(hi)) {
            return Err(why);
        }
        self.areas.push(a.area());
        self.samplers
            .push(AreaSampler::Analytic(self.analytic.len() as u32));
        self.analytic.push(a);
        Ok(())
    }

    fn add_triangles(&mut self, i: usize, desc: &ShapeDesc) -> Result<(), GeometryError> {
        let first = self.world.len();
        tessellate(i, desc, &mut self.world)?;
        let bad = |message: String| GeometryError::InvalidShape { shape: i, message };
        let mut total = 0.0f32;
        let mut cdf = Vec::with_capacity(self.world.len() - first);
        for t in &self.world[first..] {
            if let Some(why) = t.v.iter().find_map(|&v| out_of_range(v)) {
                return Err(bad(why));
            }
            total += 0.5 * (t.v[1] - t.v[0]).cross(t.v[2] - t.v[0]).length();
            cdf.push(total);
        }
        // Vertices that round to the same f32 values (a small shape far from the origin) leave
        // triangles no ray can hit: the shape would be silently missing from the image.
        if !cdf.is_empty() && total <= 0.0 {
            return Err(bad(collapsed_at(self.world[first].v[0])));
        }
        self.tri_shape.resize(self.world.len(), i as u32);
        self.areas.push(total);
        self.samplers.push(if cdf.is_empty() {
            AreaSampler::Empty
        } else {
            AreaSampler::Triangles {
                first: first as u32,
                cdf,
            }
        });
        Ok(())
    }
}

/// The wide BVH over the triangles then the analytic shapes (their primitive ids in that
/// order), and the bounds of everything.
pub(super) fn build_bvh(world: &[WorldTri], analytic: &[Analytic]) -> (Option<CwBvh>, Aabb) {
    let mut boxes: Vec<BvhAabb> = world
        .iter()
        .map(|t| {
            let lo = t.v[0].min(t.v[1]).min(t.v[2]);
            let hi = t.v[0].max(t.v[1]).max(t.v[2]);
            let pad = bvh_pad(lo, hi);
            BvhAabb::new((lo - pad).into(), (hi + pad).into())
        })
        .collect();
    boxes.extend(analytic.iter().map(|a| {
        let (lo, hi) = a.bounds();
        let pad = bvh_pad(lo, hi);
        BvhAabb::new((lo - pad).into(), (hi + pad).into())
    }));
    let mut bounds = Aabb::EMPTY;
    for b in &boxes {
        bounds.grow(b.min.into());
        bounds.grow(b.max.into());
    }
    let bvh = (!boxes.is_empty()).then(|| {
        build_cwbvh(
            &boxes,
            BvhBuildParams::medium_build(),
            &mut Duration::default(),
        )
    });
    (bvh, bounds)
}
