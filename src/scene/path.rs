//! Dotted key paths (`integrator.q`, `shapes.0.radius`) and their positions in a TOML text.

use toml::Spanned;
use toml::de::{DeTable, DeValue};

#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Seg {
    Key(String),
    Index(usize),
}

pub fn parse_path(dotted: &str) -> Vec<Seg> {
    dotted
        .split('.')
        .map(|s| match s.parse::<usize>() {
            Ok(i) => Seg::Index(i),
            Err(_) => Seg::Key(s.to_string()),
        })
        .collect()
}

pub fn display(path: &[Seg]) -> String {
    path.iter()
        .map(|s| match s {
            Seg::Key(k) => k.clone(),
            Seg::Index(i) => i.to_string(),
        })
        .collect::<Vec<_>>()
        .join(".")
}

/// Byte span of the deepest part of `path` present in the document, and whether all of it was found.
pub fn span_of(text: &str, path: &[Seg]) -> Option<std::ops::Range<usize>> {
    let root = DeTable::parse(text).ok()?;
    let root = DeValue::Table(root.into_inner());
    let mut span = None;
    let mut cur = &root;
    for seg in path {
        let next = match (seg, cur) {
            (Seg::Key(k), DeValue::Table(t)) => t
                .iter()
                .find(|(key, _)| key.get_ref().as_ref() == k.as_str())
                .map(|(key, v)| (key.span(), v)),
            (Seg::Index(i), DeValue::Array(a)) => a.get(*i).map(|v| (v.span(), v)),
            _ => None,
        };
        match next {
            Some((s, v)) => {
                span = Some(s);
                cur = v.get_ref();
            }
            None => break,
        }
    }
    span
}

/// The value at `path` in the document, with its span.
pub fn value_at<'a>(text: &'a str, path: &[Seg]) -> Option<Spanned<DeValue<'a>>> {
    let root = DeTable::parse(text).ok()?;
    let span = root.span();
    let mut cur = Spanned::new(span, DeValue::Table(root.into_inner()));
    for seg in path {
        let next = match (seg, cur.into_inner()) {
            (Seg::Key(k), DeValue::Table(t)) => t
                .into_iter()
                .find(|(key, _)| key.get_ref().as_ref() == k.as_str())
                .map(|(_, v)| v),
            (Seg::Index(i), DeValue::Array(a)) => a.into_iter().nth(*i),
            _ => None,
        };
        cur = next?;
    }
    Some(cur)
}

/// 1-based line and column of a byte offset.
pub fn line_col(text: &str, offset: usize) -> (usize, usize) {
    let offset = offset.min(text.len());
    let before = &text[..offset];
    let line = before.matches('\n').count() + 1;
    let col = before.rfind('\n').map_or(offset, |p| offset - p - 1) + 1;
    (line, col)
}
