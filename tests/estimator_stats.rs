//! Shared statistics for the Monte-Carlo tests of `medium` and `integrator::volume` (included by
//! the other test files with `#[path]`; compiled on its own it only runs its self-check).
#![allow(dead_code)]

/// Per-bin running mean and variance of i.i.d. samples (f64 to keep millions of samples exact).
#[derive(Clone, Debug)]
pub struct Acc {
    pub count: u64,
    sum: Vec<f64>,
    sum2: Vec<f64>,
}

impl Acc {
    pub fn new(bins: usize) -> Self {
        Self {
            count: 0,
            sum: vec![0.0; bins],
            sum2: vec![0.0; bins],
        }
    }

    pub fn add(&mut self, x: &[f64]) {
        self.count += 1;
        for (i, &v) in x.iter().enumerate() {
            self.sum[i] += v;
            self.sum2[i] += v * v;
        }
    }

    pub fn add_f32(&mut self, x: &[f32]) {
        let v: Vec<f64> = x.iter().map(|&a| a as f64).collect();
        self.add(&v);
    }

    pub fn mean(&self, i: usize) -> f64 {
        self.sum[i] / self.count as f64
    }

    /// Standard error of the mean.
    pub fn se(&self, i: usize) -> f64 {
        let n = self.count as f64;
        let m = self.mean(i);
        ((self.sum2[i] / n - m * m).max(0.0) / (n - 1.0)).sqrt()
    }

    /// z-score of bin i's mean against an exact value.
    pub fn z(&self, i: usize, exact: f64) -> f64 {
        z_of(self.mean(i), self.se(i), exact)
    }
}

/// z-score that treats a zero standard error as exact agreement only if the values agree.
pub fn z_of(mean: f64, se: f64, exact: f64) -> f64 {
    if se > 0.0 {
        (mean - exact) / se
    } else if (mean - exact).abs() <= 1e-12 * exact.abs().max(1.0) {
        0.0
    } else {
        f64::INFINITY
    }
}

/// Composite Simpson integral of `f` over [a, b] with `n` (even) intervals.
pub fn simpson(a: f64, b: f64, n: usize, f: impl Fn(f64) -> f64) -> f64 {
    let n = n + n % 2;
    let h = (b - a) / n as f64;
    let mut s = f(a) + f(b);
    for k in 1..n {
        s += f(a + k as f64 * h) * if k % 2 == 1 { 4.0 } else { 2.0 };
    }
    s * h / 3.0
}

#[test]
fn acc_self_check() {
    let mut a = Acc::new(1);
    for x in [1.0, 2.0, 3.0, 4.0] {
        a.add(&[x]);
    }
    assert!((a.mean(0) - 2.5).abs() < 1e-12);
    // sample variance 5/3, se = sqrt(5/3/4)
    assert!((a.se(0) - (5.0f64 / 12.0).sqrt()).abs() < 1e-12);
    assert!((simpson(0.0, 1.0, 10, |x| x * x) - 1.0 / 3.0).abs() < 1e-12);
}
