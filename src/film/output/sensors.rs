//! Sensor readings as text: a table for the terminal, CSV and JSON files (written atomically).

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use super::OutputError;
use crate::film::sensor::RELIABLE_PASSES;
use crate::film::{SensorKind, SensorReading};

fn number(v: Option<f64>) -> String {
    v.map_or_else(String::new, |v| format!("{v:.6e}"))
}

/// Where the kind's sensor is: the pixel region or the point and normal.
fn place(kind: &SensorKind) -> String {
    match kind {
        SensorKind::Luminance {
            region: [x0, y0, x1, y1],
        } => {
            format!("pixels {x0}..{x1} x {y0}..{y1}")
        }
        SensorKind::Illuminance {
            position: p,
            normal: n,
        } => format!(
            "at ({}, {}, {}) facing ({}, {}, {})",
            p[0], p[1], p[2], n[0], n[1], n[2]
        ),
    }
}

/// The readings as an aligned table (one line per sensor).
pub fn table(readings: &[SensorReading]) -> String {
    let width = readings
        .iter()
        .map(|r| r.name.len())
        .max()
        .unwrap_or(4)
        .max(6);
    let mut s = format!(
        "{:<width$}  {:<11}  {:>12}  {:>10}  {:<27}  {:<5}  where\n",
        "sensor", "type", "value", "std error", "95% interval", "unit"
    );
    for r in readings {
        let se = r.std_error.map_or("-".into(), |e| format!("{e:.4}"));
        let ci = r.ci95.map_or("- (needs 2 passes)".into(), |[a, b]| {
            let flag = if r.ci95_reliable { "" } else { " *" };
            format!("[{a:.4}, {b:.4}]{flag}")
        });
        let _ = writeln!(
            s,
            "{:<width$}  {:<11}  {:>12.4}  {:>10}  {:<27}  {:<5}  {}",
            r.name,
            r.kind.name(),
            r.value,
            se,
            ci,
            r.unit,
            place(&r.kind)
        );
    }
    if readings
        .iter()
        .any(|r| r.ci95.is_some() && !r.ci95_reliable)
    {
        let _ = writeln!(
            s,
            "* unreliable below {RELIABLE_PASSES} passes: the spread of a few passes of \
             gathered light underestimates the error (render more passes)"
        );
    }
    s
}

/// The readings as CSV: one row per sensor (value, standard error, 95 % interval, unit,
/// passes, place).
pub fn csv(readings: &[SensorReading]) -> String {
    let mut s = String::from(
        "name,type,value,std_error,ci95_low,ci95_high,unit,passes,where,ci95_reliable\n",
    );
    for r in readings {
        let [lo, hi] = r.ci95.map_or([None, None], |[a, b]| [Some(a), Some(b)]);
        let _ = writeln!(
            s,
            "{},{},{},{},{},{},{},{},\"{}\",{}",
            r.name,
            r.kind.name(),
            number(Some(r.value)),
            number(r.std_error),
            number(lo),
            number(hi),
            r.unit,
            r.passes,
            place(&r.kind),
            r.ci95_reliable
        );
    }
    s
}

/// The CSV and JSON files of the sensors of an output `NAME.ext`: `NAME.sensors.csv` and
/// `NAME.sensors.json` beside it.
pub fn paths(output: &Path) -> [PathBuf; 2] {
    let stem = output
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "render".into());
    ["csv", "json"].map(|e| output.with_file_name(format!("{stem}.sensors.{e}")))
}

/// Writes `readings` to the CSV file `csv_path` and the JSON file `json_path`.
pub fn write(
    [csv_path, json_path]: &[PathBuf; 2],
    readings: &[SensorReading],
) -> Result<(), OutputError> {
    let json =
        serde_json::to_string_pretty(&serde_json::json!({ "sensors": readings })).map_err(|e| {
            OutputError::Write {
                path: json_path.clone(),
                message: e.to_string(),
            }
        })?;
    for (path, text) in [(csv_path, csv(readings)), (json_path, json)] {
        crate::film::atomic::replace(path, |tmp| std::fs::write(tmp, text.as_bytes())).map_err(
            |e| OutputError::Write {
                path: path.clone(),
                message: e.to_string(),
            },
        )?;
    }
    Ok(())
}
