//! The checks that scene sections and kinds share: ranges, vectors, files, spectrum references
//! and names of other sections' entries. Each records a [`Problem`] at its dotted key.

use std::collections::BTreeMap;
use std::path::Path;

use super::source::Source;
use super::spectrum_desc::{LinesDesc, RgbKind, SpectrumDesc, SpectrumRef};
use crate::geometry::MAX_LENGTH;

/// One problem: the dotted key it is about and what is wrong.
#[derive(Clone, Debug, PartialEq)]
pub struct Problem {
    pub key: String,
    pub message: String,
}

/// Largest texture accepted, checked from the image header before any decoding.
pub const MAX_TEXTURE_SIDE: u32 = 16_384;
pub const MAX_TEXTURE_PIXELS: u64 = 1 << 26;

/// Whether `name` is a built-in spectrum (`D65`, `colorchecker:dark_skin`, ...): its part before
/// any `:column` names a built-in table.
pub fn is_builtin(name: &str) -> bool {
    let base = name.split(':').next().unwrap_or(name);
    crate::spectrum::builtin_table(base).is_some()
}

fn builtin_list() -> String {
    crate::spectrum::builtin_names()
        .collect::<Vec<_>>()
        .join(", ")
}

/// The names defined in a scene's sections, which other tables refer to.
pub struct Names<'a> {
    pub spectra: &'a BTreeMap<String, SpectrumDesc>,
    pub materials: Vec<&'a str>,
    pub media: Vec<&'a str>,
}

pub struct Checker<'a> {
    pub source: Source<'a>,
    pub names: Names<'a>,
    pub problems: Vec<Problem>,
}

impl<'a> Checker<'a> {
    pub fn new(source: Source<'a>, names: Names<'a>) -> Self {
        Self {
            source,
            names,
            problems: Vec::new(),
        }
    }

    pub fn fail(&mut self, key: impl Into<String>, message: impl Into<String>) {
        self.problems.push(Problem {
            key: key.into(),
            message: message.into(),
        });
    }

    pub fn positive(&mut self, key: &str, v: f64) {
        if !(v.is_finite() && v > 0.0) {
            self.fail(key, format!("must be a finite number > 0, got {v}"));
        }
    }

    pub fn non_negative(&mut self, key: &str, v: f64) {
        if !(v.is_finite() && v >= 0.0) {
            self.fail(key, format!("must be a finite number >= 0, got {v}"));
        }
    }

    pub fn range(&mut self, key: &str, v: f64, lo: f64, hi: f64, what: &str) {
        if !(v.is_finite() && v >= lo && v <= hi) {
            self.fail(key, format!("must be {what}, got {v}"));
        }
    }

    /// As [`Self::range`] for a value stored as f32: compared with bounds rounded to f32, so a
    /// documented bound (1e-4) written in the file is accepted.
    pub fn range_f32(&mut self, key: &str, v: f32, lo: f32, hi: f32, what: &str) {
        if !(v.is_finite() && v >= lo && v <= hi) {
            self.fail(key, format!("must be {what}, got {v}"));
        }
    }

    /// A positive quantity with an upper bound (`why` says where the bound comes from).
    pub fn bounded(&mut self, key: &str, v: f32, max: f32, unit: &str, why: &str) {
        self.positive(key, v as f64);
        if v.is_finite() && v > max {
            self.fail(key, format!("{v} {unit} is above the {max:e} {unit} {why}"));
        }
    }

    /// A length (a size, a radius), m: positive and within what the geometry holds.
    pub fn length(&mut self, key: &str, v: f32) {
        self.positive(key, v as f64);
        self.within_geometry(key, v);
    }

    /// A length or coordinate no larger than [`MAX_LENGTH`] in magnitude (its other checks are
    /// the caller's): beyond it f32 geometry overflows.
    pub fn within_geometry(&mut self, key: &str, v: f32) {
        if v.is_finite() && v.abs() > MAX_LENGTH {
            self.fail(
                key,
                format!(
                    "{v:e} m is beyond the {MAX_LENGTH:e} m that brume's single-precision \
                     geometry holds (larger lengths overflow areas, normals and bounding boxes)"
                ),
            );
        }
    }

    /// A position, m: finite coordinates within what the geometry holds.
    pub fn point(&mut self, key: &str, v: [f32; 3]) {
        self.vector(key, v);
        let largest = v.iter().map(|c| c.abs()).fold(0.0, f32::max);
        self.within_geometry(key, largest);
    }

