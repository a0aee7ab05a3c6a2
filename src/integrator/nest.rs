//! Nested estimates of one pass: the automatic settings' budget pilots as one pass.
//!
//! A pass of `k s` camera paths per pixel and `k n` forward rays holds, in its first `s` paths
//! of every pixel and its first `n` rays, a pass of `s` paths and `n` rays: the same
//! estimator on a subset of the same samples. Each camera path is tagged as one of the first
//! `s` of its pixel or an extra one (`record::EXTRA`, `SurfaceRecord::extra`,
//! `DirectRecord::extra`) and each forward ray as one of the first `n` or an extra one, and
//! every deposit of the pass is also added, with its factor, to the per-pixel totals of each
//! [`Variant`] it belongs to (`PassBuffer::variants`). One camera pass and one light pass so
//! give the four budget pilots (`auto::Role`: s and n, s and k n, k s and n, k s and k n) at
//! the cost of the largest alone, where four passes cost 1 + 1 + k + k camera passes and
//! 1 + k + 1 + k light passes' worth. The estimates share their samples, so their differences
//! carry less noise than those of separate passes on the same random numbers, which the
//! pilots' paired gains and noise split use (`auto::gain`, `auto::model::NoiseSplit`).
//!
//! Why the factors: the pass weighs a camera-path deposit by `1 / (k s k n)`; the estimate of
//! the first `s` paths and `n` rays weighs it by `1 / (s n)`, `k^2` times more, and only if
//! both its path and its ray are among the first. The splat to the camera weighs by
//! `1 / rays` (no camera paths), and a camera path's direct light by `1 / paths` (no rays).

use std::sync::atomic::{AtomicU64, Ordering};

use super::record::{CameraOutput, EXTRA, VolumeRecord};
use crate::film::{ChunkSplats, PassBuffer};

/// One estimate nested in a pass: its camera paths are the first [`Nest::paths`] of each
/// pixel's (or all), its forward rays the first [`Nest::rays`] (or all).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Variant {
    pub sub_paths: bool,
    pub sub_rays: bool,
}

/// What a deposit came from, for the variants it joins.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Deposit {
    /// A forward ray found a camera path's volume or surface sphere; `extra_path`: the path
    /// is not one of its pixel's first [`Nest::paths`].
    Gathered { extra_path: bool },
    /// A forward ray splatted to the camera directly (`camera_splat`): no camera path.
    CameraSplat,
    /// A camera path's own light (an emitter it saw, a next-event estimate): no forward ray.
    Direct { extra_path: bool },
}

/// The variants of a nested pass and where its subsets end.
#[derive(Clone, Debug, PartialEq)]
pub struct Nest {
    /// Camera paths per pixel of the subset (the first of each pixel's).
    pub paths: u32,
    /// Forward rays of the subset (the first of each light pass's).
    pub rays: u64,
    /// The pass's camera paths per pixel over `paths`, and its rays over `rays`.
    pub path_factor: f32,
    pub ray_factor: f32,
    pub variants: Vec<Variant>,
}

impl Nest {
    /// The factor with which a deposit, weighed as the whole pass weighs it, joins variant
    /// `v`'s estimate; None when it is not in it. `extra_ray`: the deposit's forward ray is
    /// not one of the first [`Nest::rays`] (ignored for direct light).
    #[inline]
    pub fn factor(&self, v: Variant, deposit: Deposit, extra_ray: bool) -> Option<f32> {
        let (extra_path, uses_path, uses_ray) = match deposit {
            Deposit::Gathered { extra_path } => (extra_path, true, true),
            Deposit::CameraSplat => (false, false, true),
            Deposit::Direct { extra_path } => (extra_path, true, false),
        };
        let sub_path = v.sub_paths && uses_path;
        let sub_ray = v.sub_rays && uses_ray;
        if (sub_path && extra_path) || (sub_ray && extra_ray) {
            return None;
        }
        let p = if sub_path { self.path_factor } else { 1.0 };
        let r = if sub_ray { self.ray_factor } else { 1.0 };
        Some(p * r)
    }

    /// Each variant's factor for a deposit (`factor`), in variant order.
    #[inline]
    pub fn factors(&self, deposit: Deposit, extra_ray: bool) -> [Option<f32>; MAX_VARIANTS] {
        let mut out = [None; MAX_VARIANTS];
        for (o, v) in out.iter_mut().zip(&self.variants) {
            *o = self.factor(*v, deposit, extra_ray);
        }
        out
    }
}

#[cfg(test)]
impl Nest {
    /// The four budget estimates (s n, s k n, k s n, k s k n, in that order) of a pass of `k`
    /// times `paths` camera paths and `k` times `rays` forward rays: the tests' nest.
    pub fn four(paths: u32, rays: u64, k: f32) -> Self {
        let v = |sub_paths, sub_rays| Variant {
            sub_paths,
            sub_rays,
        };
        Nest {
            paths,
            rays,
            path_factor: k,
            ray_factor: k,
            variants: vec![
                v(true, true),
                v(true, false),
                v(false, true),
                v(false, false),
            ],
        }
    }
}

