//! Where the light pass's gather splats go: the image (and the forward ray's light layer) or
//! the illuminance sensors.

use crate::film::{ChunkSplats, Layer};
use crate::spectrum::Spectrum;

/// Where a gather structure's splats go.
#[derive(Clone, Copy)]
pub enum Target {
    /// The image, and the layer of the light the forward ray came from.
    Image { light: u32 },
    /// The sensors' slots (the sensor paths' records name a sensor as their pixel), with the
    /// pixel scale times `scale`.
    Sensors { scale: f32 },
}

impl Target {
    /// Adds the sample `w * f * norm` to a pixel of record `pixel` (see `Target`).
    #[inline(always)]
    pub fn splat(
        self,
        buf: &mut ChunkSplats,
        layer: Layer,
        pixel: u32,
        w: &[f32],
        f: &[f32],
        norm: f32,
    ) {
        match self {
            Target::Image { light } => {
                buf.splat_from(layer, pixel as usize, Some(light), w, f, norm);
            }
            Target::Sensors { scale } => {
                let mut v = Spectrum::ZERO;
                for ((v, w), f) in v.0.iter_mut().zip(w).zip(f) {
                    *v = w * f;
                }
                buf.splat_sensor(pixel as usize, &v.0[..f.len()], norm * scale);
            }
        }
    }
}
