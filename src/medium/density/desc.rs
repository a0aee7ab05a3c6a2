//! A medium's `density` as the scene file gives it, its checks on its face and the runtime
//! field it builds (a grid reads its file here).

use std::path::{Path, PathBuf};
use std::sync::Arc;

use glam::{EulerRot, Mat4, Quat, Vec3};
use serde::{Deserialize, Serialize};

use super::grid::{GridField, GridFileError, vdb, vol};
use super::{Density, Height, Layer, MAX_LENGTH, MIN_LENGTH};

/// A medium's `density` as the scene file gives it: `density = { type = "...", ... }`.
/// docs/scene-format.md documents every variant.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "type", rename_all = "kebab-case", deny_unknown_fields)]
pub enum DensityDesc {
    /// Exponential height fog, `rho = exp(-(h - base) / scale_height)`, `h = up . x`.
    Height {
        #[serde(default)]
        base: f32,
        scale_height: f32,
        #[serde(default = "default_up")]
        up: [f32; 3],
    },
    /// A fog bank: 1 below `top - transition / 2`, 0 above `top + transition / 2`, a smooth
    /// step (cubic) in between.
    Layer {
        top: f32,
        transition: f32,
        #[serde(default = "default_up")]
        up: [f32; 3],
    },
    /// Samples on a grid from a file: a Mitsuba `.vol` or an OpenVDB `.vdb` (`grid` names the
    /// grid in a VDB file). `transform` maps the grid's unit box to the world (Mitsuba 3
    /// `gridvolume`'s `to_world`); without it, the box the file gives. Values times
    /// `multiplier`; files whose dense samples take more than `max_bytes` are refused.
    Grid {
        file: String,
        #[serde(default = "default_grid_name")]
        grid: String,
        #[serde(default = "one")]
        multiplier: f32,
        #[serde(default, skip_serializing_if = "Option::is_none")]
        transform: Option<GridTransform>,
        #[serde(default = "default_max_bytes")]
        max_bytes: u64,
    },
}

/// Where a grid's unit box goes: scale, then rotate (degrees about X, then Y, then Z), then
/// translate, as a shape's `transform`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct GridTransform {
    pub translate: [f32; 3],
    pub rotate: [f32; 3],
    pub scale: [f32; 3],
}

impl Default for GridTransform {
    fn default() -> Self {
        Self {
            translate: [0.0; 3],
            rotate: [0.0; 3],
            scale: [1.0; 3],
        }
    }
}

impl GridTransform {
    /// Unit box to world.
    pub fn matrix(&self) -> Mat4 {
        let [rx, ry, rz] = self.rotate.map(f32::to_radians);
        let q = Quat::from_euler(EulerRot::ZYX, rz, ry, rx);
        Mat4::from_scale_rotation_translation(self.scale.into(), q, self.translate.into())
    }
}

/// Why a density field cannot be built: the key below `density` and the message.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{key}: {message}")]
pub struct DensityError {
    pub key: &'static str,
    pub message: String,
}

fn default_grid_name() -> String {
    "density".into()
}

fn one() -> f32 {
    1.0
}

/// 4 GiB of dense samples (a 1024³ grid): more than any shipped scene needs, less than a
/// machine that renders one has; `max_bytes` raises it.
fn default_max_bytes() -> u64 {
    4 << 30
}

fn default_up() -> [f32; 3] {
    [0.0, 1.0, 0.0]
}

impl DensityDesc {
    /// Problems on the description's face: (key below `density`, message).
    pub fn check(&self) -> Vec<(String, String)> {
        if let DensityDesc::Grid { .. } = self {
            return self.check_grid();
        }
        let mut out = Vec::new();
        let (up, lengths): ([f32; 3], Vec<(&str, f32, bool)>) = match self {
            DensityDesc::Height {
                base,
                scale_height,
                up,
            } => (
                *up,
                vec![
                    ("base", *base, false),
                    ("scale_height", *scale_height, true),
                ],
            ),
            DensityDesc::Layer {
                top,
                transition,
                up,
            } => (
                *up,
                vec![("top", *top, false), ("transition", *transition, true)],
            ),
            DensityDesc::Grid { .. } => return Vec::new(),
        };
        for (key, v, positive) in lengths {
            if !v.is_finite() || v.abs() > MAX_LENGTH {
                out.push((
                    key.into(),
                    format!("must be finite, within ±{MAX_LENGTH} m, got {v}"),
                ));
            } else if positive && v < MIN_LENGTH {
                out.push((
                    key.into(),
                    format!("must be at least {MIN_LENGTH} m, got {v}"),
                ));
            }
        }
        let u = Vec3::from(up);
        if !(u.is_finite() && u.length() > 1e-6) {
            out.push((
                "up".into(),
                format!("must be a nonzero finite vector, got {up:?}"),
            ));
        }
        out
    }

