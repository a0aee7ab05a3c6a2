//! Axis ticks for the study's plots: where they go (at least two on every axis, log axes
//! included) and how they read (the fewest significant digits that tell them apart and say
//! them truly, so `0.1 + 0.2` reads `0.3`, never `0.30000000000000004`).

/// Ticks of an axis: positions and their labels.
#[derive(Clone, Debug, PartialEq)]
pub struct Ticks {
    pub values: Vec<f64>,
    pub labels: Vec<String>,
}

impl Ticks {
    pub fn new(values: Vec<f64>) -> Self {
        let labels = labels(&values);
        Self { values, labels }
    }

    /// The label of the tick nearest `v` (plotters asks for labels by value).
    pub fn label(&self, v: f64) -> String {
        self.values
            .iter()
            .zip(&self.labels)
            .min_by(|a, b| (a.0 - v).abs().total_cmp(&(b.0 - v).abs()))
            .map(|(_, l)| l.clone())
            .unwrap_or_default()
    }
}

/// `value` with `digits` significant digits, trailing zeros dropped; in scientific notation
/// (`2.5e-5`) when `scientific`.
pub fn format_sig(value: f64, digits: usize, scientific: bool) -> String {
    if value == 0.0 || !value.is_finite() {
        return format!("{value}");
    }
    let digits = digits.clamp(1, 17);
    // Rounding first fixes the exponent (9.96 at 2 digits is 10, exponent 1).
    let sci = format!("{:.*e}", digits - 1, value);
    let (mantissa, exp) = sci.split_once('e').unwrap_or((&sci, "0"));
    let exp: i32 = exp.parse().unwrap_or(0);
    if scientific {
        return format!("{}e{exp}", trim(mantissa));
    }
    let decimals = (digits as i32 - 1 - exp).max(0) as usize;
    trim(&format!("{:.*}", decimals, value))
}

/// Drops trailing zeros after a decimal point, and the point itself.
fn trim(s: &str) -> String {
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s.to_string()
    }
}

/// Labels for tick values: the fewest significant digits that keep distinct values distinct
/// and say each value truly (to 1e-9 of the largest: `0.30000000000000004` reads `0.3`, but
/// `0.25` is not cut to `0.2`), all in scientific notation when any value is below 0.001 or at
/// least 100 000 in magnitude.
pub fn labels(values: &[f64]) -> Vec<String> {
    let finite = || values.iter().filter(|v| v.is_finite());
    let scientific = finite().any(|v| *v != 0.0 && !(1e-3..1e5).contains(&v.abs()));
    let scale = finite().fold(0.0f64, |m, v| m.max(v.abs()));
    let distinct_values = {
        let mut v: Vec<f64> = values.to_vec();
        v.sort_by(f64::total_cmp);
        v.dedup();
        v.len()
    };
    for digits in 1..=17 {
        let out: Vec<String> = values
            .iter()
            .map(|v| format_sig(*v, digits, scientific))
            .collect();
        let true_to_value = out.iter().zip(values).all(|(l, v)| {
            !v.is_finite()
                || l.parse::<f64>()
                    .is_ok_and(|p| (p - v).abs() <= 1e-9 * scale)
        });
        let mut seen = out.clone();
        seen.sort();
        seen.dedup();
        if true_to_value && seen.len() == distinct_values {
            return out;
        }
    }
    values.iter().map(|v| format!("{v}")).collect()
}

/// The decimal number `m` x 10^`e` as the nearest f64 (so 3 x 10^-1 is 0.3 exactly as typed).
fn decimal(m: u32, e: i32) -> f64 {
    format!("{m}e{e}").parse().unwrap_or(f64::NAN)
}

