//! SVG plots of a study: RMSE versus rendering time (log-log, one colour per variant, one line
//! per run) and efficiency versus q (one line per combination of the other varied keys).

use std::path::Path;

use plotters::prelude::*;

use super::StudyError;
use super::run::Row;
use super::summary::VariantSummary;
use super::variants::Variant;

fn perr(path: &Path, e: impl std::fmt::Display) -> StudyError {
    StudyError::Plot {
        path: path.to_path_buf(),
        message: e.to_string(),
    }
}

fn range(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let (lo, hi) = values
        .filter(|v| v.is_finite() && *v > 0.0)
        .fold((f64::INFINITY, 0.0f64), |(lo, hi), v| {
            (lo.min(v), hi.max(v))
        });
    if lo.is_finite() && hi > lo {
        (lo / 1.2, hi * 1.2)
    } else if lo.is_finite() {
        (lo / 2.0, lo * 2.0)
    } else {
        (1e-3, 1.0)
    }
}

pub fn plot_error_vs_time(
    path: &Path,
    variants: &[Variant],
    rows: &[Row],
) -> Result<(), StudyError> {
    let root = SVGBackend::new(path, (800, 560)).into_drawing_area();
    root.fill(&WHITE).map_err(|e| perr(path, e))?;
    let (t0, t1) = range(rows.iter().map(|r| r.checkpoint.seconds));
    let (e0, e1) = range(rows.iter().map(|r| r.checkpoint.total.rmse));
    let mut chart = ChartBuilder::on(&root)
        .caption("RMSE vs rendering time", ("sans-serif", 20))
        .margin(12)
        .x_label_area_size(40)
        .y_label_area_size(70)
        .build_cartesian_2d((t0..t1).log_scale(), (e0..e1).log_scale())
        .map_err(|e| perr(path, e))?;
    chart
        .configure_mesh()
        .x_desc("seconds")
        .y_desc("RMSE")
        .draw()
        .map_err(|e| perr(path, e))?;
    for (vi, v) in variants.iter().enumerate() {
        let colour = Palette99::pick(vi).to_rgba();
        let runs: u32 = rows
            .iter()
            .filter(|r| r.variant == vi)
            .map(|r| r.run + 1)
            .max()
            .unwrap_or(0);
        for run in 0..runs {
            let pts: Vec<(f64, f64)> = rows
                .iter()
                .filter(|r| r.variant == vi && r.run == run)
                .map(|r| (r.checkpoint.seconds, r.checkpoint.total.rmse))
                .filter(|p| p.0 > 0.0 && p.1 > 0.0)
                .collect();
            let series = chart
                .draw_series(LineSeries::new(pts, colour.stroke_width(2)))
                .map_err(|e| perr(path, e))?;
            if run == 0 {
                series
                    .label(v.label.clone())
                    .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], colour));
            }
        }
    }
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.8))
        .border_style(BLACK)
        .draw()
        .map_err(|e| perr(path, e))?;
    root.present().map_err(|e| perr(path, e))
}

/// Efficiency against the value of `q_key` (log-log); variants without a numeric q value are
/// drawn at the right edge of the chart as single points.
pub fn plot_efficiency(
    path: &Path,
    variants: &[Variant],
    summaries: &[VariantSummary],
    q_key: &str,
) -> Result<(), StudyError> {
    // Group by the values of the other keys; x is q (or 1 when q is not varied).
    let mut groups: Vec<(String, Vec<(f64, f64)>)> = Vec::new();
    for s in summaries {
        let Some(v) = variants.iter().find(|v| v.label == s.label) else {
            continue;
        };
        let q = v
            .values
            .iter()
            .find(|(k, _)| k == q_key)
            .and_then(|(_, val)| val.parse::<f64>().ok())
            .unwrap_or(1.0);
        let rest: Vec<String> = v
            .values
            .iter()
            .filter(|(k, _)| k != q_key)
            .map(|(k, val)| format!("{}={val}", k.rsplit('.').next().unwrap_or(k)))
            .collect();
        let name = if rest.is_empty() {
            "all".to_string()
        } else {
            rest.join(" ")
        };
        match groups.iter_mut().find(|(n, _)| *n == name) {
            Some((_, pts)) => pts.push((q, s.efficiency)),
            None => groups.push((name, vec![(q, s.efficiency)])),
        }
    }
    let root = SVGBackend::new(path, (800, 560)).into_drawing_area();
    root.fill(&WHITE).map_err(|e| perr(path, e))?;
    let (q0, q1) = range(groups.iter().flat_map(|(_, p)| p.iter().map(|p| p.0)));
    let (e0, e1) = range(groups.iter().flat_map(|(_, p)| p.iter().map(|p| p.1)));
    let mut chart = ChartBuilder::on(&root)
        .caption("Efficiency 1/(MSE * time) vs q", ("sans-serif", 20))
        .margin(12)
        .x_label_area_size(40)
        .y_label_area_size(70)
        .build_cartesian_2d((q0..q1).log_scale(), (e0..e1).log_scale())
        .map_err(|e| perr(path, e))?;
    chart
        .configure_mesh()
        .x_desc(q_key)
        .y_desc("1 / (MSE * s)")
        .draw()
        .map_err(|e| perr(path, e))?;
    for (gi, (name, mut pts)) in groups.into_iter().enumerate() {
        pts.retain(|p| p.1.is_finite() && p.1 > 0.0);
        pts.sort_by(|a, b| a.0.total_cmp(&b.0));
        let colour = Palette99::pick(gi).to_rgba();
        chart
            .draw_series(LineSeries::new(pts.clone(), colour.stroke_width(2)))
            .map_err(|e| perr(path, e))?
            .label(name)
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], colour));
        chart
            .draw_series(pts.into_iter().map(|p| Circle::new(p, 4, colour.filled())))
            .map_err(|e| perr(path, e))?;
    }
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.8))
        .border_style(BLACK)
        .draw()
        .map_err(|e| perr(path, e))?;
    root.present().map_err(|e| perr(path, e))
}
