//! The study's CSV: one row per variant, run and checkpoint (pass).

use std::io::Write;
use std::path::Path;

use super::metrics::efficiency;
use super::run::Row;
use super::variants::Variant;
use super::{StudyError, io_err};

pub const CSV_HEADER: &str = "variant,label,run,passes,seconds,mse,rmse,rel_mse,\
medium_mse,medium_rmse,medium_rel_mse,surface_mse,surface_rmse,surface_rel_mse,noise,efficiency,mean_error";

pub fn write_csv(path: &Path, variants: &[Variant], rows: &[Row]) -> Result<(), StudyError> {
    let mut s = String::with_capacity(200 * (rows.len() + 1));
    s.push_str(CSV_HEADER);
    s.push('\n');
    for r in rows {
        let c = &r.checkpoint;
        let label = variants
            .get(r.variant)
            .map(|v| v.label.replace('"', "'"))
            .unwrap_or_default();
        s.push_str(&format!(
            "{},\"{}\",{},{},{:.6},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e}\n",
            r.variant,
            label,
            r.run,
            c.passes,
            c.seconds,
            c.total.mse,
            c.total.rmse,
            c.total.rel_mse,
            c.medium.mse,
            c.medium.rmse,
            c.medium.rel_mse,
            c.surface.mse,
            c.surface.rmse,
            c.surface.rel_mse,
            c.noise,
            efficiency(c.total.mse, c.seconds),
            c.mean_error,
        ));
    }
    let mut f = std::fs::File::create(path).map_err(|e| io_err(path, e))?;
    f.write_all(s.as_bytes()).map_err(|e| io_err(path, e))
}
