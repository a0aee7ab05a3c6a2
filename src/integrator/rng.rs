//! Random streams derived from (seed, pass, domain, index), never from thread identity, so a
//! render is bit-identical whatever the thread count.
//!
//! A stream can also hand out the first numbers of each sample (a forward ray, a camera path)
//! from an Owen-scrambled Sobol sequence (Burley 2020, "Practical Hash-based Owen Scrambling",
//! the `sobol_burley` crate): sample `i` of a pass takes point `i` of a sequence scrambled by a
//! hash of (seed, pass, domain, block), its first [`QMC_DIMS`] numbers one dimension each, then
//! the stream's own pseudo-random numbers. The points of one pass fill the unit cube evenly, so
//! the pass's forward rays start from a stratified set of positions and directions and take
//! stratified first flights and scatterings (the low-frequency noise of the photon estimate is
//! what that removes). A pixel's camera paths of a pass are the points of the pixel's own
//! sequence (`camera_pass::trace_row`): stratified pixel positions and first flights. Every
//! point of an Owen-scrambled sequence is uniform in the cube, so each sample is distributed exactly as with independent
//! numbers: the estimators stay unbiased. Passes use independent scrambles, so pass estimates
//! stay independent (the film's noise estimate and the pilots' variances assume that) and the
//! numbers of a pass depend only on (seed, pass, index): pass ranges and merges stay bit-exact.
//! The one planned exception: the automatic settings' pilots outside the film repeat their first
//! pair's passes in every configuration (`Tuner::random_pass`), so that the configurations'
//! variances are compared on the same forward rays.

use rand::{RngCore, SeedableRng};
use rand_pcg::Pcg64Mcg;

/// Numbers of each sample drawn from the Sobol point; the rest are pseudo-random. Covers a
/// forward ray's emission (light choice, position, direction: five) and, in a grey medium, its
/// first free flight and scattering direction; a camera path's pixel position and its first
/// medium segment's numbers.
pub const QMC_DIMS: u32 = 8;

/// `sobol_burley`'s longest sequence: sample indices beyond it start a new, independently
/// scrambled block (each block is stratified on its own).
const BLOCK: u64 = 1 << 16;

/// Which part of a pass a stream serves; keeps camera and light streams independent.
#[derive(Clone, Copy, Debug)]
#[repr(u64)]
pub enum Domain {
    Camera = 1,
    Light = 2,
    Sensor = 3,
}

