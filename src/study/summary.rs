//! The study's JSON summary: per variant, the errors at the end of each run averaged over runs,
//! the efficiency 1 / (MSE x t) on the study's clock, and per layer the most efficient variant.

use std::collections::BTreeMap;

use serde::Serialize;

use super::best::{Best, Estimate, Measure, rank};
use super::clock::{Budget, Clock, Elapsed};
use super::measure::Checkpoint;
use super::metrics::efficiency;
use super::reference::Reference;
use super::run::{Row, StudyConfig};
use super::variants::Variant;

#[derive(Clone, Debug, Serialize)]
pub struct VariantSummary {
    pub label: String,
    pub sets: Vec<String>,
    pub runs: usize,
    pub mean_passes: f64,
    /// Wall-clock seconds of rendering, mean over runs.
    pub mean_seconds: f64,
    /// Process CPU seconds of rendering, mean over runs.
    pub mean_cpu_seconds: f64,
    /// The longest run's seconds on the study's clock.
    pub max_seconds: f64,
    /// Whether a run went over the budget ([`Budget::overrun`]): its first pass alone is longer
    /// than the budget, so this variant is not at equal time.
    pub over_budget: bool,
    pub mse: f64,
    /// Standard error of `mse` over runs (0 with one run).
    pub mse_se: f64,
    pub rmse: f64,
    pub rel_mse: f64,
    /// Layer errors: null when the reference has no layers.
    pub medium_mse: Option<f64>,
    pub surface_mse: Option<f64>,
    pub medium_rel_mse: Option<f64>,
    pub surface_rel_mse: Option<f64>,
    pub noise: f64,
    /// Mean signed error (image minus reference) at the end of the runs.
    pub mean_error: f64,
    /// 1 / (mean MSE x mean seconds), seconds on the study's clock.
    pub efficiency: f64,
    pub medium_efficiency: Option<f64>,
    pub surface_efficiency: Option<f64>,
    /// Efficiency with the reference's own noise (its mean squared standard error) taken out
    /// of the MSE; null when the MSE is not above that floor or the floor is unknown.
    pub efficiency_corrected: Option<f64>,
    /// Efficiency relative to the study's first variant.
    pub gain_vs_first: f64,
    /// The fitted scale of the reference (k x reference ~ image), mean over runs
    /// (`--fit-scale`).
    pub k: Option<Estimate>,
    /// MSE against k x reference, mean over runs (`--fit-scale`).
    pub mse_scaled: Option<f64>,
    /// Per measure: each run's efficiency 1 / (MSE x t), mean and standard error over runs.
    pub efficiency_over_runs: BTreeMap<Measure, Estimate>,
}

#[derive(Clone, Debug, Serialize)]
pub struct Summary {
    pub scene: String,
    pub sets: Vec<String>,
    pub budget: Budget,
    /// The clock efficiencies use: `cpu` when a CPU budget was given, else `wall`.
    pub clock: Clock,
    pub runs: u32,
    pub reference: String,
    /// What the errors are measured on (spectral bins or working-space RGB).
    pub reference_values: String,
    /// Whether the reference has the medium / surface split (per-layer errors need it).
    pub reference_has_layers: bool,
    pub reference_passes: u64,
    pub reference_seconds: f64,
    /// Mean squared standard error of the reference; null when it has none.
    pub reference_noise_mse: Option<f64>,
    pub fit_scale: bool,
    pub variants: Vec<VariantSummary>,
    pub invalid: Vec<(String, String)>,
    /// Label of the most efficient variant on the whole image.
    pub best: String,
    /// Per measure (image, image against k x reference, medium, surface) the most efficient
    /// variant, by the mean over runs of each run's efficiency.
    pub best_per_layer: Vec<Best>,
    /// How the reference was read, and what could not be measured.
    pub notes: Vec<String>,
}

/// The last checkpoint of each run of variant `vi` (rows are in the order they were measured;
/// a run stopped inside a pass ends with a row of the same passes at the whole time spent).
fn finals(rows: &[Row], vi: usize) -> Vec<&Checkpoint> {
    let mut out: Vec<(u32, &Checkpoint)> = Vec::new();
    for r in rows.iter().filter(|r| r.variant == vi) {
        match out.iter_mut().find(|(run, _)| *run == r.run) {
            Some(f) => f.1 = &r.checkpoint,
            None => out.push((r.run, &r.checkpoint)),
        }
    }
    out.into_iter().map(|(_, c)| c).collect()
}

/// The budget on `clock` (NaN when that clock has none).
fn budget_on(b: Budget, clock: Clock) -> f64 {
    match clock {
        Clock::Wall => b.wall,
        Clock::Cpu => b.cpu,
    }
    .unwrap_or(f64::NAN)
}

/// Seconds of a checkpoint on `clock`.
pub fn seconds_on(c: &Checkpoint, clock: Clock) -> f64 {
    match clock {
        Clock::Wall => c.seconds,
        Clock::Cpu => c.cpu_seconds,
    }
}

/// Per variant, averages of the last checkpoint of each run.
pub fn summarise_variants(
    variants: &[Variant],
    rows: &[Row],
    reference_noise_mse: Option<f64>,
    budget: Budget,
) -> Vec<VariantSummary> {
    let clock = budget.clock();
    let mut out: Vec<VariantSummary> = Vec::new();
    for (vi, v) in variants.iter().enumerate() {
        let finals = finals(rows, vi);
        if finals.is_empty() {
            continue;
        }
        let mut one = summarise_one(v, &finals, reference_noise_mse, clock);
        one.over_budget = finals.iter().any(|c| {
            budget.overrun(Elapsed {
                wall: c.seconds,
                cpu: c.cpu_seconds,
            })
        });
        out.push(one);
    }
    if let Some(first) = out.first().map(|s| s.efficiency) {
        for s in &mut out {
            s.gain_vs_first = s.efficiency / first;
        }
    }
    out
}

