//! Which variant is most efficient, per layer, and how sure that is: the efficiency of each run
//! (1 / (MSE x t)) averaged over runs with its standard error, and the margin to the runner-up
//! in standard errors.

use serde::Serialize;

use super::measure::Checkpoint;

/// What an error (and so an efficiency) is measured on.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Measure {
    /// The whole image.
    Image,
    /// The whole image against the reference scaled by the fitted k (`--fit-scale`).
    ImageScaled,
    /// The film's `medium` layer (the medium's own luminance).
    Medium,
    /// The film's `surface` layer (surfaces seen directly or through the medium).
    Surface,
}

impl Measure {
    pub const ALL: [Measure; 4] = [
        Measure::Image,
        Measure::ImageScaled,
        Measure::Medium,
        Measure::Surface,
    ];

    pub fn name(self) -> &'static str {
        match self {
            Measure::Image => "image",
            Measure::ImageScaled => "image, k x reference",
            Measure::Medium => "medium",
            Measure::Surface => "surface",
        }
    }

    /// The MSE at a checkpoint; None when not measured (no layers, no fit).
    pub fn mse(self, c: &Checkpoint) -> Option<f64> {
        match self {
            Measure::Image => Some(c.total.mse),
            Measure::ImageScaled => c.fit.map(|f| f.mse),
            Measure::Medium => c.medium.map(|e| e.mse),
            Measure::Surface => c.surface.map(|e| e.mse),
        }
    }

    pub fn rmse(self, c: &Checkpoint) -> Option<f64> {
        self.mse(c).map(f64::sqrt)
    }
}

/// A mean over runs and its standard error (None with one run).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Estimate {
    pub mean: f64,
    pub se: Option<f64>,
    pub runs: usize,
}

impl Estimate {
    /// The mean and standard error of `values`; None when empty.
    pub fn of(values: &[f64]) -> Option<Self> {
        if values.is_empty() {
            return None;
        }
        let k = values.len() as f64;
        let mean = values.iter().sum::<f64>() / k;
        let se = (values.len() > 1).then(|| {
            let var = values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (k - 1.0);
            (var / k).sqrt()
        });
        Some(Self {
            mean,
            se,
            runs: values.len(),
        })
    }

    /// "693 ± 21" (or "693" with one run), three significant digits.
    pub fn show(&self) -> String {
        match self.se {
            Some(se) => format!("{} ± {}", sig3(self.mean), sig3(se)),
            None => sig3(self.mean),
        }
    }
}

fn sig3(v: f64) -> String {
    super::ticks::format_sig(v, 3, v != 0.0 && !(1e-3..1e5).contains(&v.abs()))
}

/// The most efficient variant for one measure.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Best {
    pub measure: Measure,
    pub label: String,
    pub efficiency: Estimate,
    /// The second most efficient variant, when there is one.
    pub runner_up: Option<String>,
    pub runner_up_efficiency: Option<Estimate>,
    /// Best over runner-up efficiency.
    pub ratio: Option<f64>,
    /// (best - runner-up) / sqrt(se_best^2 + se_runner_up^2): how many standard errors apart
    /// they are; None with one run per variant.
    pub separation_sigma: Option<f64>,
}

impl Best {
    /// One line for the terminal.
    pub fn describe(&self) -> String {
        let mut s = format!(
            "most efficient ({}): {} at {}",
            self.measure.name(),
            self.label,
            self.efficiency.show()
        );
        if let (Some(r), Some(e)) = (&self.runner_up, &self.runner_up_efficiency) {
            s.push_str(&format!("; next {r} at {}", e.show()));
            if let Some(ratio) = self.ratio {
                s.push_str(&format!(", {ratio:.2}x"));
            }
            match self.separation_sigma {
                Some(z) => s.push_str(&format!(", {z:.1} standard errors apart")),
                None => s.push_str(" (one run each: no error estimate)"),
            }
        }
        s
    }
}

/// For each measure some variant has, the best and the runner-up by mean efficiency over runs.
pub fn rank(variants: &[(String, &std::collections::BTreeMap<Measure, Estimate>)]) -> Vec<Best> {
    let mut out = Vec::new();
    for m in Measure::ALL {
        let mut scored: Vec<(&str, Estimate)> = variants
            .iter()
            .filter_map(|(label, eff)| eff.get(&m).map(|e| (label.as_str(), *e)))
            .filter(|(_, e)| !e.mean.is_nan())
            .collect();
        scored.sort_by(|a, b| b.1.mean.total_cmp(&a.1.mean));
        let Some((label, best)) = scored.first().copied() else {
            continue;
        };
        let second = scored.get(1).copied();
        let sigma = second.and_then(|(_, s)| {
            let (a, b) = (best.se?, s.se?);
            let d = (a * a + b * b).sqrt();
            (d > 0.0).then(|| (best.mean - s.mean) / d)
        });
        out.push(Best {
            measure: m,
            label: label.to_string(),
            efficiency: best,
            runner_up: second.map(|(l, _)| l.to_string()),
            runner_up_efficiency: second.map(|(_, e)| e),
            ratio: second.map(|(_, e)| best.mean / e.mean),
            separation_sigma: sigma,
        });
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::BTreeMap;

    #[test]
    fn estimate_is_mean_and_standard_error() {
        let e = Estimate::of(&[1.0, 2.0, 3.0, 6.0]).expect("values");
        assert_eq!(e.mean, 3.0);
        // Sample variance 14/3, se = sqrt(14/3/4).
        assert!((e.se.expect("se") - (14.0f64 / 12.0).sqrt()).abs() < 1e-12);
        assert_eq!(Estimate::of(&[5.0]).expect("one").se, None);
        assert!(Estimate::of(&[]).is_none());
    }

    #[test]
    fn ranking_names_the_best_per_measure_with_its_margin() {
        let est = |mean, se| Estimate {
            mean,
            se: Some(se),
            runs: 3,
        };
        let a = BTreeMap::from([
            (Measure::Image, est(100.0, 3.0)),
            (Measure::Medium, est(10.0, 1.0)),
        ]);
        let b = BTreeMap::from([
            (Measure::Image, est(80.0, 4.0)),
            (Measure::Medium, est(40.0, 2.0)),
        ]);
        let bests = rank(&[("a".into(), &a), ("b".into(), &b)]);
        assert_eq!(bests.len(), 2);
        assert_eq!(
            (bests[0].measure, bests[0].label.as_str()),
            (Measure::Image, "a")
        );
        assert_eq!(bests[0].runner_up.as_deref(), Some("b"));
        assert!((bests[0].separation_sigma.expect("sigma") - 4.0).abs() < 1e-12);
        assert!((bests[0].ratio.expect("ratio") - 1.25).abs() < 1e-12);
        assert_eq!(
            (bests[1].measure, bests[1].label.as_str()),
            (Measure::Medium, "b")
        );
        assert!(
            bests[0].describe().contains("100 ± 3"),
            "{}",
            bests[0].describe()
        );
    }
}
