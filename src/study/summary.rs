//! The study's JSON summary: per variant, the errors at the end of each run averaged over runs,
//! and the efficiency 1 / (MSE * time).

use serde::Serialize;

use super::metrics::efficiency;
use super::run::{Row, StudyConfig};
use super::variants::Variant;

#[derive(Clone, Debug, Serialize)]
pub struct VariantSummary {
    pub label: String,
    pub sets: Vec<String>,
    pub runs: usize,
    pub mean_passes: f64,
    pub mean_seconds: f64,
    pub mse: f64,
    /// Standard error of `mse` over runs (0 with one run).
    pub mse_se: f64,
    pub rmse: f64,
    pub rel_mse: f64,
    pub medium_mse: f64,
    pub surface_mse: f64,
    pub medium_rel_mse: f64,
    pub surface_rel_mse: f64,
    pub noise: f64,
    /// Mean signed error (image minus reference) at the end of the runs.
    pub mean_error: f64,
    pub efficiency: f64,
    pub medium_efficiency: f64,
    pub surface_efficiency: f64,
    /// Efficiency with the reference's own noise (its mean squared standard error) taken out
    /// of the MSE; null when the MSE is not above that floor.
    pub efficiency_corrected: Option<f64>,
    /// Efficiency relative to the study's first variant.
    pub gain_vs_first: f64,
}

#[derive(Clone, Debug, Serialize)]
pub struct Summary {
    pub scene: String,
    pub sets: Vec<String>,
    pub seconds_per_run: f64,
    pub runs: u32,
    pub reference: String,
    pub reference_passes: u64,
    pub reference_seconds: f64,
    pub reference_noise_mse: f64,
    pub variants: Vec<VariantSummary>,
    pub invalid: Vec<(String, String)>,
    /// Label of the most efficient variant (total MSE).
    pub best: String,
}

/// Per variant, averages of the last checkpoint of each run.
pub fn summarise_variants(
    variants: &[Variant],
    rows: &[Row],
    reference_noise_mse: f64,
) -> Vec<VariantSummary> {
    let mut out: Vec<VariantSummary> = Vec::new();
    for (vi, v) in variants.iter().enumerate() {
        let mut finals: Vec<&Row> = Vec::new();
        for r in rows.iter().filter(|r| r.variant == vi) {
            match finals.iter_mut().find(|f| f.run == r.run) {
                Some(f) if r.checkpoint.passes > f.checkpoint.passes => *f = r,
                Some(_) => {}
                None => finals.push(r),
            }
        }
        if finals.is_empty() {
            continue;
        }
        let k = finals.len() as f64;
        let mean = |f: &dyn Fn(&Row) -> f64| finals.iter().map(|r| f(r)).sum::<f64>() / k;
        let mse = mean(&|r| r.checkpoint.total.mse);
        let mse_se = if finals.len() > 1 {
            let var = finals
                .iter()
                .map(|r| (r.checkpoint.total.mse - mse).powi(2))
                .sum::<f64>()
                / (k - 1.0);
            (var / k).sqrt()
        } else {
            0.0
        };
        let seconds = mean(&|r| r.checkpoint.seconds);
        let medium_mse = mean(&|r| r.checkpoint.medium.mse);
        let surface_mse = mean(&|r| r.checkpoint.surface.mse);
        let corrected = mse - reference_noise_mse;
        out.push(VariantSummary {
            label: v.label.clone(),
            sets: v.sets.clone(),
            runs: finals.len(),
            mean_passes: mean(&|r| r.checkpoint.passes as f64),
            mean_seconds: seconds,
            mse,
            mse_se,
            rmse: mse.sqrt(),
            rel_mse: mean(&|r| r.checkpoint.total.rel_mse),
            medium_mse,
            surface_mse,
            medium_rel_mse: mean(&|r| r.checkpoint.medium.rel_mse),
            surface_rel_mse: mean(&|r| r.checkpoint.surface.rel_mse),
            noise: mean(&|r| r.checkpoint.noise),
            mean_error: mean(&|r| r.checkpoint.mean_error),
            efficiency: efficiency(mse, seconds),
            medium_efficiency: efficiency(medium_mse, seconds),
            surface_efficiency: efficiency(surface_mse, seconds),
            efficiency_corrected: (corrected > 0.0).then(|| efficiency(corrected, seconds)),
            gain_vs_first: 1.0,
        });
    }
    if let Some(first) = out.first().map(|s| s.efficiency) {
        for s in &mut out {
            s.gain_vs_first = s.efficiency / first;
        }
    }
    out
}

pub fn summarise(
    cfg: &StudyConfig,
    reference: &str,
    reference_meta: (u64, f64, f64),
    rows: &[Row],
    invalid: &[(usize, String)],
) -> Summary {
    let variants = summarise_variants(&cfg.variants, rows, reference_meta.2);
    let best = variants
        .iter()
        .max_by(|a, b| a.efficiency.total_cmp(&b.efficiency))
        .map(|s| s.label.clone())
        .unwrap_or_default();
    Summary {
        scene: cfg.scene.display().to_string(),
        sets: cfg.sets.clone(),
        seconds_per_run: cfg.seconds,
        runs: cfg.runs,
        reference: reference.to_string(),
        reference_passes: reference_meta.0,
        reference_seconds: reference_meta.1,
        reference_noise_mse: reference_meta.2,
        variants,
        invalid: invalid
            .iter()
            .map(|(i, m)| {
                (
                    cfg.variants
                        .get(*i)
                        .map(|v| v.label.clone())
                        .unwrap_or_default(),
                    m.clone(),
                )
            })
            .collect(),
        best,
    }
}
