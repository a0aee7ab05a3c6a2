//! Fixed-size number arrays that refuse extra elements: serde's `[f32; N]` reads the first N
//! elements of a longer TOML array and drops the rest without a word.

use std::fmt;
use std::marker::PhantomData;

use serde::de::{self, IgnoredAny, SeqAccess, Visitor};
use serde::{Deserialize, Deserializer};

/// For `#[serde(deserialize_with = "exact")]` on a `[f32; N]` (or `[u32; N]`) field.
pub fn exact<'de, D, T, const N: usize>(d: D) -> Result<[T; N], D::Error>
where
    D: Deserializer<'de>,
    T: Deserialize<'de> + Default + Copy,
{
    d.deserialize_seq(Exact::<T, N>(PhantomData))
}

/// As [`exact`] for an optional field (`#[serde(default, deserialize_with = "exact_opt")]`).
pub fn exact_opt<'de, D, T, const N: usize>(d: D) -> Result<Option<[T; N]>, D::Error>
where
    D: Deserializer<'de>,
    T: Deserialize<'de> + Default + Copy,
{
    exact(d).map(Some)
}

struct Exact<T, const N: usize>(PhantomData<[T; N]>);

impl<'de, T: Deserialize<'de> + Default + Copy, const N: usize> Visitor<'de> for Exact<T, N> {
    type Value = [T; N];

    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        write!(f, "an array of {N} numbers")
    }

    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<[T; N], A::Error> {
        let mut out = [T::default(); N];
        for (i, v) in out.iter_mut().enumerate() {
            *v = seq
                .next_element()?
                .ok_or_else(|| de::Error::invalid_length(i, &self))?;
        }
        let mut len = N;
        while seq.next_element::<IgnoredAny>()?.is_some() {
            len += 1;
        }
        if len != N {
            return Err(de::Error::invalid_length(len, &self));
        }
        Ok(out)
    }
}

#[cfg(test)]
mod tests {
    use serde::Deserialize;

    #[derive(Debug, Deserialize)]
    struct T {
        #[serde(deserialize_with = "super::exact")]
        v: [f32; 2],
    }

    #[test]
    fn exactly_n_numbers() {
        let ok: T = toml::from_str("v = [1, 2.5]").expect("two numbers");
        assert_eq!(ok.v, [1.0, 2.5]);
        for bad in ["v = [1]", "v = [1, 2, 3]", "v = 1"] {
            let e = toml::from_str::<T>(bad).expect_err(bad).to_string();
            assert!(e.contains("array of 2 numbers"), "{bad}: {e}");
        }
    }
}
