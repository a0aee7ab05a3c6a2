//! Tables whose `type` key picks one of a closed set of kinds: `[[lights]]`, `[[shapes]]` and
//! `[materials.NAME]`. Each kind's keys are a plain serde struct beside the kind's own code, and
//! a key that belongs to no kind of the table's type is refused.
//!
//! serde's internally tagged enums would do the dispatch, but they buffer the table before they
//! know its kind, so an error inside it loses its key and line. Instead [`read`] works on the
//! spanned document: it reads `type`, refuses keys the kind does not have, then hands the keys
//! every kind shares and the kind's own keys to their structs through toml's span-keeping
//! deserializer. The generic [`Deserialize`] impl (used for `--set` round trips) goes through
//! the same function, and the loader calls [`read`] again on the original text to place an
//! error exactly.

use std::ops::Range;

use serde::de::{self, DeserializeOwned, Deserializer, Visitor};
use serde::{Deserialize, Serialize};
use toml::Spanned;
use toml::de::{DeTable, DeValue, ValueDeserializer};

/// A closed set of kinds, read from a table by the spelling of its `type` key. Implemented by
/// the [`kinds!`] macro, which keeps the spellings, the enum and the dispatch in one list.
pub trait Kinds: Sized + Serialize {
    /// What the table describes ("light"), for messages.
    const WHAT: &'static str;
    /// Every spelling of `type`.
    const NAMES: &'static [&'static str];
    /// Reads the kind spelled `name` from its own keys; `Ok(None)` if no kind is spelled so.
    fn read<'de, D: Deserializer<'de>>(name: &str, body: D) -> Result<Option<Self>, D::Error>;
}

