//! Patchy fog: fractal sums (fBm) of a gradient noise, sampled on a lattice over the medium's
//! box and then a grid like any other (`grid/`), so its depth along rays stays exact.
//!
//! The noise: at every integer lattice point a pseudo-random gradient, one of the 12 directions
//! to the edges of a cube, chosen by hashing the point and the seed (SplitMix64); inside a
//! lattice cell the value is the blend of the 8 corners' linear ramps `g . (p - corner)` with
//! the quintic fade `6t⁵ - 15t⁴ + 10t³` per axis (Perlin's improved noise, 2002). It is 0 at
//! every lattice point, smooth, and stays within about ±1. Octave `o` is the noise at
//! `2^o x / scale` with amplitude `2^-o`; the sum is divided by the amplitudes' sum, so `fbm`
//! stays in about [-1, 1] whatever the octave count. The density is
//! `clamp(1 + contrast * fbm(x), 0, max)`, times the `times` field where one is given.
//!
//! The field brume renders is the trilinear interpolation of that density sampled at the
//! centres of `voxel`-sized cells over the box (by default 4 samples per wavelength of the
//! finest octave), exactly as if the samples had come from a file.

use glam::{DVec3, Vec3};
use rayon::prelude::*;

use super::Density;
use super::grid::GridData;

/// The noise's parameters, as the scene gives them.
#[derive(Clone, Debug, PartialEq)]
pub struct Noise {
    pub scale: f64,
    pub octaves: u32,
    pub contrast: f64,
    pub seed: u64,
    pub max: f64,
}

/// The 12 gradients: the directions to the midpoints of a cube's edges.
const GRADIENTS: [[f64; 3]; 12] = [
    [1.0, 1.0, 0.0],
    [-1.0, 1.0, 0.0],
    [1.0, -1.0, 0.0],
    [-1.0, -1.0, 0.0],
    [1.0, 0.0, 1.0],
    [-1.0, 0.0, 1.0],
    [1.0, 0.0, -1.0],
    [-1.0, 0.0, -1.0],
    [0.0, 1.0, 1.0],
    [0.0, -1.0, 1.0],
    [0.0, 1.0, -1.0],
    [0.0, -1.0, -1.0],
];