/// Ticks for a logarithmic axis over [lo, hi] (0 < lo < hi). Candidates: powers of ten
/// (every n-th decade when there are many), 1-2-5 per decade and 1 to 9 per decade (when they
/// make at most 10 ticks), and evenly spaced round numbers; the one with 3 to 10 ticks (else 2 or more) that spans the most of
/// the axis wins, the coarsest on a tie.
pub fn log_ticks(lo: f64, hi: f64) -> Vec<f64> {
    if !(lo > 0.0 && hi > lo && hi.is_finite()) {
        return linear_ticks(lo, hi, 5);
    }
    let (e0, e1) = (lo.log10().floor() as i32, hi.log10().ceil() as i32);
    let per_decade = [&[1u32][..], &[1, 2, 5], &[1, 2, 3, 4, 5, 6, 7, 8, 9]];
    let mut candidates: Vec<Vec<f64>> = per_decade
        .iter()
        .map(|mantissas| {
            let ticks: Vec<f64> = (e0..=e1)
                .flat_map(|e| mantissas.iter().map(move |&m| decimal(m, e)))
                .filter(|v| *v >= lo && *v <= hi)
                .collect();
            // Many decades: every n-th. The finer sets are only candidates when short.
            match mantissas.len() {
                1 => ticks
                    .iter()
                    .copied()
                    .step_by(ticks.len().div_ceil(10).max(1))
                    .collect(),
                _ if ticks.len() <= 10 => ticks,
                _ => Vec::new(),
            }
        })
        .collect();
    candidates.push(
        linear_ticks(lo, hi, 5)
            .into_iter()
            .filter(|v| *v > 0.0)
            .collect(),
    );
    // The fraction of the axis (in log) between the first and last tick.
    let span = |t: &Vec<f64>| match (t.first(), t.last()) {
        (Some(a), Some(b)) => (b / a).ln() / (hi / lo).ln(),
        _ => 0.0,
    };
    let widest = |min: usize| {
        candidates
            .iter()
            .filter(|t| t.len() >= min)
            .fold(None::<&Vec<f64>>, |best, t| match best {
                Some(b) if span(b) >= span(t) - 1e-9 => Some(b),
                _ => Some(t),
            })
            .cloned()
    };
    widest(3)
        .or_else(|| widest(2))
        .unwrap_or_else(|| vec![lo, hi])
}

/// Minor grid lines of a log axis: 1 to 9 per decade inside [lo, hi].
pub fn log_minor(lo: f64, hi: f64) -> Vec<f64> {
    if !(lo > 0.0 && hi > lo && hi.is_finite()) {
        return Vec::new();
    }
    let (e0, e1) = (lo.log10().floor() as i32, hi.log10().ceil() as i32);
    if e1 - e0 > 12 {
        return Vec::new();
    }
    (e0..=e1)
        .flat_map(|e| (1..10).map(move |m| decimal(m, e)))
        .filter(|v| *v >= lo && *v <= hi)
        .collect()
}

