//! Image textures in a scene: `texture = "file.png"` or, with options,
//! `texture = { file = "wood.exr", colour_space = "linear", wrap = "clamp" }`.

use std::cell::Cell;
use std::fmt;
use std::path::Path;
use std::sync::Arc;

use serde::de::value::MapAccessDeserializer;
use serde::de::{MapAccess, Visitor};
use serde::{Deserialize, Deserializer, Serialize};

use crate::material::{Encoding, Texture, Wrap};
use crate::scene::builder::Builder;
use crate::scene::check::Checker;
use crate::scene::error::SceneError;
use crate::spectrum::Spectrum;

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TextureDesc {
    /// PNG or OpenEXR file, relative to the scene file.
    pub file: String,
    /// How stored values map to linear RGB; default: `srgb` for PNG, `linear` for EXR.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub colour_space: Option<Encoding>,
    /// Lookups outside [0, 1]: `repeat` (default) or `clamp`.
    #[serde(default)]
    pub wrap: Wrap,
    /// Texels already decoded (a glTF's textures, which may live inside the glTF file; `file`
    /// then names the image for messages). Never read from a scene file.
    #[serde(skip)]
    pub decoded: Option<Decoded>,
}

/// Decoded linear RGB texels: width, height, texels (top row first).
#[derive(Clone)]
pub struct Decoded(pub Arc<(usize, usize, Vec<[f32; 3]>)>);

impl fmt::Debug for Decoded {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "Decoded({} x {})", self.0.0, self.0.1)
    }
}

impl PartialEq for Decoded {
    fn eq(&self, other: &Self) -> bool {
        Arc::ptr_eq(&self.0, &other.0)
    }
}

/// What loading a texture saw of its linear RGB values.
pub struct Loaded {
    pub texture: Texture,
    /// Largest RGB component.
    pub max: f32,
    /// Smallest RGB component.
    pub min: f32,
}

impl TextureDesc {
    fn file_only(file: &str) -> TextureDesc {
        TextureDesc {
            file: file.to_string(),
            colour_space: None,
            wrap: Wrap::default(),
            decoded: None,
        }
    }

    pub fn check(&self, c: &mut Checker, key: &str) {
        if self.decoded.is_some() {
            return;
        }
        c.texture(key, &self.file);
    }

    pub fn encoding(&self, path: &Path) -> Encoding {
        self.colour_space
            .unwrap_or_else(|| Encoding::default_for(path))
    }

    /// Decodes the file to linear RGB and upsamples each texel with `to_spectrum`. A texel that
    /// is not a finite number is refused: it would put NaN into the image.
    pub fn load(
        &self,
        b: &Builder,
        key: &str,
        n_bins: usize,
        to_spectrum: &dyn Fn([f32; 3]) -> Spectrum,
    ) -> Result<Loaded, SceneError> {
        let path = b.source.resolve(&self.file);
        let (lo, hi) = (Cell::new(f32::INFINITY), Cell::new(f32::NEG_INFINITY));
        let finite = Cell::new(true);
        let seen = |rgb: [f32; 3]| {
            for c in rgb {
                finite.set(finite.get() && c.is_finite());
                lo.set(lo.get().min(c));
                hi.set(hi.get().max(c));
            }
            to_spectrum(rgb)
        };
        let texture = match &self.decoded {
            Some(Decoded(d)) => Texture::from_rgb(d.0, d.1, &d.2, n_bins, &seen),
            None => Texture::load_encoded(&path, self.encoding(&path), n_bins, &seen)
                .map_err(|e| b.source.invalid(key, e.to_string()))?,
        };
        if !finite.get() {
            return Err(b.source.invalid(
                key,
                format!(
                    "{}: holds values that are not finite numbers",
                    path.display()
                ),
            ));
        }
        Ok(Loaded {
            texture: texture.with_wrap(self.wrap),
            max: hi.get(),
            min: lo.get(),
        })
    }
}

/// For `#[serde(deserialize_with)]`: a texture given as a file name or as a table.
pub fn optional<'de, D: Deserializer<'de>>(d: D) -> Result<Option<TextureDesc>, D::Error> {
    d.deserialize_any(FileOrTable).map(Some)
}

struct FileOrTable;

impl<'de> Visitor<'de> for FileOrTable {
    type Value = TextureDesc;

    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("a file name or a table { file = .., colour_space = .., wrap = .. }")
    }

    fn visit_str<E: serde::de::Error>(self, v: &str) -> Result<TextureDesc, E> {
        Ok(TextureDesc::file_only(v))
    }

    fn visit_map<A: MapAccess<'de>>(self, map: A) -> Result<TextureDesc, A::Error> {
        // The struct's own impl over the same map keeps each key's path and position.
        TextureDesc::deserialize(MapAccessDeserializer::new(map))
    }
}

/// A blend's weight: a constant in [0, 1] or a texture (its linear luminance).
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(untagged)]
pub enum WeightDesc {
    Constant(f32),
    Texture(TextureDesc),
}

impl<'de> Deserialize<'de> for WeightDesc {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        d.deserialize_any(WeightVisitor)
    }
}

struct WeightVisitor;

impl<'de> Visitor<'de> for WeightVisitor {
    type Value = WeightDesc;

    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("a number in [0, 1], or a texture (a file name or a table { file = .. })")
    }

    fn visit_f64<E: serde::de::Error>(self, v: f64) -> Result<WeightDesc, E> {
        Ok(WeightDesc::Constant(v as f32))
    }

    fn visit_i64<E: serde::de::Error>(self, v: i64) -> Result<WeightDesc, E> {
        Ok(WeightDesc::Constant(v as f32))
    }

    fn visit_u64<E: serde::de::Error>(self, v: u64) -> Result<WeightDesc, E> {
        Ok(WeightDesc::Constant(v as f32))
    }

    fn visit_str<E: serde::de::Error>(self, v: &str) -> Result<WeightDesc, E> {
        FileOrTable.visit_str(v).map(WeightDesc::Texture)
    }

    fn visit_map<A: MapAccess<'de>>(self, map: A) -> Result<WeightDesc, A::Error> {
        FileOrTable.visit_map(map).map(WeightDesc::Texture)
    }
}
