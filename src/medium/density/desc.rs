//! A medium's `density` as the scene file gives it, its checks on its face and the runtime
//! field it builds (a grid reads its file here).

use std::path::{Path, PathBuf};
use std::sync::Arc;

use glam::{Mat4, Vec3};
use serde::{Deserialize, Serialize};

use crate::geometry::Transform;

use super::grid::{GridField, GridFileError, vdb, vol};
use super::noise::Noise;
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
    /// Patchy fog: `clamp(1 + contrast fbm(x / scale), 0, max)` (noise.rs), times `times`,
    /// sampled every `voxel` metres over `bounds` (default: the box of the shapes holding the
    /// medium) and interpolated as a grid.
    Noise {
        scale: f32,
        #[serde(default = "four")]
        octaves: u32,
        #[serde(default = "half")]
        contrast: f32,
        #[serde(default)]
        seed: u64,
        #[serde(default = "two")]
        max: f32,
        #[serde(default, skip_serializing_if = "Option::is_none")]
        voxel: Option<f32>,
        #[serde(default, skip_serializing_if = "Option::is_none")]
        bounds: Option<[[f32; 3]; 2]>,
        #[serde(default, skip_serializing_if = "Option::is_none")]
        times: Option<Box<DensityDesc>>,
        #[serde(default = "default_max_bytes")]
        max_bytes: u64,
    },
}

fn four() -> u32 {
    4
}

fn half() -> f32 {
    0.5
}

fn two() -> f32 {
    2.0
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
        Transform::new(self.translate.into(), self.rotate.into(), self.scale.into()).matrix()
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
        match self {
            DensityDesc::Grid { .. } => return self.check_grid(),
            DensityDesc::Noise { .. } => return self.check_noise(),
            DensityDesc::Height { .. } | DensityDesc::Layer { .. } => {}
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
            DensityDesc::Grid { .. } | DensityDesc::Noise { .. } => return Vec::new(),
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
    /// `interior` is the box of the shapes holding the medium (a noise field is sampled there).
    pub fn build(
        &self,
        resolve: &dyn Fn(&str) -> PathBuf,
        interior: Option<(Vec3, Vec3)>,
    ) -> Result<Density, DensityError> {
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
            DensityDesc::Noise { .. } => self.build_noise(resolve, interior)?,
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

impl DensityDesc {
    /// A noise field's keys on their face.
    fn check_noise(&self) -> Vec<(String, String)> {
        let DensityDesc::Noise {
            scale,
            octaves,
            contrast,
            max,
            voxel,
            bounds,
            times,
            max_bytes,
            ..
        } = self
        else {
            return Vec::new();
        };
        let mut out = Vec::new();
        let mut bad = |key: &str, ok: bool, what: String| {
            if !ok {
                out.push((key.to_string(), what));
            }
        };
        let length = |v: f32| v.is_finite() && (MIN_LENGTH..=MAX_LENGTH).contains(&v);
        let range = format!("{MIN_LENGTH} to {MAX_LENGTH} m");
        bad(
            "scale",
            length(*scale),
            format!("must be {range}, got {scale}"),
        );
        bad(
            "octaves",
            (1..=16).contains(octaves),
            format!("must be 1 to 16, got {octaves}"),
        );
        let c_ok = contrast.is_finite() && (0.0..=100.0).contains(contrast);
        bad(
            "contrast",
            c_ok,
            format!("must be 0 to 100, got {contrast}"),
        );
        let m_ok = max.is_finite() && *max > 0.0 && *max <= 1e6;
        bad("max", m_ok, format!("must be in (0, 1e6], got {max}"));
        if let Some(v) = voxel {
            bad("voxel", length(*v), format!("must be {range}, got {v}"));
        }
        if let Some([lo, hi]) = bounds {
            let ok = lo
                .iter()
                .chain(hi)
                .all(|x| x.is_finite() && x.abs() <= MAX_LENGTH)
                && (0..3).all(|k| lo[k] < hi[k]);
            bad(
                "bounds",
                ok,
                format!("must be [[min x, y, z], [max x, y, z]] with min < max, got {bounds:?}"),
            );
        }
        bad("max_bytes", *max_bytes > 0, "must be positive".into());
        if let Some(t) = times {
            if let DensityDesc::Noise { .. } = **t {
                out.push((
                    "times".into(),
                    "a noise field cannot be times another noise field".into(),
                ));
            } else {
                out.extend(
                    t.check()
                        .into_iter()
                        .map(|(k, m)| (format!("times.{k}"), m)),
                );
            }
        }
        out
    }

    /// A noise field sampled over `bounds` or the medium's shapes' box.
    fn build_noise(
        &self,
        resolve: &dyn Fn(&str) -> PathBuf,
        interior: Option<(Vec3, Vec3)>,
    ) -> Result<Density, DensityError> {
        let DensityDesc::Noise {
            scale,
            octaves,
            contrast,
            seed,
            max,
            voxel,
            bounds,
            times,
            max_bytes,
        } = self
        else {
            return Ok(Density::Uniform);
        };
        let noise = Noise {
            scale: *scale as f64,
            octaves: *octaves,
            contrast: *contrast as f64,
            seed: *seed,
            max: *max as f64,
        };
        let times = match times {
            Some(t) => Some(t.build(resolve, interior).map_err(|e| DensityError {
                key: "times",
                message: format!("{}: {}", e.key, e.message),
            })?),
            None => None,
        };
        let (lo, hi) = match (bounds, interior) {
            (Some([lo, hi]), _) => (Vec3::from(*lo), Vec3::from(*hi)),
            (None, Some(b)) => b,
            (None, None) => {
                return Err(DensityError {
                    key: "bounds",
                    message: "a noise field is sampled over the box of the shapes that hold \
                              its medium, and none does: give `bounds`"
                        .into(),
                });
            }
        };
        let step = voxel.map_or(noise.default_voxel(), |v| v as f64);
        let data = noise
            .bake((lo, hi), step, times.as_ref(), *max_bytes)
            .map_err(|bytes| DensityError {
                key: "voxel",
                message: format!(
                    "samples every {step:.4} m over {lo} to {hi} take {bytes} bytes, over \
                     max_bytes = {max_bytes}: give a larger `voxel` (or raise max_bytes)"
                ),
            })?;
        let what =
            format!("noise (scale {scale} m, {octaves} octaves, seed {seed}, voxel {step:.4} m)");
        let field = GridField::new(data, 1.0, None, what).map_err(|e| DensityError {
            key: "contrast",
            message: e.to_string(),
        })?;
        Ok(Density::Grid(Arc::new(field)))
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
