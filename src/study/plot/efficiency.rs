//! Efficiency plots: per variant (a dot per variant with its standard-error bar, log scale) and
//! against q (log-log, one line per combination of the other varied keys; variants whose q is
//! not a number, such as `auto`, as dashed horizontal lines).

use plotters::coord::Shift;
use plotters::coord::combinators::BindKeyPoints;
use plotters::prelude::*;

use super::{FONT, Figure, LogLog, LogLogAxes, colour, legend, log_axis, log_log, log_range, text};
use crate::study::best::{Estimate, Measure};
use crate::study::clock::Clock;
use crate::study::summary::VariantSummary;
use crate::study::ticks::Ticks;
use crate::study::variants::Variant;

/// (low, high) of mean -/+ one standard error, the low end kept positive for a log axis.
fn bar(e: &Estimate) -> (f64, f64) {
    let se = e.se.unwrap_or(0.0);
    ((e.mean - se).max(e.mean / 10.0), e.mean + se)
}

fn usable(e: &Estimate) -> bool {
    e.mean.is_finite() && e.mean > 0.0
}

fn y_desc(clock: Clock) -> String {
    match clock {
        Clock::Wall => "1 / (MSE · s)".into(),
        Clock::Cpu => "1 / (MSE · CPU s)".into(),
    }
}

/// Efficiency of each variant, first variant at the top.
pub(super) struct ByVariant {
    title: String,
    x_desc: String,
    entries: Vec<(String, Estimate)>,
}

impl ByVariant {
    pub fn new(summaries: &[VariantSummary], m: Measure, clock: Clock) -> Self {
        let entries = summaries
            .iter()
            .filter_map(|s| {
                let e = s.efficiency_over_runs.get(&m)?;
                Some((s.label.clone(), *e))
            })
            .collect();
        Self {
            title: format!("Efficiency ({}), mean ± standard error over runs", m.name()),
            x_desc: y_desc(clock),
            entries,
        }
    }
}

impl Figure for ByVariant {
    fn size(&self) -> (u32, u32) {
        (900, (140 + 36 * self.entries.len() as u32).max(320))
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), String> {
        root.fill(&WHITE).map_err(text)?;
        let good: Vec<&(String, Estimate)> = self.entries.iter().filter(|e| usable(&e.1)).collect();
        let (x0, x1) = log_range(good.iter().flat_map(|(_, e)| {
            let (lo, hi) = bar(e);
            [lo, hi]
        }));
        let (xt, xm) = log_axis(x0, x1);
        let n = self.entries.len() as i32;
        // Row i (from the top) sits at y = n - 1 - i.
        let names: Vec<String> = self.entries.iter().rev().map(|e| e.0.clone()).collect();
        let longest = names.iter().map(|l| l.chars().count()).max().unwrap_or(4) as u32;
        let mut chart = ChartBuilder::on(root)
            .caption(&self.title, (FONT, 20))
            .margin(16)
            .x_label_area_size(50)
            .y_label_area_size((longest * 8 + 24).clamp(60, 420))
            .build_cartesian_2d(
                (x0..x1)
                    .log_scale()
                    .with_key_points(xt.values.clone())
                    .with_light_points(xm),
                (-1..n).with_key_points((0..n).collect()),
            )
            .map_err(text)?;
        chart
            .configure_mesh()
            .x_desc(&self.x_desc)
            .x_label_formatter(&|v| xt.label(*v))
            .y_label_formatter(&|v| {
                usize::try_from(*v)
                    .ok()
                    .and_then(|i| names.get(i).cloned())
                    .unwrap_or_default()
            })
            .label_style((FONT, 14))
            .axis_desc_style((FONT, 16))
            .draw()
            .map_err(text)?;
        for (i, (_, e)) in self.entries.iter().enumerate() {
            if !usable(e) {
                continue;
            }
            let y = n - 1 - i as i32;
            let (lo, hi) = bar(e);
            let c = colour(i);
            chart
                .draw_series([PathElement::new(vec![(lo, y), (hi, y)], c.stroke_width(2))])
                .map_err(text)?;
            chart
                .draw_series([Circle::new((e.mean, y), 5, c.filled())])
                .map_err(text)?;
        }
        Ok(())
    }
}

/// Efficiency against q.
pub(super) struct VsQ {
    title: String,
    q_key: String,
    y_desc: String,
    /// Per combination of the other varied keys: (q, efficiency) points.
    groups: Vec<(String, Vec<(f64, Estimate)>)>,
    /// Variants whose q is not a number: (label, efficiency).
    flat: Vec<(String, Estimate)>,
}

