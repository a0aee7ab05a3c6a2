//! RMSE against rendering time, log-log: one colour per variant, one line per run, a point per
//! checkpoint, a dashed 1/sqrt(t) guide (the slope of an unbiased estimator's error) and, on the
//! whole image, the reference's noise floor: the RMSE its own standard error adds to every
//! measurement, under which no variant can be seen to improve.

use plotters::coord::Shift;
use plotters::prelude::*;

use super::{Figure, LogLogAxes, colour, legend, log_log, log_range, text};
use crate::study::best::Measure;
use crate::study::clock::Clock;
use crate::study::run::Row;
use crate::study::summary::seconds_on;
use crate::study::variants::Variant;

/// One variant's runs, each a list of (seconds, RMSE) checkpoints.
struct Series {
    label: String,
    runs: Vec<Vec<(f64, f64)>>,
}

pub(super) struct ErrorVsTime {
    title: String,
    x_desc: String,
    series: Vec<Series>,
    /// The reference's RMSE floor, sqrt(mean squared standard error), when known for `m`.
    floor: Option<f64>,
}

impl ErrorVsTime {
    /// `noise_mse` is the reference's mean squared standard error of the whole image (its
    /// layers and the scaled reference carry none of their own).
    pub fn new(
        variants: &[Variant],
        rows: &[Row],
        m: Measure,
        clock: Clock,
        noise_mse: Option<f64>,
    ) -> Self {
        let series = variants
            .iter()
            .enumerate()
            .map(|(vi, v)| {
                let mut runs: Vec<(u32, Vec<(f64, f64)>)> = Vec::new();
                for r in rows.iter().filter(|r| r.variant == vi) {
                    let (Some(e), t) = (m.rmse(&r.checkpoint), seconds_on(&r.checkpoint, clock))
                    else {
                        continue;
                    };
                    if !(t > 0.0 && e > 0.0 && t.is_finite() && e.is_finite()) {
                        continue;
                    }
                    match runs.iter_mut().find(|(run, _)| *run == r.run) {
                        Some((_, pts)) => pts.push((t, e)),
                        None => runs.push((r.run, vec![(t, e)])),
                    }
                }
                Series {
                    label: v.label.clone(),
                    runs: runs.into_iter().map(|(_, p)| p).collect(),
                }
            })
            .collect();
        Self {
            title: format!("RMSE ({}) vs rendering time", m.name()),
            x_desc: clock.name().to_string(),
            series,
            floor: match m {
                Measure::Image => noise_mse
                    .map(f64::sqrt)
                    .filter(|f| f.is_finite() && *f > 0.0),
                Measure::ImageScaled | Measure::Medium | Measure::Surface => None,
            },
        }
    }

    fn points(&self) -> impl Iterator<Item = &(f64, f64)> {
        self.series.iter().flat_map(|s| s.runs.iter().flatten())
    }

    /// A 1/sqrt(t) line through the first series' last point, across the time axis.
    fn guide(&self, x0: f64, x1: f64) -> Option<Vec<(f64, f64)>> {
        let &(t, e) = self.series.iter().find_map(|s| s.runs.first()?.last())?;
        let at = |x: f64| e * (t / x).sqrt();
        Some(vec![(x0, at(x0)), (x1, at(x1))])
    }
}

impl Figure for ErrorVsTime {
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), String> {
        root.fill(&WHITE).map_err(text)?;
        let (x0, x1) = log_range(self.points().map(|p| p.0));
        let (y0, y1) = log_range(self.points().map(|p| p.1).chain(self.floor));
        let axes = LogLogAxes::new(self.title.clone(), (x0, x1), &self.x_desc, (y0, y1), "RMSE");
        let mut chart = log_log(root, &axes)?;
        if let Some(g) = self.guide(x0, x1) {
            let grey = RGBColor(150, 150, 150);
            chart
                .draw_series(DashedLineSeries::new(g, 8, 6, grey.stroke_width(1)))
                .map_err(text)?
                .label("∝ 1/√t")
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], grey));
        }
        if let Some(f) = self.floor {
            let dark = RGBColor(60, 60, 60);
            chart
                .draw_series(DashedLineSeries::new(
                    vec![(x0, f), (x1, f)],
                    3,
                    4,
                    dark.stroke_width(2),
                ))
                .map_err(text)?
                .label("reference noise floor")
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], dark));
        }
        for (i, s) in self.series.iter().enumerate() {
            let c = colour(i);
            for (ri, pts) in s.runs.iter().enumerate() {
                let line = chart
                    .draw_series(LineSeries::new(pts.clone(), c.stroke_width(2)))
                    .map_err(text)?;
                if ri == 0 {
                    line.label(s.label.clone()).legend(move |(x, y)| {
                        PathElement::new(vec![(x, y), (x + 20, y)], c.stroke_width(3))
                    });
                }
                chart
                    .draw_series(pts.iter().map(|p| Circle::new(*p, 3, c.filled())))
                    .map_err(text)?;
            }
        }
        legend(&mut chart)
    }
}
