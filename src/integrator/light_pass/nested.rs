//! The forward tracer's part in a nested pass (`integrator::nest`): which of the pass's
//! estimates a splat joins.

use super::{ForwardTracer, camera_splat};
use crate::film::Layer;
use crate::integrator::nest::{self, Deposit, Nest};
use crate::integrator::target::Target;
use crate::spectrum::Spectrum;

impl<'a> ForwardTracer<'a> {
    /// The nest and whether this ray is an extra one, for splats into `target` (the image's
    /// only: the sensors' are no pilots' business).
    pub(super) fn nested(&self, target: Target) -> Option<(&'a Nest, bool)> {
        let image = matches!(target, Target::Image { .. });
        self.nest.filter(|_| image).map(|n| (n, self.extra_ray))
    }

    /// Puts a connection to the camera `(pixel, v)` into the pass (`camera_splat::put`) and
    /// into the nested estimates it belongs to.
    pub(super) fn splat_to_camera(&mut self, layer: Layer, (pixel, v): (u32, Spectrum), norm: f32) {
        let n = self.scene.grid.n;
        camera_splat::put(self.buf, layer, (pixel, v), self.light, n, norm);
        let nest = self.nested(Target::Image { light: self.light });
        let one = Spectrum::splat(1.0, n);
        let sample = (&v.0[..n], &one.0[..n], norm);
        nest::add(self.buf, nest, Deposit::CameraSplat, pixel, sample);
    }
}