/// Declares a [`Kinds`] enum: each variant's `type` spelling and the struct of its keys.
macro_rules! kinds {
    (
        $(#[$meta:meta])*
        $vis:vis enum $name:ident: $what:literal {
            $($(#[$vmeta:meta])* $tag:literal => $variant:ident($ty:ty),)+
        }
    ) => {
        $(#[$meta])*
        #[derive(Clone, Debug, serde::Serialize)]
        #[serde(tag = "type")]
        $vis enum $name {
            $($(#[$vmeta])* #[serde(rename = $tag)] $variant($ty),)+
        }

        impl $crate::scene::tagged::Kinds for $name {
            const WHAT: &'static str = $what;
            const NAMES: &'static [&'static str] = &[$($tag),+];
            fn read<'de, D: serde::Deserializer<'de>>(
                name: &str,
                body: D,
            ) -> Result<Option<Self>, D::Error> {
                Ok(Some(match name {
                    $($tag => Self::$variant(<$ty as serde::Deserialize>::deserialize(body)?),)+
                    // A spelling, not a variant: unknown names are the caller's error.
                    _ => return Ok(None),
                }))
            }
        }
    };
}
pub(crate) use kinds;

/// A table of kind `K` with the keys `C` that every kind of it shares.
#[derive(Clone, Debug, Serialize)]
pub struct Tagged<C, K> {
    #[serde(flatten)]
    pub common: C,
    #[serde(flatten)]
    pub kind: K,
}

/// Why a table could not be read: the key path inside it (empty: the table itself), the
/// message, and the span of the offending key or value in the text that was read.
#[derive(Clone, Debug, PartialEq)]
pub struct Fault {
    pub path: String,
    pub message: String,
    pub span: Option<Range<usize>>,
}

impl Fault {
    fn at(path: &str, message: String, span: Option<Range<usize>>) -> Fault {
        Fault {
            path: path.to_string(),
            message,
            span,
        }
    }
}

fn list(names: &[&str]) -> String {
    names
        .iter()
        .map(|n| format!("`{n}`"))
        .collect::<Vec<_>>()
        .join(", ")
}

/// Reads a table of kind `K` from the spanned document value `table`.
pub fn read<C, K>(table: Spanned<DeValue<'_>>) -> Result<Tagged<C, K>, Fault>
where
    C: DeserializeOwned,
    K: Kinds,
{
    let span = table.span();
    let DeValue::Table(entries) = table.into_inner() else {
        return Err(Fault::at(
            "",
            format!("a {} must be a table", K::WHAT),
            Some(span),
        ));
    };
    let name = kind_name::<K>(&entries)?;
    let Some(own) = kind_fields::<K>(&name) else {
        let span = entries
            .iter()
            .find(|(k, _)| k.get_ref().as_ref() == "type")
            .map(|(_, v)| v.span());
        return Err(Fault::at(
            "type",
            format!(
                "unknown {} type `{name}`, expected one of {}",
                K::WHAT,
                list(K::NAMES)
            ),
            span,
        ));
    };
    let shared = struct_fields::<C>();
    // The first key (in the text) that no part reads; the map itself is sorted by key.
    let unknown = entries
        .keys()
        .filter(|k| {
            let k = k.get_ref().as_ref();
            k != "type" && !shared.contains(&k) && !own.contains(&k)
        })
        .min_by_key(|k| k.span().start);
    if let Some(key) = unknown {
        let k = key.get_ref().as_ref();
        let mut expected = vec!["type"];
        expected.extend_from_slice(shared);
        expected.extend_from_slice(own);
        let message = format!(
            "unknown field `{k}` for a {name} {}, expected one of {}",
            K::WHAT,
            list(&expected)
        );
        return Err(Fault::at(k, message, Some(key.span())));
    }
    let (mut common, mut body) = (DeTable::default(), DeTable::default());
    for (key, value) in entries {
        let k = key.get_ref().as_ref();
        if shared.contains(&k) {
            common.insert(key, value);
        } else if k != "type" {
            body.insert(key, value);
        }
    }
    let common = traced(part(&span, common), |d| C::deserialize(d))?;
    let kind = traced(part(&span, body), |d| K::read(&name, d))?
        .ok_or_else(|| Fault::at("type", format!("unknown {} type `{name}`", K::WHAT), None))?;
    Ok(Tagged { common, kind })
}

/// Some of a table's keys, read as a table at the table's own span.
fn part<'i>(span: &Range<usize>, t: DeTable<'i>) -> ValueDeserializer<'i> {
    ValueDeserializer::from(Spanned::new(span.clone(), DeValue::Table(t)))
}

/// The `type` spelling of a table.
fn kind_name<K: Kinds>(entries: &DeTable<'_>) -> Result<String, Fault> {
    let expected = || format!("one of {}", list(K::NAMES));
    match entries.iter().find(|(k, _)| k.get_ref().as_ref() == "type") {
        None => Err(Fault::at(
            "",
            format!("missing field `type` ({})", expected()),
            None,
        )),
        Some((_, v)) => match v.get_ref() {
            DeValue::String(s) => Ok(s.to_string()),
            _ => Err(Fault::at(
                "type",
                format!(
                    "must be a string naming the {} type, {}",
                    K::WHAT,
                    expected()
                ),
                Some(v.span()),
            )),
        },
    }
}

/// Runs `f` on `de` tracking the key path of an error, which is placed by the span toml gives it.
fn traced<'de, T>(
    de: ValueDeserializer<'de>,
    f: impl FnOnce(
        serde_path_to_error::Deserializer<'_, '_, ValueDeserializer<'de>>,
    ) -> Result<T, toml::de::Error>,
) -> Result<T, Fault> {
    let mut track = serde_path_to_error::Track::new();
    f(serde_path_to_error::Deserializer::new(de, &mut track)).map_err(|e| {
        // Dotted as everywhere in brume: `position[1]` is `position.1`.
        let path = track.path().to_string().replace('[', ".").replace(']', "");
        let path = path.trim_matches('.');
        let path = if path == "?" { "" } else { path };
        // A fault about the whole part (a missing key) is placed at the table's header by the
        // caller, as the other checks on the table are.
        let span = if path.is_empty() { None } else { e.span() };
        Fault::at(path, e.message().to_string(), span)
    })
}

impl<'de, C, K> Deserialize<'de> for Tagged<C, K>
where
    C: DeserializeOwned,
    K: Kinds,
{
    /// Through [`read`]: the table is written back to TOML text and read with spans, so that
    /// every source of a table (the file, `--set` round trips) follows the same rules.
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let table = toml::Table::deserialize(d)?;
        let text = toml::to_string(&table).map_err(de::Error::custom)?;
        let doc = DeTable::parse(&text).map_err(|e| de::Error::custom(e.message()))?;
        let span = doc.span();
        read(Spanned::new(span, DeValue::Table(doc.into_inner()))).map_err(|f| {
            de::Error::custom(if f.path.is_empty() {
                f.message
            } else {
                format!("`{}`: {}", f.path, f.message)
            })
        })
    }
}

/// The keys of the struct of kind `name`, or None if `K` has no such kind.
pub fn kind_fields<K: Kinds>(name: &str) -> Option<&'static [&'static str]> {
    match K::read(name, Probe) {
        Ok(None) => None,
        Ok(Some(_)) | Err(Found(None)) => Some(&[]),
        Err(Found(Some(fields))) => Some(fields),
    }
}

/// The keys a serde struct reads.
pub fn struct_fields<T: DeserializeOwned>() -> &'static [&'static str] {
    match T::deserialize(Probe) {
        Err(Found(Some(fields))) => fields,
        Ok(_) | Err(Found(None)) => &[],
    }
}

