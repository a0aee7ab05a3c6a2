//! glTF materials as brume materials: the metallic-roughness model becomes `lambert`
//! (metallic 0), the metal of [`metal`] (metallic 1) or a `blend` of the two by `metallic`;
//! `KHR_materials_transmission` with `KHR_materials_ior` becomes `dielectric`; `emissive`
//! (times `KHR_materials_emissive_strength`) becomes the luminance of an emitting surface.

use std::collections::BTreeMap;
use std::sync::Arc;

use super::Notes;
use super::file::{Fault, GltfFile, percent_decoded, read_bounded};
use crate::material::{Encoding, Texture, Wrap};
use crate::scene::check::{MAX_TEXTURE_PIXELS, MAX_TEXTURE_SIDE};
use crate::scene::desc::{
    BlendDesc, ConductorDesc, DielectricDesc, LambertDesc, MaterialCommon, MaterialDesc,
    MaterialKind, SpectrumRef, TextureDesc, WeightDesc,
};
use crate::scene::materials::{Decoded, Roughness};

/// What a primitive takes from its glTF material: the scene material it is made of and, for
/// an emissive material, the colour and luminance (cd/m²) it emits.
#[derive(Clone, Debug)]
pub struct Surface {
    pub material: String,
    pub emit: Option<([f64; 3], f32)>,
}

/// The materials of one glTF file, made once each as primitives ask for them.
pub struct Materials<'f> {
    file: &'f GltfFile,
    /// Prefix of the scene material names made (`gltf<shape>:`).
    prefix: String,
    /// Display name of the glTF file, for texture names in messages.
    shown: String,
    pub made: BTreeMap<String, MaterialDesc>,
    surfaces: BTreeMap<Option<usize>, Surface>,
    textures: BTreeMap<usize, Decoded>,
}

impl<'f> Materials<'f> {
    pub fn new(file: &'f GltfFile, shape: usize, shown: String) -> Self {
        Materials {
            file,
            prefix: format!("gltf{shape}:"),
            shown,
            made: BTreeMap::new(),
            surfaces: BTreeMap::new(),
            textures: BTreeMap::new(),
        }
    }

    /// The surface of glTF material `m` (None: the glTF default material).
    pub fn surface(&mut self, m: gltf::Material, notes: &mut Notes) -> Result<Surface, Fault> {
        if let Some(s) = self.surfaces.get(&m.index()) {
            return Ok(s.clone());
        }
        let at = match m.index() {
            Some(i) => format!("materials[{i}]"),
            None => "the default material".to_string(),
        };
        let stem = match (m.index(), m.name()) {
            (Some(i), Some(n)) => format!("{}{i}:{}", self.prefix, clean(n)),
            (Some(i), None) => format!("{}{i}", self.prefix),
            (None, _) => format!("{}default", self.prefix),
        };
        note_ignored(&m, &at, notes);
        let kind = if let Some(t) = m.transmission() {
            if t.transmission_factor() < 1.0 {
                notes.add("transmissionFactor below 1 (taken as 1)", &at);
            }
            let ior = m.ior().unwrap_or(1.5);
            if !(1.0..=5.0).contains(&ior) {
                return Err(Fault::at(
                    format!("{at}.extensions.KHR_materials_ior.ior"),
                    format!("{ior} is outside the [1, 5] brume accepts"),
                ));
            }
            MaterialKind::Dielectric(DielectricDesc {
                ior: SpectrumRef::Constant(ior as f64),
            })
        } else {
            self.metallic_roughness(&m, &at, &stem, notes)?
        };
        self.made.insert(stem.clone(), tagged(kind));
        let surface = Surface {
            material: stem,
            emit: emission(&m, &at)?,
        };
        self.surfaces.insert(m.index(), surface.clone());
        Ok(surface)
    }

