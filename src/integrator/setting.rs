//! A setting that is either a value or `"auto"` (chosen by the integrator from the scene, or
//! from what the first passes measure). In a scene file: `radius = 0.01` or `radius = "auto"`.

use std::fmt;
use std::marker::PhantomData;

use serde::de::{self, Visitor};
use serde::{Deserialize, Deserializer, Serialize, Serializer};

/// `"auto"` or a value.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Setting<T> {
    Auto,
    Value(T),
}

impl<T: Copy> Setting<T> {
    /// The value, if one is set.
    pub fn value(&self) -> Option<T> {
        match self {
            Setting::Auto => None,
            Setting::Value(v) => Some(*v),
        }
    }

    pub fn is_auto(&self) -> bool {
        matches!(self, Setting::Auto)
    }
}

/// The numbers a setting may hold, read from any TOML number.
pub trait SettingNumber: Copy + fmt::Display {
    fn from_f64(v: f64) -> Option<Self>;
    fn from_i64(v: i64) -> Option<Self>;
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error>;
}

impl SettingNumber for f32 {
    fn from_f64(v: f64) -> Option<Self> {
        Some(v as f32)
    }
    fn from_i64(v: i64) -> Option<Self> {
        Some(v as f32)
    }
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_f32(*self)
    }
}

impl SettingNumber for u64 {
    fn from_f64(v: f64) -> Option<Self> {
        // Counts may be written as 1e6; they must still be whole.
        (v.fract() == 0.0 && v >= 0.0 && v <= u64::MAX as f64).then_some(v as u64)
    }
    fn from_i64(v: i64) -> Option<Self> {
        u64::try_from(v).ok()
    }
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_u64(*self)
    }
}

impl SettingNumber for u32 {
    fn from_f64(v: f64) -> Option<Self> {
        (v.fract() == 0.0 && v >= 0.0 && v <= u32::MAX as f64).then_some(v as u32)
    }
    fn from_i64(v: i64) -> Option<Self> {
        u32::try_from(v).ok()
    }
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_u32(*self)
    }
}

impl<T: SettingNumber> Serialize for Setting<T> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        match self {
            Setting::Auto => s.serialize_str("auto"),
            Setting::Value(v) => v.serialize(s),
        }
    }
}

impl<'de, T: SettingNumber> Deserialize<'de> for Setting<T> {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct V<T>(PhantomData<T>);
        impl<T: SettingNumber> Visitor<'_> for V<T> {
            type Value = Setting<T>;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                f.write_str("a number or \"auto\"")
            }
            fn visit_f64<E: de::Error>(self, v: f64) -> Result<Setting<T>, E> {
                T::from_f64(v)
                    .map(Setting::Value)
                    .ok_or_else(|| E::custom(format!("{v} is not a valid value here")))
            }
            fn visit_i64<E: de::Error>(self, v: i64) -> Result<Setting<T>, E> {
                T::from_i64(v)
                    .map(Setting::Value)
                    .ok_or_else(|| E::custom(format!("{v} is not a valid value here")))
            }
            fn visit_u64<E: de::Error>(self, v: u64) -> Result<Setting<T>, E> {
                match i64::try_from(v) {
                    Ok(i) => self.visit_i64(i),
                    Err(_) => self.visit_f64(v as f64),
                }
            }
            fn visit_str<E: de::Error>(self, v: &str) -> Result<Setting<T>, E> {
                if v == "auto" {
                    Ok(Setting::Auto)
                } else {
                    Err(E::custom(format!(
                        "expected a number or \"auto\", got \"{v}\""
                    )))
                }
            }
        }
        d.deserialize_any(V(PhantomData))
    }
}

impl<T: fmt::Display> fmt::Display for Setting<T> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Setting::Auto => f.write_str("auto"),
            Setting::Value(v) => write!(f, "{v}"),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(Deserialize, Serialize, Debug)]
    struct T {
        r: Setting<f32>,
        n: Setting<u64>,
    }

    #[test]
    fn numbers_and_auto_round_trip() {
        let t: T = toml::from_str("r = 0.5\nn = 1e6").unwrap();
        assert_eq!(t.r, Setting::Value(0.5));
        assert_eq!(t.n, Setting::Value(1_000_000));
        let t: T = toml::from_str("r = \"auto\"\nn = 20000").unwrap();
        assert_eq!(t.r, Setting::Auto);
        assert_eq!(t.n, Setting::Value(20000));
        let back: T = toml::from_str(&toml::to_string(&t).unwrap()).unwrap();
        assert_eq!((back.r, back.n), (t.r, t.n));
        for bad in [
            "r = \"sometimes\"\nn = 1",
            "r = 1\nn = 1.5",
            "r = 1\nn = -3",
        ] {
            assert!(toml::from_str::<T>(bad).is_err(), "{bad}");
        }
    }
}
