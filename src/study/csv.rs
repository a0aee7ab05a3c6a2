//! The study's CSV: one row per variant, run and checkpoint (pass). Values not measured (layer
//! errors against a reference without layers, the scale fit without `--fit-scale`, CPU time
//! where there is no CPU clock) are empty fields.

use std::fmt::Write as _;
use std::path::Path;

use super::metrics::{LayerErrors, efficiency};
use super::run::Row;
use super::variants::Variant;
use super::{StudyError, io_err};

/// The columns, in order. Every number is written exactly (shortest round-trip form), so the
/// efficiencies can be recomputed from the other columns. `efficiency` is 1 / (mse x seconds) (wall clock) and
/// `cpu_efficiency` 1 / (mse x cpu_seconds); `k` is the fitted scale of the reference and
/// `mse_scaled` the error against k x reference.
pub const CSV_HEADER: &str = "variant,label,run,passes,seconds,mse,rmse,rel_mse,\
medium_mse,medium_rmse,medium_rel_mse,surface_mse,surface_rmse,surface_rel_mse,noise,efficiency,mean_error,\
cpu_seconds,cpu_efficiency,k,mse_scaled,rmse_scaled";

fn num(v: f64) -> String {
    if v.is_nan() {
        String::new()
    } else {
        format!("{v:e}")
    }
}

fn opt(v: Option<f64>) -> String {
    v.map_or(String::new(), num)
}

fn layer(e: Option<LayerErrors>) -> String {
    match e {
        Some(e) => format!("{},{},{}", num(e.mse), num(e.rmse), num(e.rel_mse)),
        None => ",,".into(),
    }
}

pub fn write_csv(path: &Path, variants: &[Variant], rows: &[Row]) -> Result<(), StudyError> {
    let mut s = String::with_capacity(260 * (rows.len() + 1));
    s.push_str(CSV_HEADER);
    s.push('\n');
    for r in rows {
        let c = &r.checkpoint;
        let label = variants
            .get(r.variant)
            .map(|v| v.label.replace('"', "'"))
            .unwrap_or_default();
        let cpu_eff = (!c.cpu_seconds.is_nan()).then(|| efficiency(c.total.mse, c.cpu_seconds));
        let _ = writeln!(
            s,
            "{},\"{}\",{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}",
            r.variant,
            label,
            r.run,
            c.passes,
            c.seconds,
            num(c.total.mse),
            num(c.total.rmse),
            num(c.total.rel_mse),
            layer(c.medium),
            layer(c.surface),
            num(c.noise),
            num(efficiency(c.total.mse, c.seconds)),
            num(c.mean_error),
            if c.cpu_seconds.is_nan() {
                String::new()
            } else {
                c.cpu_seconds.to_string()
            },
            opt(cpu_eff),
            opt(c.fit.map(|f| f.k)),
            opt(c.fit.map(|f| f.mse)),
            opt(c.fit.map(|f| f.rmse)),
        );
    }
    crate::film::atomic::replace(path, |tmp| std::fs::write(tmp, s.as_bytes()))
        .map_err(|e| io_err(path, e))
}