/// The most variants a nest holds (the four budget pilots).
pub const MAX_VARIANTS: usize = 4;

/// Adds a deposit splatted into the pass as `w * f * norm` at `pixel` to the variants of
/// `nest` it belongs to (`Nest::factor`); `nest` carries whether the deposit's forward ray is
/// an extra one. Nothing without a nest.
#[inline(always)]
pub fn add(
    buf: &mut ChunkSplats,
    nest: Option<(&Nest, bool)>,
    deposit: Deposit,
    pixel: u32,
    sample: (&[f32], &[f32], f32),
) {
    if let Some((nest, extra_ray)) = nest {
        let factors = nest.factors(deposit, extra_ray);
        buf.add_to_variants(pixel as usize, sample, &factors[..nest.variants.len()]);
    }
}

/// Adds a camera pass's own light (what its paths saw directly and their next-event
/// estimates, splatted into the pass at `scale`: `camera_pass::splat_direct`) to the variants
/// of `nest` it belongs to.
pub fn add_direct(buf: &mut PassBuffer, nest: &Nest, out: &CameraOutput, scale: f32) {
    let n = buf.n;
    let pixels = buf.pixels;
    for r in out
        .direct
        .iter()
        .chain(&out.nee_medium)
        .chain(&out.nee_surface)
    {
        let v = r.value.as_slice(n);
        if !v.iter().all(|x| (x * scale).is_finite()) {
            continue;
        }
        let total: f32 = v.iter().map(|x| x * scale).sum();
        let deposit = Deposit::Direct {
            extra_path: r.extra,
        };
        let factors = nest.factors(deposit, false);
        for (i, f) in factors.iter().take(nest.variants.len()).enumerate() {
            if let (Some(f), Some(t)) = (f, buf.variants.get_mut(i * pixels + r.pixel as usize)) {
                *t += f64::from(total * f);
            }
        }
    }
}

/// What a nested pass counted, for each variant's work (`auto::Work`).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct NestCounts {
    /// Camera paths started, and those of them among their pixel's first.
    pub paths: u64,
    pub sub_paths: u64,
    /// Integration volumes left, and those of the first paths.
    pub volumes: u64,
    pub sub_volumes: u64,
    /// Forward rays traced.
    pub rays: u64,
    /// Gather candidates met: by every ray on every record, by the first rays on every record,
    /// by every ray on the first paths' records, by the first rays on the first paths' records.
    pub hits: [u64; 4],
}

impl NestCounts {
    /// Counts a camera pass's (or tile's) paths and volumes, and those of the first paths.
    pub fn add_camera(&mut self, out: &CameraOutput) {
        self.paths += out.paths;
        self.sub_paths += out.paths - out.extra_paths;
        self.volumes += out.volumes.len() as u64;
        let first = |v: &&VolumeRecord| {
            let seg = out.segments.get(v.segment as usize);
            seg.is_some_and(|s| s.classes & EXTRA == 0)
        };
        self.sub_volumes += out.volumes.iter().filter(first).count() as u64;
    }

    /// Counts a light pass's rays and gather candidates: all of them, and the nest's
    /// (`light_pass::LightJob::nested_hits`).
    pub fn add_light(&mut self, rays: u64, hits: &AtomicU64, nested: &[AtomicU64; 3]) {
        self.rays += rays;
        self.hits[0] += hits.load(Ordering::Relaxed);
        for (h, n) in self.hits[1..].iter_mut().zip(nested) {
            *h += n.load(Ordering::Relaxed);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn nest() -> Nest {
        Nest::four(1, 10, 4.0)
    }

    /// Each variant's factor is its own norm over the pass's, for the deposits it keeps.
    #[test]
    fn factors_weigh_each_deposit_as_its_variant_would() {
        let n = nest();
        let g = |extra_path| Deposit::Gathered { extra_path };
        let d = |extra_path| Deposit::Direct { extra_path };
        // (s, n), (s, k n), (k s, n), (k s, k n).
        assert_eq!(
            n.factors(g(false), false),
            [Some(16.0), Some(4.0), Some(4.0), Some(1.0)]
        );
        assert_eq!(
            n.factors(g(true), false),
            [None, None, Some(4.0), Some(1.0)]
        );
        assert_eq!(
            n.factors(g(false), true),
            [None, Some(4.0), None, Some(1.0)]
        );
        assert_eq!(n.factors(g(true), true), [None, None, None, Some(1.0)]);
        assert_eq!(
            n.factors(Deposit::CameraSplat, false),
            [Some(4.0), Some(1.0), Some(4.0), Some(1.0)]
        );
        assert_eq!(
            n.factors(Deposit::CameraSplat, true),
            [None, Some(1.0), None, Some(1.0)]
        );
        assert_eq!(
            n.factors(d(false), true),
            [Some(4.0), Some(4.0), Some(1.0), Some(1.0)]
        );
        assert_eq!(
            n.factors(d(true), false),
            [None, None, Some(1.0), Some(1.0)]
        );
    }
}
