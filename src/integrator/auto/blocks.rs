//! The pilots' noise at a coarser scale: the variance of the means of blocks of
//! [`BLOCK`] x [`BLOCK`] points of a pilot's grid (4 x 4 pixels on the pilots' lattice).
//!
//! Why a second scale: the per-pixel variance alone cannot tell the camera paths' noise, which is
//! white (a pixel's own), from the forward rays' (a forward segment deposits along its whole
//! length, so its noise is a line across many pixels: docs/performance.md, "Why it is
//! low-frequency"). Near the per-pixel optimum the per-pixel efficiency is flat in the budgets
//! (fog-cube at 10 s: 2-5 camera paths and 90 000-200 000 forward rays within 1-3 % of error),
//! while the 4x4-binned error moves by up to 18 % across the same choices: the forward rays'
//! share of it is larger. The budgets are therefore chosen for both scales at once
//! (`model::budgets`; docs/performance.md, "The budgets chosen at two scales").

/// Side of a block, in points of the pilot's grid.
pub const BLOCK: usize = 2;

/// The mean of each block of [`BLOCK`] x [`BLOCK`] points of a `w` x `h` grid of per-pixel
/// totals (row-major); the blocks at the right and bottom edges keep the points there are.
pub fn block_means(totals: &[f64], w: usize, h: usize) -> Vec<f64> {
    let (bw, bh) = (w.div_ceil(BLOCK), h.div_ceil(BLOCK));
    let mut sums = vec![0.0f64; bw * bh];
    let mut counts = vec![0u32; bw * bh];
    for (i, t) in totals.iter().enumerate().take(w * h) {
        let (x, y) = (i % w, i / w);
        let b = (y / BLOCK) * bw + x / BLOCK;
        sums[b] += t;
        counts[b] += 1;
    }
    sums.iter()
        .zip(&counts)
        .map(|(s, &c)| if c > 0 { s / c as f64 } else { 0.0 })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn blocks_average_their_points_and_keep_ragged_edges() {
        // A 3 x 3 grid: blocks of 2 x 2, 2 x 1, 1 x 2 and 1 x 1 points.
        let t: Vec<f64> = (1..=9).map(f64::from).collect();
        let m = block_means(&t, 3, 3);
        assert_eq!(m, vec![3.0, 4.5, 7.5, 9.0]);
    }

    /// White noise of variance v per point: the block means' variance is v / 4; a noise shared
    /// by the points of a block (a line through it) keeps its variance. Each sum is over 40 000
    /// blocks: the bounds are about 10 standard errors of each.
    #[test]
    fn block_means_shrink_white_noise_and_keep_shared_noise() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_pcg::Pcg64Mcg::seed_from_u64(3);
        let (w, h) = (400, 400);
        let white: Vec<f64> = (0..w * h)
            .map(|_| rng.random::<f64>() * 12f64.sqrt())
            .collect();
        let mean_sq = |m: &[f64]| {
            let mu = m.iter().sum::<f64>() / m.len() as f64;
            m.iter().map(|x| (x - mu) * (x - mu)).sum::<f64>() / m.len() as f64
        };
        assert!((mean_sq(&white) - 1.0).abs() < 0.02);
        assert!((mean_sq(&block_means(&white, w, h)) - 0.25).abs() < 0.02);
        // One value per column pair (a vertical line through each block).
        let lines: Vec<f64> = (0..w / 2)
            .map(|_| rng.random::<f64>() * 12f64.sqrt())
            .collect();
        let shared: Vec<f64> = (0..w * h).map(|i| lines[(i % w) / 2]).collect();
        let v = mean_sq(&shared);
        assert!((mean_sq(&block_means(&shared, w, h)) / v - 1.0).abs() < 1e-9);
    }
}