    /// Lambert, the metal, or their blend by `metallic` (glTF's own mix of the two lobes).
    fn metallic_roughness(
        &mut self,
        m: &gltf::Material,
        at: &str,
        stem: &str,
        notes: &mut Notes,
    ) -> Result<MaterialKind, Fault> {
        let pbr = m.pbr_metallic_roughness();
        let at = format!("{at}.pbrMetallicRoughness");
        let [r, g, b, alpha] = pbr.base_color_factor();
        let rgb = [r, g, b];
        if rgb.iter().any(|c| !(0.0..=1.0).contains(c)) {
            return Err(Fault::at(
                format!("{at}.baseColorFactor"),
                format!("{rgb:?} is outside [0, 1]"),
            ));
        }
        if alpha < 1.0 {
            notes.add("base colour alpha below 1 (surfaces are opaque)", &at);
        }
        let texture = match pbr.base_color_texture() {
            Some(info) => Some(self.texture(&info, &format!("{at}.baseColorTexture"), notes)?),
            None => None,
        };
        let metallic = pbr.metallic_factor();
        let alpha_ggx = pbr.roughness_factor().clamp(0.0, 1.0).powi(2);
        let albedo = (rgb != [1.0; 3]).then(|| SpectrumRef::Rgb(rgb.map(|c| c as f64)));
        let diffuse = MaterialKind::Lambert(LambertDesc {
            albedo: Some(albedo.clone().unwrap_or(SpectrumRef::Constant(1.0))),
            texture,
            allow_energy_gain: false,
        });
        if metallic <= 0.0 {
            return Ok(diffuse);
        }
        let metal = metal(rgb, alpha_ggx);
        if metallic >= 1.0 {
            return Ok(metal);
        }
        let (first, second) = (format!("{stem}:diffuse"), format!("{stem}:metal"));
        self.made.insert(first.clone(), tagged(diffuse));
        self.made.insert(second.clone(), tagged(metal));
        Ok(MaterialKind::Blend(BlendDesc {
            first,
            second,
            weight: WeightDesc::Constant(metallic),
        }))
    }

    /// A base colour texture, decoded once per glTF texture.
    fn texture(
        &mut self,
        info: &gltf::texture::Info,
        at: &str,
        notes: &mut Notes,
    ) -> Result<TextureDesc, Fault> {
        if info.tex_coord() != 0 {
            notes.add(
                "texture coordinates other than TEXCOORD_0 (TEXCOORD_0 used)",
                at,
            );
        }
        let t = info.texture();
        let sampler = t.sampler();
        use gltf::texture::WrappingMode as W;
        let wrap = match (sampler.wrap_s(), sampler.wrap_t()) {
            (W::ClampToEdge, W::ClampToEdge) => Wrap::Clamp,
            (W::Repeat, W::Repeat) => Wrap::Repeat,
            _ => {
                notes.add("mirrored or mixed texture wrapping (repeat used)", at);
                Wrap::Repeat
            }
        };
        let image = t.source();
        let decoded = match self.textures.get(&image.index()) {
            Some(d) => d.clone(),
            None => {
                let d = self.decode(&image)?;
                self.textures.insert(image.index(), d.clone());
                d
            }
        };
        Ok(TextureDesc {
            file: format!("{}: images[{}]", self.shown, image.index()),
            colour_space: Some(Encoding::Srgb),
            wrap,
            decoded: Some(decoded),
        })
    }