/// A deserializer that learns a struct's keys from the list serde passes to
/// `deserialize_struct`, and refuses everything else.
struct Probe;

#[derive(Debug)]
struct Found(Option<&'static [&'static str]>);

impl std::fmt::Display for Found {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("probe")
    }
}

impl std::error::Error for Found {}

impl de::Error for Found {
    fn custom<T: std::fmt::Display>(_: T) -> Self {
        Found(None)
    }
}

impl<'de> Deserializer<'de> for Probe {
    type Error = Found;

    fn deserialize_any<V: Visitor<'de>>(self, _: V) -> Result<V::Value, Found> {
        Err(Found(None))
    }

    fn deserialize_struct<V: Visitor<'de>>(
        self,
        _: &'static str,
        fields: &'static [&'static str],
        _: V,
    ) -> Result<V::Value, Found> {
        Err(Found(Some(fields)))
    }

    serde::forward_to_deserialize_any! {
        bool i8 i16 i32 i64 i128 u8 u16 u32 u64 u128 f32 f64 char str string bytes byte_buf
        option unit unit_struct newtype_struct seq tuple tuple_struct map enum identifier
        ignored_any
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
    #[serde(deny_unknown_fields)]
    struct Common {
        #[serde(default)]
        colour: Option<String>,
    }

    #[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
    #[serde(deny_unknown_fields)]
    struct Round {
        radius: f32,
    }

    #[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
    #[serde(deny_unknown_fields)]
    struct Square {
        side: f32,
        #[serde(default)]
        rotate: [f32; 2],
    }

    kinds! {
        enum Thing: "thing" {
            "round" => Round(Round),
            "square" => Square(Square),
        }
    }

    type ThingDesc = Tagged<Common, Thing>;

    fn parse(text: &str) -> Result<ThingDesc, Fault> {
        let doc = DeTable::parse(text).expect("toml");
        let span = doc.span();
        read(Spanned::new(span, DeValue::Table(doc.into_inner())))
    }

    #[test]
    fn keys_are_learnt_from_serde() {
        assert_eq!(struct_fields::<Common>(), &["colour"]);
        assert_eq!(
            kind_fields::<Thing>("square"),
            Some(&["side", "rotate"][..])
        );
        assert_eq!(kind_fields::<Thing>("hexagon"), None);
    }

    #[test]
    fn reads_each_kind_and_round_trips() {
        let t = parse("type = \"square\"\nside = 2\ncolour = \"red\"").expect("square");
        assert!(matches!(t.kind, Thing::Square(Square { side: 2.0, .. })));
        assert_eq!(t.common.colour.as_deref(), Some("red"));
        let v = toml::Value::try_from(&t).expect("serialises");
        assert_eq!(v.get("type").and_then(|v| v.as_str()), Some("square"));
        let back: ThingDesc = v.try_into().expect("reads back");
        assert!(matches!(back.kind, Thing::Square(Square { side: 2.0, .. })));
    }

    #[test]
    fn faults_name_the_key_and_its_span() {
        let text = "type = \"round\"\nradius = 1\nside = 2";
        let f = parse(text).expect_err("side is not a key of round things");
        assert_eq!(f.path, "side");
        assert_eq!(&text[f.span.clone().expect("span")], "side");
        assert!(f.message.contains("unknown field `side` for a round thing"));

        let text = "type = \"square\"\nside = \"big\"";
        let f = parse(text).expect_err("wrong type");
        assert_eq!(f.path, "side");
        assert_eq!(&text[f.span.clone().expect("span")], "\"big\"");

        let text = "type = \"hexagon\"";
        let f = parse(text).expect_err("unknown kind");
        assert_eq!(f.path, "type");
        assert!(f.message.contains("`round`, `square`"), "{}", f.message);

        let f = parse("side = 1").expect_err("no type");
        assert_eq!((f.path.as_str(), f.span.clone()), ("", None));
        let f = parse("type = \"round\"").expect_err("missing radius");
        assert_eq!(f.path, "");
        assert!(
            f.message.contains("missing field `radius`"),
            "{}",
            f.message
        );
    }

    #[test]
    fn the_generic_path_follows_the_same_rules() {
        let v: toml::Value =
            toml::from_str("type = \"round\"\nradius = 1\nrotate = [1, 2]").unwrap();
        let e = ThingDesc::deserialize(v).expect_err("rotate is a square's key");
        assert!(e.to_string().contains("`rotate`"), "{e}");
    }
}