fn splitmix(mut z: u64) -> u64 {
    z = z.wrapping_add(0x9e37_79b9_7f4a_7c15);
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

fn gradient(seed: u64, c: [i64; 3]) -> DVec3 {
    let h = c
        .iter()
        .fold(splitmix(seed), |h, &x| splitmix(h ^ x as u64));
    DVec3::from(GRADIENTS[(h % 12) as usize])
}

fn fade(t: f64) -> f64 {
    t * t * t * (t * (t * 6.0 - 15.0) + 10.0)
}

/// Gradient noise at `p` (0 at lattice points, within about ±1).
pub fn gradient_noise(seed: u64, p: DVec3) -> f64 {
    let base = p.floor();
    let f = p - base;
    let w = [fade(f.x), fade(f.y), fade(f.z)];
    let mut sum = 0.0;
    for c in 0..8 {
        let o = [c & 1, (c >> 1) & 1, (c >> 2) & 1];
        let corner = [
            base.x as i64 + o[0] as i64,
            base.y as i64 + o[1] as i64,
            base.z as i64 + o[2] as i64,
        ];
        let d = f - DVec3::new(o[0] as f64, o[1] as f64, o[2] as f64);
        let weight: f64 = (0..3)
            .map(|a| if o[a] == 1 { w[a] } else { 1.0 - w[a] })
            .product();
        sum += weight * gradient(seed, corner).dot(d);
    }
    sum
}

impl Noise {
    /// The fractal sum at `p`, normalised to about [-1, 1].
    pub fn fbm(&self, p: DVec3) -> f64 {
        let (mut sum, mut norm, mut amp) = (0.0, 0.0, 1.0);
        let mut q = p / self.scale;
        for o in 0..self.octaves {
            // Each octave its own gradients, so octaves do not line up at the origin.
            sum += amp * gradient_noise(self.seed.wrapping_add(o as u64), q);
            norm += amp;
            amp *= 0.5;
            q *= 2.0;
        }
        sum / norm
    }

    /// The density before sampling: `clamp(1 + contrast fbm, 0, max)`.
    pub fn rho(&self, p: DVec3) -> f64 {
        (1.0 + self.contrast * self.fbm(p)).clamp(0.0, self.max)
    }

    /// The default sample spacing: 4 samples per wavelength of the finest octave.
    pub fn default_voxel(&self) -> f64 {
        self.scale / 2f64.powi(self.octaves as i32 - 1) / 4.0
    }

    /// Samples over the box `[lo, hi]` at cells of about `voxel` (times `times` where given).
    /// Err(bytes) when they would take more than `budget` bytes, before anything is allocated.
    pub fn bake(
        &self,
        (lo, hi): (Vec3, Vec3),
        voxel: f64,
        times: Option<&Density>,
        budget: u64,
    ) -> Result<GridData, u64> {
        let size = (hi - lo).as_dvec3();
        let n = |l: f64| ((l / voxel).ceil() as u64).max(2);
        let res = [n(size.x), n(size.y), n(size.z)];
        let bytes = res.iter().try_fold(4u64, |b, &k| b.checked_mul(k));
        match bytes {
            Some(b) if b <= budget => {}
            Some(b) => return Err(b),
            None => return Err(u64::MAX),
        }
        let [nx, ny, nz] = res.map(|k| k as usize);
        let cell = size / DVec3::new(nx as f64, ny as f64, nz as f64);
        let values = (0..nx * ny * nz)
            .into_par_iter()
            .map(|i| {
                let (x, y, z) = (i % nx, (i / nx) % ny, i / (nx * ny));
                let p =
                    lo.as_dvec3() + cell * DVec3::new(x as f64, y as f64, z as f64) + cell * 0.5;
                let t = times.map_or(1.0, |f| f.at(p.as_vec3()) as f64);
                (self.rho(p) * t) as f32
            })
            .collect();
        Ok(GridData {
            res: [nx, ny, nz],
            values,
            bounds: Some((lo, hi)),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn noise(seed: u64) -> Noise {
        Noise {
            scale: 2.0,
            octaves: 4,
            contrast: 0.5,
            seed,
            max: 2.0,
        }
    }

    fn points(n: usize) -> impl Iterator<Item = DVec3> {
        (0..n).map(|i| {
            let h = |k: u64| (splitmix(i as u64 * 3 + k) >> 11) as f64 / (1u64 << 53) as f64;
            DVec3::new(h(0), h(1), h(2)) * 40.0 - 20.0
        })
    }

    #[test]
    fn gradient_noise_vanishes_on_the_lattice_and_stays_within_one() {
        for c in [[0, 0, 0], [3, -2, 7], [-5, 1, -1]] {
            let p = DVec3::new(c[0] as f64, c[1] as f64, c[2] as f64);
            assert_eq!(gradient_noise(9, p), 0.0);
        }
        let max = points(100_000)
            .map(|p| gradient_noise(9, p).abs())
            .fold(0.0, f64::max);
        assert!(max > 0.5 && max < 1.1, "{max}");
    }

    /// Mean about 0 (|mean| < 4 standard errors of independent draws would be too strict for
    /// correlated samples: the bound is 0.02 over 10^5 points spread over 20 wavelengths),
    /// spread well away from 0, and continuous.
    #[test]
    fn fbm_is_centred_continuous_and_seeded() {
        let n = noise(7);
        let v: Vec<f64> = points(100_000).map(|p| n.fbm(p)).collect();
        let mean = v.iter().sum::<f64>() / v.len() as f64;
        let sd = (v.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / v.len() as f64).sqrt();
        assert!(mean.abs() < 0.02 && sd > 0.1 && sd < 0.5, "{mean} {sd}");
        assert!(v.iter().all(|x| x.abs() <= 1.1));
        let p = DVec3::new(0.3, 1.7, -2.2);
        let step = DVec3::splat(1e-6);
        assert!((n.fbm(p + step) - n.fbm(p)).abs() < 1e-4);
        assert_eq!(n.fbm(p), noise(7).fbm(p));
        assert_ne!(n.fbm(p), noise(8).fbm(p));
    }

    #[test]
    fn density_is_clamped_and_baking_respects_the_budget() {
        let mut n = noise(3);
        n.contrast = 4.0;
        n.max = 1.5;
        let rho: Vec<f64> = points(20_000).map(|p| n.rho(p)).collect();
        assert!(rho.iter().all(|r| (0.0..=1.5).contains(r)));
        assert!(rho.contains(&0.0) && rho.contains(&1.5));
        let b = (Vec3::ZERO, Vec3::new(1.0, 2.0, 0.5));
        let g = n.bake(b, 0.1, None, 1 << 20).unwrap();
        assert_eq!(g.res, [10, 20, 5]);
        let centre = DVec3::new(0.05, 0.05, 0.05);
        assert_eq!(g.values[0], n.rho(centre) as f32);
        assert_eq!(n.bake(b, 0.1, None, 3999), Err(4000));
    }
}
