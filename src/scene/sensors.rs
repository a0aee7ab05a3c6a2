//! `[[sensors]]`: photometric measurements of a render, read with their standard error at the
//! end (`type = "luminance"` over a pixel region, `type = "illuminance"` at a point with a
//! normal). The keys, checks and the runtime [`Sensor`] the film and the integrator use.

use glam::Vec3;
use serde::{Deserialize, Serialize};

use super::array::exact;
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

/// `type = "luminance"`: the mean luminance over a region of pixels.
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LuminanceSensorDesc {
    /// `[x0, y0, x1, y1]`: pixels x0 <= x < x1, y0 <= y < y1 (row 0 at the top).
    #[serde(deserialize_with = "exact")]
    pub region: [u32; 4],
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
            SensorKindDesc::Luminance(s) => {
                let [x0, y0, x1, y1] = s.region;
                if !(x0 < x1 && y0 < y1 && x1 <= width && y1 <= height) {
                    c.fail(
                        format!("{key}.region"),
                        format!(
                            "[x0, y0, x1, y1] must hold x0 < x1 <= {width} and y0 < y1 <= \
                             {height} (the image's size), got {:?}",
                            s.region
                        ),
                    );
                }
            }
            SensorKindDesc::Illuminance(s) => {
                c.vector(&format!("{key}.position"), s.position);
                c.direction(&format!("{key}.normal"), s.normal);
            }
        }
    }

    /// The runtime sensor (index `index` in the scene's list).
    pub fn build(&self, index: usize) -> Sensor {
        let kind = match &self.kind {
            SensorKindDesc::Luminance(s) => SensorKind::Luminance { region: s.region },
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