    pub fn vector(&mut self, key: &str, v: [f32; 3]) {
        if v.iter().any(|c| !c.is_finite()) {
            self.fail(key, "must hold finite numbers");
        }
    }

    pub fn direction(&mut self, key: &str, v: [f32; 3]) {
        self.vector(key, v);
        if v.iter().all(|c| *c == 0.0) {
            self.fail(key, "must not be the zero vector");
        }
    }

    pub fn file(&mut self, key: &str, rel: &str) {
        let p = self.source.resolve(rel);
        if !p.is_file() {
            self.fail(key, super::source::not_a_file(&p));
        }
    }

    /// A texture file: present, readable as an image, and of sane size, judged from its header
    /// so that a forged or absurd file is refused before its pixels are allocated.
    pub fn texture(&mut self, key: &str, rel: &str) {
        let p = self.source.resolve(rel);
        if !p.is_file() {
            return self.fail(key, super::source::not_a_file(&p));
        }
        match image_size(&p) {
            Err(e) => self.fail(key, format!("{}: not a readable image: {e}", p.display())),
            Ok((w, h)) => {
                if w == 0
                    || h == 0
                    || w > MAX_TEXTURE_SIDE
                    || h > MAX_TEXTURE_SIDE
                    || w as u64 * h as u64 > MAX_TEXTURE_PIXELS
                {
                    self.fail(
                        key,
                        format!(
                            "{}: a {w}x{h} texture is outside the supported 1..={MAX_TEXTURE_SIDE} \
                             pixels per side ({MAX_TEXTURE_PIXELS} pixels in all)",
                            p.display()
                        ),
                    );
                }
            }
        }
    }

    /// A spectrum reference that is not an emission: spectral lines are refused.
    pub fn spectrum_ref(&mut self, key: &str, r: &SpectrumRef) {
        match r {
            SpectrumRef::Lines(_) => self.fail(
                key,
                "spectral lines (`line`, `lines`) are an emission: give them as a light's \
                 `spectrum` or a shape's `emit`",
            ),
            SpectrumRef::Constant(v) => self.non_negative(key, *v),
            SpectrumRef::Rgb(rgb) => {
                if rgb.iter().any(|c| !(c.is_finite() && *c >= 0.0)) {
                    self.fail(key, "RGB components must be finite and >= 0");
                }
            }
            SpectrumRef::Named(n) => {
                if !self.names_spectrum(n) {
                    self.fail(
                        key,
                        format!(
                            "`{n}` is not a spectrum in [spectra], a built-in ({}), or a CSV file",
                            builtin_list()
                        ),
                    );
                }
            }
        }
    }

    /// Whether `name` is a spectrum in [spectra], a built-in, or a CSV file (before any
    /// `:column`).
    pub fn names_spectrum(&self, name: &str) -> bool {
        let file = name.split(':').next().unwrap_or(name);
        self.names.spectra.contains_key(name)
            || is_builtin(name)
            || self.source.resolve(file).is_file()
    }

    /// An emission spectrum (a light's `spectrum`, a shape's `emit`): any reference, lines
    /// included. Whether lines lie in the film's range is checked with the spectral grid.
    pub fn emission_ref(&mut self, key: &str, r: &SpectrumRef) {
        match r {
            SpectrumRef::Lines(l) => self.lines(key, l),
            SpectrumRef::Constant(_) | SpectrumRef::Named(_) | SpectrumRef::Rgb(_) => {
                self.spectrum_ref(key, r)
            }
        }
    }

    fn lines(&mut self, key: &str, l: &LinesDesc) {
        if l.line.is_some() == l.lines.is_some() {
            return self.fail(
                key,
                "give either `line = <nm>` or `lines = [[<nm>, <power>], ...]`",
            );
        }
        let entries = l.entries();
        if entries.is_empty() {
            return self.fail(format!("{key}.lines"), "needs at least one line");
        }
        for e in &entries {
            if !(e.lambda.is_finite() && e.lambda > 0.0) {
                let message = format!(
                    "a line's wavelength must be finite and > 0 nm, got {}",
                    e.lambda
                );
                self.fail(format!("{key}.{}", e.lambda_key), message);
            }
            if let Some(pk) = &e.power_key {
                self.non_negative(&format!("{key}.{pk}"), e.power);
            }
        }
        if entries.iter().all(|e| e.power == 0.0) {
            self.fail(format!("{key}.lines"), "the lines' powers are all zero");
        }
    }

