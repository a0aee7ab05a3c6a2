//! The study's plots, each written as SVG and PNG (plotters' SVG and bitmap backends; the PNG's
//! text in DejaVu Sans, embedded, so it reads the same on every machine):
//!
//! - `error-vs-time[-LAYER]`: RMSE against rendering time on the study's clock, log-log, one
//!   colour per variant, one line per run, with a 1/sqrt(t) guide and (whole image) the
//!   reference's noise floor;
//! - `efficiency[-LAYER]`: each variant's efficiency 1 / (MSE x t), mean over runs with its
//!   standard error, log scale;
//! - `efficiency-vs-q[-LAYER]` (when `integrator.q` is varied): efficiency against q, one line
//!   per combination of the other varied keys; variants whose q is not a number (`auto`) are
//!   dashed horizontal lines.
//!
//! LAYER is empty for the whole image, `scaled` for the image against k x reference
//! (`--fit-scale`), `medium` and `surface` for the film's layers (when the reference has them).
//! Ticks are chosen and labelled by `ticks`.

mod efficiency;
mod error_time;

use std::path::{Path, PathBuf};
use std::sync::Once;

use plotters::coord::Shift;
use plotters::coord::combinators::{BindKeyPoints, LogCoord, WithKeyPoints};
use plotters::prelude::*;

use super::best::Measure;
use super::run::Row;
use super::summary::Summary;
use super::ticks::{Ticks, log_minor, log_ticks};
use super::variants::Variant;
use super::{StudyError, io_err};

/// The font family every plot uses (registered from the embedded DejaVu Sans).
const FONT: &str = "sans-serif";

/// A figure that can draw itself on any plotters backend.
trait Figure {
    fn size(&self) -> (u32, u32) {
        (900, 600)
    }
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), String>;
}

/// plotters' errors as text.
fn text<E: std::fmt::Display>(e: E) -> String {
    e.to_string()
}

fn register_font() {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| {
        // The embedded font is a valid TrueType file: registering cannot fail at run time, and
        // if it did, drawing text would report the missing font as a plot error.
        let _ = plotters::style::register_font(FONT, FontStyle::Normal, dejavu::sans::regular());
    });
}

/// Writes `STEM.svg` and `STEM.png` (atomically) and returns their paths.
fn save(fig: &impl Figure, stem: &Path) -> Result<Vec<PathBuf>, StudyError> {
    register_font();
    let (w, h) = fig.size();
    let svg_path = stem.with_extension("svg");
    let perr = |path: &Path, message: String| StudyError::Plot {
        path: path.to_path_buf(),
        message,
    };
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (w, h)).into_drawing_area();
        fig.draw(&root).map_err(|m| perr(&svg_path, m))?;
        root.present().map_err(|e| perr(&svg_path, text(e)))?;
    }
    crate::film::atomic::replace(&svg_path, |tmp| std::fs::write(tmp, &svg))
        .map_err(|e| io_err(&svg_path, e))?;

    let png_path = stem.with_extension("png");
    let mut pixels = vec![0u8; w as usize * h as usize * 3];
    {
        let root = BitMapBackend::with_buffer(&mut pixels, (w, h)).into_drawing_area();
        fig.draw(&root).map_err(|m| perr(&png_path, m))?;
        root.present().map_err(|e| perr(&png_path, text(e)))?;
    }
    crate::film::atomic::replace(&png_path, |tmp| {
        image::save_buffer_with_format(
            tmp,
            &pixels,
            w,
            h,
            image::ColorType::Rgb8,
            image::ImageFormat::Png,
        )
        .map_err(std::io::Error::other)
    })
    .map_err(|e| io_err(&png_path, e))?;
    Ok(vec![svg_path, png_path])
}

/// The file-name suffix of a measure's plots.
fn suffix(m: Measure) -> &'static str {
    match m {
        Measure::Image => "",
        Measure::ImageScaled => "-scaled",
        Measure::Medium => "-medium",
        Measure::Surface => "-surface",
    }
}

