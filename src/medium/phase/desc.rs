use std::path::Path;

use serde::{Deserialize, Serialize};

use super::{Draine, HgDraine, Phase, Rayleigh, TwoTermHg, intern, table_csv};
use crate::medium::MediumError;
use crate::spectrum::SpectralGrid;

/// A medium's phase function as the scene file gives it: `phase = { type = "...", ... }`.
/// docs/scene-format.md documents every variant.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "type", rename_all = "kebab-case", deny_unknown_fields)]
pub enum PhaseDesc {
    /// Henyey–Greenstein.
    Hg { g: f32 },
    /// `weight * HG(g1) + (1 - weight) * HG(g2)`.
    TwoTermHg { g1: f32, g2: f32, weight: f32 },
    /// Rayleigh, `3 (1 + cos²) / 16π`.
    Rayleigh,
    /// Draine 2003 with asymmetry `g` and `alpha` >= 0.
    Draine { g: f32, alpha: f32 },
    /// Jendersie & d'Eon 2023's fit for water droplets of `diameter` µm.
    HgDraine { diameter: f32 },
    /// A CSV table (angle in degrees, then values), relative to the scene file.
    Tabulated { file: String },
}

impl PhaseDesc {
    /// Range checks that need no file: (key below `phase`, message) for each problem.
    pub fn check(&self) -> Vec<(String, String)> {
        let mut out = Vec::new();
        let mut g = |key: &str, v: f32| {
            if !(v.is_finite() && v.abs() < 1.0) {
                out.push((key.to_string(), format!("must be in (-1, 1), got {v}")));
            }
        };
        match self {
            PhaseDesc::Hg { g: v } => g("g", *v),
            PhaseDesc::TwoTermHg { g1, g2, weight } => {
                g("g1", *g1);
                g("g2", *g2);
                if !(weight.is_finite() && (0.0..=1.0).contains(weight)) {
                    out.push(("weight".into(), format!("must be in [0, 1], got {weight}")));
                }
            }
            PhaseDesc::Rayleigh => {}
            PhaseDesc::Draine { g: v, alpha } => {
                g("g", *v);
                if !(alpha.is_finite() && *alpha >= 0.0) {
                    out.push(("alpha".into(), format!("must be >= 0, got {alpha}")));
                }
            }
            PhaseDesc::HgDraine { diameter } => {
                if !(diameter.is_finite() && *diameter > 0.0 && *diameter <= super::MAX_DIAMETER) {
                    out.push((
                        "diameter".into(),
                        format!("must be in (0, 50] µm (the fit's range), got {diameter}"),
                    ));
                }
            }
            PhaseDesc::Tabulated { .. } => {}
        }
        out
    }

    /// The runtime phase. `resolve` turns the scene's relative file name into a path; a table
    /// with one column per wavelength is reduced to `grid`'s bins.
    pub fn build(
        &self,
        grid: &SpectralGrid,
        resolve: &dyn Fn(&str) -> std::path::PathBuf,
    ) -> Result<Phase, MediumError> {
        Ok(match self {
            PhaseDesc::Hg { g } => Phase::hg(*g)?,
            PhaseDesc::TwoTermHg { g1, g2, weight } => {
                Phase::TwoTermHg(TwoTermHg::new(*g1, *g2, *weight)?)
            }
            PhaseDesc::Rayleigh => Phase::Rayleigh(Rayleigh),
            PhaseDesc::Draine { g, alpha } => Phase::Draine(Draine::new(*g, *alpha)?),
            PhaseDesc::HgDraine { diameter } => Phase::HgDraine(HgDraine::new(*diameter)?),
            PhaseDesc::Tabulated { file } => {
                Phase::Tabulated(intern(load_table(&resolve(file), grid)?))
            }
        })
    }
}

/// Reads and reduces a phase table file.
pub fn load_table(path: &Path, grid: &SpectralGrid) -> Result<super::PhaseTable, MediumError> {
    let text = std::fs::read_to_string(path).map_err(|e| MediumError::Read {
        file: path.to_path_buf(),
        message: e.to_string(),
    })?;
    table_csv::parse(&text, path)?.table(grid, path)
}
