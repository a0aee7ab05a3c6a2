//! What a pilot pass gives the tuner: its per-pixel totals and its work, counted, and those of
//! the estimates nested in it (`integrator::nest`).

use super::COST_WEIGHTS;
use crate::film::PassBuffer;
use crate::integrator::nest::{Nest, NestCounts, Variant};

/// Deterministic work counters of a pass.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Work {
    pub paths: u64,
    pub volumes: u64,
    pub rays: u64,
    pub hits: u64,
}

impl Work {
    /// The counters weighed into seconds on the reference machine.
    pub fn parts(&self) -> [f64; 4] {
        let n = [self.paths, self.volumes, self.rays, self.hits];
        std::array::from_fn(|i| n[i] as f64 * COST_WEIGHTS[i])
    }

    pub fn cost(&self) -> f64 {
        self.parts().iter().sum()
    }
}

/// What a pilot pass gave: the pass's per-pixel totals and work, and those of each estimate
/// nested in it (`Tuner::nest`), in the nest's order.
#[derive(Clone, Debug, Default)]
pub struct PilotResult {
    pub totals: Vec<f64>,
    pub work: Work,
    pub variants: Vec<(Vec<f64>, Work)>,
}

impl PilotResult {
    /// What pilot pass `buf` gave: its totals and work, and those of the estimates nested in
    /// it (`nest`, with what the pass counted for them).
    pub fn from_pass(
        buf: &PassBuffer,
        work: Work,
        nest: Option<&Nest>,
        counts: &NestCounts,
    ) -> Self {
        let pixels = buf.pixels;
        let variants = nest.map_or_else(Vec::new, |nest| {
            let totals = buf.variants.chunks_exact(pixels.max(1));
            (nest.variants.iter().zip(totals))
                .map(|(v, t)| (t.to_vec(), variant_work(counts, nest, *v)))
                .collect()
        });
        Self {
            totals: pixel_totals(&buf.data, pixels, buf.n),
            work,
            variants,
        }
    }
}

/// The work of variant `v` of `nest`: the counters of its own paths and rays.
pub fn variant_work(counts: &NestCounts, nest: &Nest, v: Variant) -> Work {
    let (paths, volumes) = if v.sub_paths {
        (counts.sub_paths, counts.sub_volumes)
    } else {
        (counts.paths, counts.volumes)
    };
    let rays = if v.sub_rays {
        (counts.rays as f64 / f64::from(nest.ray_factor)).round() as u64
    } else {
        counts.rays
    };
    let hits = counts.hits[usize::from(v.sub_rays) | (usize::from(v.sub_paths) << 1)];
    Work {
        paths,
        volumes,
        rays,
        hits,
    }
}

/// Work of a pass that traced 1/k of the pixels, as the whole image would have cost: the
/// counters that grow with the pixels traced (camera paths, their volumes, and the gather hits
/// on them) times k; the forward rays are the pass's own.
pub(super) fn scaled(w: &Work, k: f64) -> Work {
    let up = |n: u64| (n as f64 * k).round() as u64;
    Work {
        paths: up(w.paths),
        volumes: up(w.volumes),
        rays: w.rays,
        hits: up(w.hits),
    }
}

pub(super) fn average(a: &Work, b: &Work) -> Work {
    Work {
        paths: (a.paths + b.paths) / 2,
        volumes: (a.volumes + b.volumes) / 2,
        rays: (a.rays + b.rays) / 2,
        hits: (a.hits + b.hits) / 2,
    }
}

/// Per pixel, the sum over layers and bins of a pass's values (`data` is `[layer][pixel][bin]`).
pub fn pixel_totals(data: &[f32], pixels: usize, n: usize) -> Vec<f64> {
    let mut out = vec![0.0f64; pixels];
    for layer in data.chunks_exact(pixels * n) {
        for (t, px) in out.iter_mut().zip(layer.chunks_exact(n)) {
            *t += px.iter().map(|&v| v as f64).sum::<f64>();
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Each nested estimate counts the work of its own paths and rays: the first paths' and
    /// the first rays' counters where it keeps only those.
    #[test]
    fn each_variant_counts_its_own_work() {
        let n = Nest::four(1, 10, 4.0);
        let c = NestCounts {
            paths: 40,
            sub_paths: 10,
            volumes: 400,
            sub_volumes: 90,
            rays: 40,
            hits: [1000, 260, 240, 70],
        };
        let w: Vec<_> = n
            .variants
            .iter()
            .map(|v| variant_work(&c, &n, *v))
            .collect();
        let four = |w: &Work| (w.paths, w.volumes, w.rays, w.hits);
        assert_eq!(four(&w[0]), (10, 90, 10, 70));
        assert_eq!(four(&w[1]), (10, 90, 40, 240));
        assert_eq!(four(&w[2]), (40, 400, 10, 260));
        assert_eq!(four(&w[3]), (40, 400, 40, 1000));
    }
}