    /// The runtime field (the description must have passed [`DensityDesc::check`]); a grid's
    /// file is found by `resolve` (relative to the scene's folder) and read here.
    pub fn build(&self, resolve: &dyn Fn(&str) -> PathBuf) -> Result<Density, DensityError> {
        Ok(match self {
            DensityDesc::Height {
                base,
                scale_height,
                up,
            } => Density::Height(Height::new(*base, *scale_height, Vec3::from(*up))),
            DensityDesc::Layer {
                top,
                transition,
                up,
            } => Density::Layer(Layer::new(*top, *transition, Vec3::from(*up))),
            DensityDesc::Grid {
                file,
                grid,
                multiplier,
                transform,
                max_bytes,
            } => {
                let path = resolve(file);
                let data = read_grid(&path, grid, *max_bytes).map_err(|e| DensityError {
                    key: match e {
                        GridFileError::NoSuchGrid { .. } => "grid",
                        GridFileError::TooLarge { .. } => "max_bytes",
                        _ => "file",
                    },
                    message: e.to_string(),
                })?;
                let field = GridField::new(
                    data,
                    *multiplier,
                    transform.as_ref().map(GridTransform::matrix),
                    file.clone(),
                )
                .map_err(|e| DensityError {
                    key: "file",
                    message: format!("{}: {e}", path.display()),
                })?;
                Density::Grid(Arc::new(field))
            }
        })
    }

    /// A grid's keys on their face (its file is read by `build`).
    fn check_grid(&self) -> Vec<(String, String)> {
        let DensityDesc::Grid {
            file,
            grid,
            multiplier,
            transform,
            max_bytes,
            ..
        } = self
        else {
            return Vec::new();
        };
        let mut out = Vec::new();
        let known = [".vol", ".vdb"]
            .iter()
            .any(|x| file.to_lowercase().ends_with(x));
        if !known {
            out.push(("file".into(), format!("a .vol or .vdb file, got {file:?}")));
        }
        if file.to_lowercase().ends_with(".vol") && grid != "density" {
            out.push((
                "grid".into(),
                format!("a .vol file holds one unnamed grid: `grid` ({grid:?}) names grids in .vdb files"),
            ));
        }
        if !(multiplier.is_finite() && *multiplier > 0.0 && *multiplier <= 1e6) {
            out.push((
                "multiplier".into(),
                format!("must be in (0, 1e6], got {multiplier}"),
            ));
        }
        if *max_bytes == 0 {
            out.push(("max_bytes".into(), "must be positive".into()));
        }
        if let Some(t) = transform {
            let finite = |v: [f32; 3], m: f32| v.iter().all(|x| x.is_finite() && x.abs() <= m);
            if !finite(t.translate, MAX_LENGTH) || !finite(t.rotate, 1e6) {
                out.push((
                    "transform".into(),
                    format!("must be finite, within ±{MAX_LENGTH} m"),
                ));
            }
            if !t
                .scale
                .iter()
                .all(|x| x.is_finite() && x.abs() >= MIN_LENGTH && x.abs() <= MAX_LENGTH)
            {
                out.push((
                    "transform.scale".into(),
                    format!(
                        "each must be within {MIN_LENGTH} to {MAX_LENGTH} m in size, got {:?}",
                        t.scale
                    ),
                ));
            }
        }
        out
    }
}

/// The samples of a grid file, by its extension (`check_grid` allowed only these two).
fn read_grid(path: &Path, grid: &str, budget: u64) -> Result<super::grid::GridData, GridFileError> {
    let vdb = path
        .extension()
        .is_some_and(|x| x.eq_ignore_ascii_case("vdb"));
    if vdb {
        vdb::read(path, grid, budget)
    } else {
        vol::read(path, budget)
    }
}