    /// The image's texels as linear RGB (glTF colour textures are sRGB-encoded).
    fn decode(&self, image: &gltf::Image) -> Result<Decoded, Fault> {
        let at = format!("images[{}]", image.index());
        let bytes: Vec<u8> = match image.source() {
            gltf::image::Source::View { view, .. } => {
                let start = view.offset();
                // `open` checked that every view lies inside its buffer.
                self.file.buffers[view.buffer().index()][start..start + view.length()].to_vec()
            }
            gltf::image::Source::Uri { uri, .. } if uri.starts_with("data:") => {
                let source = gltf::buffer::Source::Uri(uri);
                gltf::buffer::Data::from_source(source, Some(&self.file.dir))
                    .map_err(|e| Fault::at(&at, format!("data URI: {e}")))?
                    .0
            }
            gltf::image::Source::Uri { uri, .. } => {
                let path = percent_decoded(uri).map_err(|m| Fault::at(&at, m))?;
                read_bounded(&self.file.dir.join(path)).map_err(|m| Fault::at(&at, m))?
            }
        };
        let max = MAX_TEXTURE_PIXELS.min(MAX_TEXTURE_SIDE as u64 * MAX_TEXTURE_SIDE as u64);
        let (w, h, rgb) = Texture::decode_memory(&bytes, Encoding::Srgb, max)
            .map_err(|e| Fault::at(&at, format!("cannot decode the image: {e}")))?;
        if w > MAX_TEXTURE_SIDE as usize || h > MAX_TEXTURE_SIDE as usize {
            return Err(Fault::at(
                &at,
                format!("{w} x {h} pixels: a side is too long"),
            ));
        }
        Ok(Decoded(Arc::new((w, h, rgb))))
    }
}

/// The material of a metallic surface: a `conductor` whose Schlick `f0` is the base colour
/// and whose GGX alpha is glTF's perceptual roughness squared (as glTF's own BRDF defines it).
fn metal(f0: [f32; 3], alpha: f32) -> MaterialKind {
    MaterialKind::Conductor(ConductorDesc {
        roughness: Roughness::Isotropic(alpha),
        eta: None,
        k: None,
        f0: Some(SpectrumRef::Rgb(f0.map(|c| c as f64))),
    })
}

/// The emitted colour (largest component 1) and luminance in cd/m² of an emissive material:
/// `emissiveFactor` times `KHR_materials_emissive_strength`, white (1, 1, 1) at strength 1
/// being 1 cd/m²; a colour's luminance is its Rec. 709 relative luminance.
pub(super) fn emission(m: &gltf::Material, at: &str) -> Result<Option<([f64; 3], f32)>, Fault> {
    let e = m.emissive_factor();
    let strength = m.emissive_strength().unwrap_or(1.0);
    let bad = e.iter().any(|c| !(c.is_finite() && *c >= 0.0));
    if bad || !(strength.is_finite() && strength >= 0.0) {
        return Err(Fault::at(
            format!("{at}.emissiveFactor"),
            format!("{e:?} at strength {strength}: not a colour >= 0 and a finite strength"),
        ));
    }
    let max = e[0].max(e[1]).max(e[2]);
    if max <= 0.0 || strength == 0.0 {
        return Ok(None);
    }
    let y = 0.2126 * e[0] + 0.7152 * e[1] + 0.0722 * e[2];
    let colour = e.map(|c| (c / max) as f64);
    Ok(Some((colour, y * strength)))
}

/// What a material has that brume does not render, noted once per kind of feature.
fn note_ignored(m: &gltf::Material, at: &str, notes: &mut Notes) {
    let pbr = m.pbr_metallic_roughness();
    let features = [
        (m.normal_texture().is_some(), "normalTexture (ignored)"),
        (
            m.occlusion_texture().is_some(),
            "occlusionTexture (ignored)",
        ),
        (
            m.emissive_texture().is_some(),
            "emissiveTexture (emissiveFactor used)",
        ),
        (
            pbr.metallic_roughness_texture().is_some(),
            "metallicRoughnessTexture (the factors used)",
        ),
        (
            m.alpha_mode() != gltf::material::AlphaMode::Opaque,
            "alphaMode MASK or BLEND (surfaces are opaque)",
        ),
    ];
    for (present, what) in features {
        if present {
            notes.add(what, at);
        }
    }
}

fn tagged(kind: MaterialKind) -> MaterialDesc {
    MaterialDesc {
        common: MaterialCommon {},
        kind,
    }
}

/// A glTF name as part of a scene material name: letters, digits, `-` and `_` kept.
pub fn clean(name: &str) -> String {
    name.chars()
        .map(|c| {
            if c.is_alphanumeric() || c == '-' || c == '_' {
                c
            } else {
                '_'
            }
        })
        .collect()
}