impl VsQ {
    /// None when `q_key` is not varied.
    pub fn new(
        variants: &[Variant],
        summaries: &[VariantSummary],
        m: Measure,
        q_key: &str,
        clock: Clock,
    ) -> Option<Self> {
        variants
            .iter()
            .find(|v| v.values.iter().any(|(k, _)| k == q_key))?;
        let mut out = Self {
            title: format!("Efficiency ({}) vs q", m.name()),
            q_key: q_key.to_string(),
            y_desc: y_desc(clock),
            groups: Vec::new(),
            flat: Vec::new(),
        };
        for s in summaries {
            let Some(v) = variants.iter().find(|v| v.label == s.label) else {
                continue;
            };
            let Some(e) = s.efficiency_over_runs.get(&m).filter(|e| usable(e)) else {
                continue;
            };
            out.add(v, *e, q_key);
        }
        Some(out)
    }

    fn add(&mut self, v: &Variant, e: Estimate, q_key: &str) {
        let q = v
            .values
            .iter()
            .find(|(k, _)| k == q_key)
            .map(|(_, val)| val);
        let rest: Vec<String> = v
            .values
            .iter()
            .filter(|(k, _)| k != q_key)
            .map(|(k, val)| format!("{}={val}", k.rsplit('.').next().unwrap_or(k)))
            .collect();
        let name = if rest.is_empty() {
            "mean ± standard error".to_string()
        } else {
            rest.join(" ")
        };
        match q.and_then(|q| q.parse::<f64>().ok()).filter(|q| *q > 0.0) {
            Some(q) => match self.groups.iter_mut().find(|(n, _)| *n == name) {
                Some((_, pts)) => pts.push((q, e)),
                None => self.groups.push((name, vec![(q, e)])),
            },
            None => self.flat.push((v.label.clone(), e)),
        }
    }
}

impl VsQ {
    /// One line per group, with standard-error bars.
    fn draw_groups<DB: DrawingBackend>(
        &self,
        chart: &mut ChartContext<'_, DB, LogLog>,
    ) -> Result<(), String> {
        for (gi, (name, pts)) in self.groups.iter().enumerate() {
            let mut pts = pts.clone();
            pts.sort_by(|a, b| a.0.total_cmp(&b.0));
            let c = colour(gi);
            let line: Vec<(f64, f64)> = pts.iter().map(|(q, e)| (*q, e.mean)).collect();
            chart
                .draw_series(LineSeries::new(line.clone(), c.stroke_width(2)))
                .map_err(text)?
                .label(name.clone())
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], c.stroke_width(3))
                });
            chart
                .draw_series(pts.iter().map(|(q, e)| {
                    let (lo, hi) = bar(e);
                    PathElement::new(vec![(*q, lo), (*q, hi)], c.stroke_width(2))
                }))
                .map_err(text)?;
            chart
                .draw_series(line.iter().map(|p| Circle::new(*p, 4, c.filled())))
                .map_err(text)?;
        }
        Ok(())
    }
}

impl Figure for VsQ {
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), String> {
        root.fill(&WHITE).map_err(text)?;
        let mut qs: Vec<f64> = self
            .groups
            .iter()
            .flat_map(|(_, p)| p.iter().map(|p| p.0))
            .collect();
        qs.sort_by(f64::total_cmp);
        qs.dedup();
        let (x0, x1) = log_range(qs.iter().copied());
        let all = self
            .groups
            .iter()
            .flat_map(|(_, p)| p.iter().map(|p| p.1))
            .chain(self.flat.iter().map(|f| f.1));
        let (y0, y1) = log_range(all.flat_map(|e| {
            let (lo, hi) = bar(&e);
            [lo, hi]
        }));
        let mut axes = LogLogAxes::new(
            self.title.clone(),
            (x0, x1),
            &self.q_key,
            (y0, y1),
            &self.y_desc,
        );
        // The q values studied are the ticks, when there are two or more.
        if qs.len() >= 2 {
            (axes.x_ticks, axes.x_minor) = (Ticks::new(qs), Vec::new());
        }
        let mut chart = log_log(root, &axes)?;
        self.draw_groups(&mut chart)?;
        for (fi, (label, e)) in self.flat.iter().enumerate() {
            let c = colour(self.groups.len() + fi);
            chart
                .draw_series(DashedLineSeries::new(
                    vec![(x0, e.mean), (x1, e.mean)],
                    10,
                    6,
                    c.stroke_width(2),
                ))
                .map_err(text)?
                .label(label.clone())
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], c.stroke_width(2))
                });
        }
        legend(&mut chart)
    }
}