fn summarise_one(
    v: &Variant,
    finals: &[&Checkpoint],
    reference_noise_mse: Option<f64>,
    clock: Clock,
) -> VariantSummary {
    let k = finals.len() as f64;
    let mean = |f: &dyn Fn(&Checkpoint) -> f64| finals.iter().map(|c| f(c)).sum::<f64>() / k;
    // Mean over runs of a value only some checkpoints have: None unless all have it.
    let mean_opt = |f: &dyn Fn(&Checkpoint) -> Option<f64>| {
        let v: Option<Vec<f64>> = finals.iter().map(|c| f(c)).collect();
        v.map(|v| v.iter().sum::<f64>() / k)
    };
    let mse = mean(&|c| c.total.mse);
    let mse_se = Estimate::of(&finals.iter().map(|c| c.total.mse).collect::<Vec<_>>())
        .and_then(|e| e.se)
        .unwrap_or(0.0);
    let t = mean(&|c| seconds_on(c, clock));
    let medium_mse = mean_opt(&|c| c.medium.map(|e| e.mse));
    let surface_mse = mean_opt(&|c| c.surface.map(|e| e.mse));
    let corrected = reference_noise_mse.map(|n| mse - n).filter(|c| *c > 0.0);
    let mut over_runs = BTreeMap::new();
    for m in Measure::ALL {
        let per_run: Option<Vec<f64>> = finals
            .iter()
            .map(|c| m.mse(c).map(|e| efficiency(e, seconds_on(c, clock))))
            .collect();
        if let Some(e) = per_run.as_deref().and_then(Estimate::of) {
            over_runs.insert(m, e);
        }
    }
    let ks: Option<Vec<f64>> = finals.iter().map(|c| c.fit.map(|f| f.k)).collect();
    VariantSummary {
        label: v.label.clone(),
        sets: v.sets.clone(),
        runs: finals.len(),
        mean_passes: mean(&|c| c.passes as f64),
        mean_seconds: mean(&|c| c.seconds),
        mean_cpu_seconds: mean(&|c| c.cpu_seconds),
        max_seconds: finals
            .iter()
            .map(|c| seconds_on(c, clock))
            .fold(0.0, f64::max),
        over_budget: false,
        mse,
        mse_se,
        rmse: mse.sqrt(),
        rel_mse: mean(&|c| c.total.rel_mse),
        medium_mse,
        surface_mse,
        medium_rel_mse: mean_opt(&|c| c.medium.map(|e| e.rel_mse)),
        surface_rel_mse: mean_opt(&|c| c.surface.map(|e| e.rel_mse)),
        noise: mean(&|c| c.noise),
        mean_error: mean(&|c| c.mean_error),
        efficiency: efficiency(mse, t),
        medium_efficiency: medium_mse.map(|m| efficiency(m, t)),
        surface_efficiency: surface_mse.map(|m| efficiency(m, t)),
        efficiency_corrected: corrected.map(|c| efficiency(c, t)),
        gain_vs_first: 1.0,
        k: ks.as_deref().and_then(Estimate::of),
        mse_scaled: mean_opt(&|c| c.fit.map(|f| f.mse)),
        efficiency_over_runs: over_runs,
    }
}

/// The summary of a study: `reference_name` says where the reference came from.
pub fn summarise(
    cfg: &StudyConfig,
    reference: &Reference,
    reference_name: &str,
    rows: &[Row],
    invalid: &[(usize, String)],
) -> Summary {
    let clock = cfg.budget.clock();
    let noise = reference.noise_mse();
    let variants = summarise_variants(&cfg.variants, rows, noise, cfg.budget);
    let labelled: Vec<(String, &BTreeMap<Measure, Estimate>)> = variants
        .iter()
        .map(|v| (v.label.clone(), &v.efficiency_over_runs))
        .collect();
    let best_per_layer = rank(&labelled);
    let best = best_per_layer
        .iter()
        .find(|b| b.measure == Measure::Image)
        .map(|b| b.label.clone())
        .unwrap_or_default();
    let mut notes = reference.notes.clone();
    if reference.layers.is_none() {
        notes.push(
            "the reference has no medium / surface layers (only brume's references do): \
             per-layer errors are not measured"
                .into(),
        );
    }
    for v in variants.iter().filter(|v| v.over_budget) {
        notes.push(format!(
            "{} is NOT at equal time: a run took {:.2} {}, over the {:.2} s budget (its first \
             pass alone is longer; a run needs one whole pass); raise --time or make its \
             passes cheaper before comparing it",
            v.label,
            v.max_seconds,
            clock.name(),
            budget_on(cfg.budget, clock),
        ));
    }
    if noise.is_none() {
        notes.push("the reference carries no standard error: its noise floor is unknown".into());
    }
    Summary {
        scene: cfg.scene.display().to_string(),
        sets: cfg.sets.clone(),
        budget: cfg.budget,
        clock,
        runs: cfg.runs,
        reference: reference_name.to_string(),
        reference_values: reference.values.describe(),
        reference_has_layers: reference.layers.is_some(),
        reference_passes: reference.passes,
        reference_seconds: reference.seconds,
        reference_noise_mse: noise,
        fit_scale: cfg.fit_scale,
        variants,
        invalid: invalid
            .iter()
            .map(|(i, m)| {
                let label = cfg.variants.get(*i).map(|v| v.label.clone());
                (label.unwrap_or_default(), m.clone())
            })
            .collect(),
        best,
        best_per_layer,
        notes,
    }
}
