//! `[[sensors]]`: photometric measurements of a render, read with their standard error at the
//! end (`type = "luminance"` over a pixel region, `type = "illuminance"` at a point with a
//! normal). The keys, checks and the runtime [`Sensor`] the film and the integrator use.

use glam::Vec3;
use serde::{Deserialize, Serialize};

use super::array::{exact, exact_opt};
use super::check::Checker;
use super::tagged::{Tagged, kinds};
use crate::film::{Sensor, SensorKind};

/// Keys every sensor has.
#[derive(Clone, Debug, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SensorCommon {
    /// Name in the outputs (letters, digits, `-`, `_`, `.`); default `sensorN`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
}

/// `type = "luminance"`: the mean luminance over a region of pixels, given in pixels or as
/// fractions of the image (which follow a change of resolution).
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LuminanceSensorDesc {
    /// `[x0, y0, x1, y1]`: pixels x0 <= x < x1, y0 <= y < y1 (row 0 at the top).
    #[serde(
        default,
        deserialize_with = "exact_opt",
        skip_serializing_if = "Option::is_none"
    )]
    pub region: Option<[u32; 4]>,
    /// `[x0, y0, x1, y1]` as fractions of the width and height, in [0, 1]: the pixels the
    /// rectangle touches (at least one).
    #[serde(
        default,
        deserialize_with = "exact_opt",
        skip_serializing_if = "Option::is_none"
    )]
    pub window: Option<[f32; 4]>,
}

impl LuminanceSensorDesc {
    /// The pixel region on an image of `(width, height)`.
    pub fn pixels(&self, (width, height): (u32, u32)) -> [u32; 4] {
        match (self.region, self.window) {
            (Some(r), _) => r,
            (None, Some([x0, y0, x1, y1])) => {
                let lo =
                    |f: f32, n: u32| ((f.clamp(0.0, 1.0) * n as f32).floor() as u32).min(n - 1);
                let hi = |f: f32, n: u32, lo: u32| {
                    ((f.clamp(0.0, 1.0) * n as f32).ceil() as u32).clamp(lo + 1, n)
                };
                let (a, b) = (lo(x0, width.max(1)), lo(y0, height.max(1)));
                [a, b, hi(x1, width.max(1), a), hi(y1, height.max(1), b)]
            }
            (None, None) => [0, 0, 0, 0],
        }
    }
}

/// `type = "illuminance"`: the illuminance at a point on a surface of a given normal (direct
/// light and light scattered by media and surfaces).
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct IlluminanceSensorDesc {
    #[serde(deserialize_with = "exact")]
    pub position: [f32; 3],
    /// The side of the receiving surface light is measured on.
    #[serde(deserialize_with = "exact")]
    pub normal: [f32; 3],
}

kinds! {
    /// The kinds of sensor, by their `type`.
    pub enum SensorKindDesc: "sensor" {
        "luminance" => Luminance(LuminanceSensorDesc),
        "illuminance" => Illuminance(IlluminanceSensorDesc),
    }
}

/// A `[[sensors]]` table.
pub type SensorDesc = Tagged<SensorCommon, SensorKindDesc>;

impl SensorDesc {
    /// The sensor's name (its own, or `sensor<index>`).
    pub fn name(&self, index: usize) -> String {
        self.common
            .name
            .clone()
            .unwrap_or_else(|| format!("sensor{index}"))
    }

    /// Checks against the image size `(width, height)`.
    pub fn check(&self, c: &mut Checker, key: &str, (width, height): (u32, u32)) {
        if let Some(n) = &self.common.name {
            let ok = !n.is_empty()
                && n.len() <= 64
                && n.chars()
                    .all(|ch| ch.is_ascii_alphanumeric() || "-_.".contains(ch));
            if !ok {
                c.fail(
                    format!("{key}.name"),
                    "must be 1 to 64 letters, digits, `-`, `_` or `.`",
                );
            }
        }
        match &self.kind {
            SensorKindDesc::Luminance(s) => check_luminance(c, key, s, (width, height)),
            SensorKindDesc::Illuminance(s) => {
                c.point(&format!("{key}.position"), s.position);
                c.direction(&format!("{key}.normal"), s.normal);
            }
        }
    }

    /// The runtime sensor (index `index` in the scene's list) on an image of `size`.
    pub fn build(&self, index: usize, size: (u32, u32)) -> Sensor {
        let kind = match &self.kind {
            SensorKindDesc::Luminance(s) => SensorKind::Luminance {
                region: s.pixels(size),
            },
            SensorKindDesc::Illuminance(s) => SensorKind::Illuminance {
                position: s.position,
                normal: Vec3::from(s.normal).normalize_or(Vec3::Y).to_array(),
            },
        };
        Sensor {
            name: self.name(index),
            kind,
        }
    }
}

/// A luminance sensor's region: exactly one of `region` (within the image) and `window` (in
/// [0, 1], low < high).
fn check_luminance(c: &mut Checker, key: &str, s: &LuminanceSensorDesc, (w, h): (u32, u32)) {
    match (s.region, s.window) {
        (Some([x0, y0, x1, y1]), None) => {
            if !(x0 < x1 && y0 < y1 && x1 <= w && y1 <= h) {
                c.fail(
                    format!("{key}.region"),
                    format!(
                        "[x0, y0, x1, y1] must hold x0 < x1 <= {w} and y0 < y1 <= {h} (the \
                         image's size), got {:?}; `window` gives fractions of the image instead",
                        [x0, y0, x1, y1]
                    ),
                );
            }
        }
        (None, Some([x0, y0, x1, y1])) => {
            let unit = |v: f32| (0.0..=1.0).contains(&v);
            if !([x0, y0, x1, y1].into_iter().all(unit) && x0 < x1 && y0 < y1) {
                c.fail(
                    format!("{key}.window"),
                    format!(
                        "[x0, y0, x1, y1] must be fractions of the image in [0, 1] with x0 < x1 \
                         and y0 < y1, got {:?}",
                        [x0, y0, x1, y1]
                    ),
                );
            }
        }
        (Some(_), Some(_)) => c.fail(
            format!("{key}.window"),
            "give `region` or `window`, not both",
        ),
        (None, None) => c.fail(
            key,
            "a luminance sensor needs `region` (pixels) or `window` (fractions)",
        ),
    }
}

/// Sensor names must differ (they name the rows of the outputs).
pub fn check_all(c: &mut Checker, sensors: &[SensorDesc], size: (u32, u32)) {
    for (i, s) in sensors.iter().enumerate() {
        let key = format!("sensors.{i}");
        s.check(c, &key, size);
        let name = s.name(i);
        if sensors[..i]
            .iter()
            .enumerate()
            .any(|(j, o)| o.name(j) == name)
        {
            c.fail(
                format!("{key}.name"),
                format!("another sensor is named `{name}`"),
            );
        }
    }
}