fn splitmix(mut z: u64) -> u64 {
    z = z.wrapping_add(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// The Sobol point a sample is reading: its index in its block, the block's scramble, and the
/// next dimension.
#[derive(Clone, Copy, Debug)]
struct Point {
    index: u32,
    scramble: u32,
    dim: u32,
}

/// A pseudo-random stream (PCG) that can serve the first numbers of a sample from a scrambled
/// Sobol point (see the module comment). Without [`Rng::begin_sample`] it is the plain stream.
#[derive(Clone, Debug)]
pub struct Rng {
    pcg: Pcg64Mcg,
    point: Option<Point>,
}

impl Rng {
    /// Sample `index` of the pass's sequence `key` (from [`sequence`]) starts: its next
    /// [`QMC_DIMS`] numbers come from its Sobol point.
    pub fn begin_sample(&mut self, key: u64, index: u64) {
        let block = index / BLOCK;
        let scramble = splitmix(key ^ splitmix(block.wrapping_add(0x5EED)));
        self.point = Some(Point {
            index: (index % BLOCK) as u32,
            scramble: scramble as u32,
            dim: 0,
        });
    }

    /// The next Sobol coordinate of the current sample, if it has one left.
    fn qmc(&mut self) -> Option<f32> {
        let p = self.point.as_mut()?;
        if p.dim >= QMC_DIMS {
            self.point = None;
            return None;
        }
        let v = sobol_burley::sample(p.index, p.dim, p.scramble);
        p.dim += 1;
        Some(v)
    }
}

impl RngCore for Rng {
    // A Sobol coordinate has 24 bits (an f32 in [0, 1)); placed in the top bits, `random::<f32>`
    // (the top 24 bits of `next_u32`) returns it exactly, and `random::<f64>` (the top 53 of
    // `next_u64`) returns it with zeros below.
    fn next_u32(&mut self) -> u32 {
        match self.qmc() {
            Some(v) => (v as f64 * 4_294_967_296.0) as u32,
            None => self.pcg.next_u32(),
        }
    }

    fn next_u64(&mut self) -> u64 {
        match self.qmc() {
            Some(v) => (v as f64 * 18_446_744_073_709_551_616.0) as u64,
            None => self.pcg.next_u64(),
        }
    }

    fn fill_bytes(&mut self, dst: &mut [u8]) {
        self.pcg.fill_bytes(dst)
    }
}

/// The key of a pass's sample sequence in one domain (and gather tile): hashes (seed, pass,
/// domain, tile) so that passes, domains and tiles are scrambled independently.
pub fn sequence(seed: u64, pass: u64, domain: Domain, tile: u64) -> u64 {
    let a = splitmix(seed ^ splitmix(pass.wrapping_add(0x9E37)));
    splitmix(a ^ splitmix((domain as u64) << 32 | tile).wrapping_add(0x50B0))
}

pub fn stream(seed: u64, pass: u64, domain: Domain, index: u64) -> Rng {
    let a = splitmix(seed ^ splitmix(pass.wrapping_add(0x1234_5678)));
    let b = splitmix(a ^ splitmix(domain as u64).wrapping_add(index));
    let c = splitmix(b ^ index.rotate_left(29));
    Rng {
        pcg: Pcg64Mcg::seed_from_u64(c ^ (b << 1)),
        point: None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::Rng as _;

    /// Without a sample begun, the stream is the plain PCG stream it always was (so code that
    /// does not use Sobol points keeps its images bit for bit).
    #[test]
    fn plain_stream_is_pcg() {
        let mut a = Rng {
            pcg: Pcg64Mcg::seed_from_u64(5),
            point: None,
        };
        let mut b = Pcg64Mcg::seed_from_u64(5);
        for _ in 0..10 {
            assert_eq!(a.random::<f32>(), b.random::<f32>());
            assert_eq!(a.random::<f64>(), b.random::<f64>());
        }
    }

    /// A sample's first numbers are its Sobol coordinates exactly, then the stream resumes.
    #[test]
    fn sample_reads_its_point_then_the_stream() {
        let key = sequence(7, 3, Domain::Light, 0);
        let mut r = stream(7, 3, Domain::Light, 0);
        let mut plain = stream(7, 3, Domain::Light, 0);
        r.begin_sample(key, 12);
        let scramble = splitmix(key ^ splitmix(0x5EED)) as u32;
        for d in 0..QMC_DIMS {
            let want = sobol_burley::sample(12, d, scramble);
            if d % 2 == 0 {
                assert_eq!(r.random::<f32>(), want);
            } else {
                assert_eq!(r.random::<f64>(), want as f64);
            }
        }
        assert_eq!(r.random::<f32>(), plain.random::<f32>());
    }

    /// Uniformity of the numbers a pass's samples receive, per dimension and jointly in the
    /// first two: chi-square over 64 and 8 x 8 cells of 2^14 samples, from several passes
    /// (scrambles) and across a block boundary. A stratified set is far more even than random
    /// numbers, so the bound (the chi-square's 1e-6 tail, about 130 for 63 degrees of freedom)
    /// is loose; the test catches a wrong mapping (values outside [0, 1), a dimension repeated,
    /// a scramble ignored so every pass gets the same points).
    #[test]
    fn coordinates_are_uniform_and_passes_differ() {
        let n = 1u64 << 14;
        for pass in 0..3 {
            let key = sequence(1, pass, Domain::Camera, 0);
            let mut r = stream(1, pass, Domain::Camera, 0);
            let mut one = [[0u32; 64]; QMC_DIMS as usize];
            let mut two = [0u32; 64];
            for i in (BLOCK - n / 2)..(BLOCK + n / 2) {
                r.begin_sample(key, i);
                let u: Vec<f32> = (0..QMC_DIMS).map(|_| r.random::<f32>()).collect();
                for (d, &v) in u.iter().enumerate() {
                    assert!((0.0..1.0).contains(&v));
                    one[d][(v * 64.0) as usize] += 1;
                }
                two[(u[0] * 8.0) as usize * 8 + (u[1] * 8.0) as usize] += 1;
            }
            let chi = |c: &[u32]| {
                let e = n as f64 / c.len() as f64;
                c.iter().map(|&k| (k as f64 - e).powi(2) / e).sum::<f64>()
            };
            for d in &one {
                assert!(chi(d) < 130.0, "pass {pass}: chi2 {}", chi(d));
            }
            assert!(chi(&two) < 130.0, "pass {pass}: joint chi2 {}", chi(&two));
        }
        let mut a = stream(1, 0, Domain::Light, 0);
        let mut b = stream(1, 1, Domain::Light, 0);
        a.begin_sample(sequence(1, 0, Domain::Light, 0), 0);
        b.begin_sample(sequence(1, 1, Domain::Light, 0), 0);
        assert_ne!(a.random::<f32>(), b.random::<f32>());
    }
}