/// Writes every plot of the study into `dir`; returns the files written.
pub fn write_plots(
    dir: &Path,
    variants: &[Variant],
    rows: &[Row],
    summary: &Summary,
) -> Result<Vec<PathBuf>, StudyError> {
    let mut written = Vec::new();
    let clock = summary.clock;
    for m in Measure::ALL {
        let measured = rows.iter().any(|r| m.mse(&r.checkpoint).is_some());
        if !measured {
            continue;
        }
        let stem = |name: &str| dir.join(format!("{name}{}", suffix(m)));
        let fig =
            error_time::ErrorVsTime::new(variants, rows, m, clock, summary.reference_noise_mse);
        written.extend(save(&fig, &stem("error-vs-time"))?);
        let fig = efficiency::ByVariant::new(&summary.variants, m, clock);
        written.extend(save(&fig, &stem("efficiency"))?);
        if let Some(fig) =
            efficiency::VsQ::new(variants, &summary.variants, m, "integrator.q", clock)
        {
            written.extend(save(&fig, &stem("efficiency-vs-q"))?);
        }
    }
    Ok(written)
}

/// A padded range for a log axis over the positive, finite `values`.
fn log_range(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let (lo, hi) = values
        .filter(|v| v.is_finite() && *v > 0.0)
        .fold((f64::INFINITY, 0.0f64), |(lo, hi), v| {
            (lo.min(v), hi.max(v))
        });
    if lo.is_finite() && hi > lo {
        (lo / 1.25, hi * 1.25)
    } else if lo.is_finite() {
        (lo / 2.0, lo * 2.0)
    } else {
        (1e-3, 1.0)
    }
}

/// Major ticks (with labels) and minor grid positions of a log axis.
fn log_axis(lo: f64, hi: f64) -> (Ticks, Vec<f64>) {
    let major = log_ticks(lo, hi);
    let minor = log_minor(lo, hi);
    (Ticks::new(major), minor)
}

/// A log axis with our own ticks.
type LogAxis = WithKeyPoints<LogCoord<f64>>;
/// The coordinates of a log-log chart.
type LogLog = Cartesian2d<LogAxis, LogAxis>;

/// What a log-log chart shows on its axes.
struct LogLogAxes {
    title: String,
    /// Range, ticks and minor grid lines of x.
    x: (f64, f64),
    x_ticks: Ticks,
    x_minor: Vec<f64>,
    x_desc: String,
    y: (f64, f64),
    y_ticks: Ticks,
    y_minor: Vec<f64>,
    y_desc: String,
}

impl LogLogAxes {
    /// Axes over the given ranges with ticks from `log_axis`.
    fn new(title: String, x: (f64, f64), x_desc: &str, y: (f64, f64), y_desc: &str) -> Self {
        let (x_ticks, x_minor) = log_axis(x.0, x.1);
        let (y_ticks, y_minor) = log_axis(y.0, y.1);
        Self {
            title,
            x,
            x_ticks,
            x_minor,
            x_desc: x_desc.to_string(),
            y,
            y_ticks,
            y_minor,
            y_desc: y_desc.to_string(),
        }
    }
}

/// A log-log chart with its mesh, labelled ticks and axis descriptions drawn.
fn log_log<'a, DB: DrawingBackend>(
    root: &'a DrawingArea<DB, Shift>,
    a: &LogLogAxes,
) -> Result<ChartContext<'a, DB, LogLog>, String> {
    let mut chart = ChartBuilder::on(root)
        .caption(&a.title, (FONT, 22))
        .margin(16)
        .x_label_area_size(50)
        .y_label_area_size(80)
        .build_cartesian_2d(
            (a.x.0..a.x.1)
                .log_scale()
                .with_key_points(a.x_ticks.values.clone())
                .with_light_points(a.x_minor.clone()),
            (a.y.0..a.y.1)
                .log_scale()
                .with_key_points(a.y_ticks.values.clone())
                .with_light_points(a.y_minor.clone()),
        )
        .map_err(text)?;
    chart
        .configure_mesh()
        .x_desc(&a.x_desc)
        .y_desc(&a.y_desc)
        .x_label_formatter(&|v| a.x_ticks.label(*v))
        .y_label_formatter(&|v| a.y_ticks.label(*v))
        .label_style((FONT, 15))
        .axis_desc_style((FONT, 16))
        .draw()
        .map_err(text)?;
    Ok(chart)
}

/// The colour of series `i`.
fn colour(i: usize) -> RGBAColor {
    Palette99::pick(i).to_rgba()
}

/// Draws the legend of `chart` in its upper right corner.
fn legend<'a, DB: DrawingBackend + 'a, CT: CoordTranslate>(
    chart: &mut ChartContext<'a, DB, CT>,
) -> Result<(), String> {
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperRight)
        .label_font((FONT, 14))
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .draw()
        .map_err(text)
}