    /// A reflectance (an albedo): a spectrum reference whose constant or RGB form is at most 1
    /// unless the material allows energy gain. Named spectra are checked once resolved.
    pub fn reflectance_ref(&mut self, key: &str, r: &SpectrumRef, allow_gain: bool) {
        self.spectrum_ref(key, r);
        let max = match r {
            SpectrumRef::Constant(v) => *v,
            SpectrumRef::Rgb(rgb) => rgb.iter().copied().fold(0.0, f64::max),
            SpectrumRef::Named(_) | SpectrumRef::Lines(_) => return,
        };
        if max > 1.0 && !allow_gain {
            self.fail(key, above_one(max));
        }
    }

    pub fn named_spectrum(&mut self, key: &str, s: &SpectrumDesc) {
        let sources = s.sources();
        if sources.len() != 1 {
            self.fail(
                key,
                format!(
                    "give exactly one of file, builtin, value, rgb, power_law (found {})",
                    if sources.is_empty() {
                        "none".to_string()
                    } else {
                        sources.join(", ")
                    }
                ),
            );
        }
        if let Some(f) = &s.file
            && !is_builtin(f)
        {
            // `file.csv:column` names a column of the file.
            let path = match f.rsplit_once(':') {
                Some((p, _)) if !self.source.resolve(f).is_file() => p,
                _ => f,
            };
            self.file(&format!("{key}.file"), path);
        }
        if let Some(b) = &s.builtin
            && !is_builtin(b)
        {
            self.fail(
                format!("{key}.builtin"),
                format!("unknown built-in spectrum `{b}`"),
            );
        }
        if let Some(v) = s.value {
            self.non_negative(&format!("{key}.value"), v);
        }
        if let Some(rgb) = s.rgb
            && rgb.iter().any(|c| !(c.is_finite() && *c >= 0.0))
        {
            self.fail(
                format!("{key}.rgb"),
                "RGB components must be finite and >= 0",
            );
        }
        // The reflectance upsampling is bounded to [0, 1]: a larger component would be clipped
        // without a word.
        if let Some(rgb) = s.rgb
            && s.rgb_kind == RgbKind::Reflectance
            && rgb.iter().any(|c| *c > 1.0)
        {
            self.fail(
                format!("{key}.rgb"),
                "a reflectance RGB (the default `rgb_kind`) has components in [0, 1]; use \
                 rgb_kind = \"unbounded\" for coefficients or \"emission\" for lights",
            );
        }
        if let Some(p) = &s.power_law {
            self.non_negative(&format!("{key}.power_law.k"), p.k);
            self.range(
                &format!("{key}.power_law.p"),
                p.p,
                -20.0,
                20.0,
                "in [-20, 20]",
            );
            self.positive(&format!("{key}.power_law.lambda_ref"), p.lambda_ref);
        }
        if let Some(sc) = s.scale {
            self.non_negative(&format!("{key}.scale"), sc);
        }
    }

    /// `name` is a material of the scene.
    pub fn material(&mut self, key: &str, name: &str) {
        if let Some(m) = undefined(name, &self.names.materials, "material") {
            self.fail(key, m);
        }
    }

    /// `name` is a medium of the scene.
    pub fn medium(&mut self, key: &str, name: &str) {
        if let Some(m) = undefined(name, &self.names.media, "medium") {
            self.fail(key, m);
        }
    }
}

/// The message for a reference to a `what` that is not among `known`.
fn undefined(name: &str, known: &[&str], what: &str) -> Option<String> {
    (!known.contains(&name)).then(|| {
        format!(
            "no {what} named `{name}` (defined: {})",
            if known.is_empty() {
                "none".into()
            } else {
                known.join(", ")
            }
        )
    })
}

/// The message for a reflectance above one.
pub fn above_one(max: f64) -> String {
    format!(
        "a reflectance of {max} is above 1: the surface would reflect more light than it \
         receives; set `allow_energy_gain = true` on the material if that is meant"
    )
}

/// Width and height of an image file from its header: OpenEXR through `exr`, the rest
/// through `image`.
fn image_size(p: &Path) -> Result<(u32, u32), String> {
    let exr = p
        .extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case("exr"));
    if exr {
        let meta = exr::meta::MetaData::read_from_file(p, false).map_err(|e| e.to_string())?;
        let header = meta.headers.first().ok_or("no image in the file")?;
        let size = header.layer_size;
        let side = |v: usize| u32::try_from(v).unwrap_or(u32::MAX);
        return Ok((side(size.width()), side(size.height())));
    }
    image::ImageReader::open(p)
        .and_then(|r| r.with_guessed_format())
        .map_err(|e| e.to_string())
        .and_then(|r| r.into_dimensions().map_err(|e| e.to_string()))
}