/// About `target` evenly spaced ticks inside [lo, hi] at 1, 2 or 5 x 10^k steps (at least two).
pub fn linear_ticks(lo: f64, hi: f64, target: usize) -> Vec<f64> {
    if !(lo.is_finite() && hi.is_finite()) || hi <= lo {
        return vec![lo, hi];
    }
    let raw = (hi - lo) / target.max(1) as f64;
    let e = raw.log10().floor() as i32;
    // Candidate steps 1, 2, 5 x 10^k, ascending.
    let steps: Vec<f64> = (e - 3..=e + 1)
        .flat_map(|k| [1, 2, 5].map(|m| decimal(m, k)))
        .collect();
    let ticks = |step: f64| -> Vec<f64> {
        let (first, last) = ((lo / step).ceil() as i64, (hi / step).floor() as i64);
        (first..=last)
            .map(|k| {
                // k x step as the decimal it stands for (0.6, not 0.6000000000000001).
                let v = k as f64 * step;
                format!("{v:.14e}").parse().unwrap_or(v)
            })
            .filter(|v| *v >= lo && *v <= hi)
            .collect()
    };
    // The finest step not finer than asked, else the coarsest finer one, with two ticks.
    let coarse = steps.iter().filter(|s| **s >= raw);
    let fine = steps.iter().rev().filter(|s| **s < raw);
    coarse
        .chain(fine)
        .map(|s| ticks(*s))
        .find(|t| t.len() >= 2)
        .unwrap_or_else(|| vec![lo, hi])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn labels_use_the_fewest_digits_that_distinguish() {
        assert_eq!(labels(&[0.1, 0.2, 0.1 + 0.2]), ["0.1", "0.2", "0.3"]);
        assert_eq!(labels(&[1.0, 1.5, 2.0]), ["1", "1.5", "2"]);
        assert_eq!(labels(&[1.0001, 1.0002]), ["1.0001", "1.0002"]);
        assert_eq!(
            labels(&[20.0, 50.0, 100.0, 200.0]),
            ["20", "50", "100", "200"]
        );
        assert_eq!(labels(&[0.25, 0.5, 0.75]), ["0.25", "0.5", "0.75"]);
        // Small or large values: scientific for the whole axis.
        assert_eq!(labels(&[1e-5, 1e-4, 1e-3]), ["1e-5", "1e-4", "1e-3"]);
        assert_eq!(labels(&[2.5e-5, 5e-5]), ["2.5e-5", "5e-5"]);
        assert_eq!(labels(&[1e5, 2e5]), ["1e5", "2e5"]);
        assert_eq!(labels(&[0.0, 0.5, 1.0]), ["0", "0.5", "1"]);
        // Rounding up carries into the exponent.
        assert_eq!(format_sig(9.96, 2, false), "10");
        assert_eq!(format_sig(-0.30000000000000004, 3, false), "-0.3");
        assert_eq!(format_sig(693.2, 3, false), "693");
    }

    #[test]
    fn every_log_axis_gets_at_least_two_ticks_inside() {
        for (lo, hi) in [
            (1e-5, 1e-2),
            (17.0, 693.0),
            (1.1, 1.9),
            (1.1, 1.3),
            (0.9, 1.1),
            (3e-7, 4e-7),
            (1e-30, 1e30),
        ] {
            let t = log_ticks(lo, hi);
            assert!(t.len() >= 2, "{lo}..{hi}: {t:?}");
            assert!(t.len() <= 12, "{lo}..{hi}: {t:?}");
            assert!(t.iter().all(|v| *v >= lo && *v <= hi), "{lo}..{hi}: {t:?}");
            let l = labels(&t);
            let mut d = l.clone();
            d.dedup();
            assert_eq!(d.len(), l.len(), "{l:?}");
        }
        assert_eq!(log_ticks(1e-5, 1e-2), [1e-5, 1e-4, 1e-3, 1e-2]);
        assert_eq!(log_ticks(17.0, 693.0), [20.0, 50.0, 100.0, 200.0, 500.0]);
        assert_eq!(log_ticks(0.085, 1.27), [0.1, 0.2, 0.5, 1.0]);
        assert_eq!(
            log_ticks(0.0055, 0.03),
            [0.006, 0.007, 0.008, 0.009, 0.01, 0.02, 0.03]
        );
        assert_eq!(
            log_ticks(8700.0, 17000.0),
            [10000.0, 12000.0, 14000.0, 16000.0]
        );
        // 1 to 9 per decade would leave the top of this axis bare.
        assert_eq!(log_ticks(3400.0, 19000.0), [5000.0, 10000.0, 15000.0]);
        assert_eq!(
            labels(&log_ticks(0.25, 0.35)),
            ["0.26", "0.28", "0.3", "0.32", "0.34"]
        );
    }

    #[test]
    fn linear_ticks_are_round_and_inside() {
        assert_eq!(linear_ticks(0.0, 1.0, 5), [0.0, 0.2, 0.4, 0.6, 0.8, 1.0]);
        assert_eq!(
            labels(&linear_ticks(0.0, 1.0, 5)),
            ["0", "0.2", "0.4", "0.6", "0.8", "1"]
        );
        let t = linear_ticks(0.12, 0.31, 4);
        assert!(
            t.len() >= 2 && t.iter().all(|v| (0.12..=0.31).contains(v)),
            "{t:?}"
        );
        assert!(labels(&t).iter().all(|l| l.len() <= 4), "{:?}", labels(&t));
    }
}
