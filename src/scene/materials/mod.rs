//! `[materials.NAME]`: the loops over material kinds, the checks that blends name existing
//! materials without containing themselves, and building every material once. Each kind's
//! keys, defaults, checks and runtime [`Material`] are in its own file.

mod albedo;
mod blend;
mod conductor;
mod dielectric;
mod glossy;
mod lambert;
mod mirror;
mod texture;

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

pub use blend::BlendDesc;
pub use conductor::{ConductorDesc, Roughness};
pub use dielectric::DielectricDesc;
pub use glossy::GlossyDesc;
pub use lambert::LambertDesc;
pub use mirror::MirrorDesc;
pub use texture::{Decoded, TextureDesc, WeightDesc};

use super::builder::Builder;
use super::check::Checker;
use super::error::SceneError;
use super::spectrum_desc::SpectrumRef;
use super::tagged::{Tagged, kinds};
use crate::material::Material;

/// Keys every material has: none besides `type`.
#[derive(Clone, Debug, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MaterialCommon {}

kinds! {
    /// The kinds of material, by their `type`.
    pub enum MaterialKind: "material" {
        "lambert" => Lambert(LambertDesc),
        "mirror" => Mirror(MirrorDesc),
        "glossy" => Glossy(GlossyDesc),
        "conductor" => Conductor(ConductorDesc),
        "dielectric" => Dielectric(DielectricDesc),
        "blend" => Blend(BlendDesc),
    }
}

/// A `[materials.NAME]` table.
pub type MaterialDesc = Tagged<MaterialCommon, MaterialKind>;

impl MaterialDesc {
    pub fn check(&self, c: &mut Checker, key: &str) {
        match &self.kind {
            MaterialKind::Lambert(m) => m.check(c, key),
            MaterialKind::Mirror(m) => m.check(c, key),
            MaterialKind::Glossy(m) => m.check(c, key),
            MaterialKind::Conductor(m) => m.check(c, key),
            MaterialKind::Dielectric(m) => m.check(c, key),
            MaterialKind::Blend(m) => m.check(c, key),
        }
    }

    /// The materials a blend mixes (none for the other kinds).
    fn parts(&self) -> Vec<&str> {
        match &self.kind {
            MaterialKind::Blend(b) => vec![b.first.as_str(), b.second.as_str()],
            MaterialKind::Lambert(_)
            | MaterialKind::Mirror(_)
            | MaterialKind::Glossy(_)
            | MaterialKind::Conductor(_)
            | MaterialKind::Dielectric(_) => Vec::new(),
        }
    }
}

/// Index of refraction: a spectrum, and a constant in [1, 5].
fn check_ior(c: &mut Checker, key: &str, ior: &SpectrumRef) {
    let key = format!("{key}.ior");
    c.spectrum_ref(&key, ior);
    if let SpectrumRef::Constant(v) = ior {
        c.range(&key, *v, 1.0, 5.0, "in [1, 5]");
    }
}

/// A blend that contains itself (through any chain of blends) has no value: refused.
pub fn check_blends(c: &mut Checker, materials: &BTreeMap<String, MaterialDesc>) {
    for name in materials.keys() {
        if let Some(cycle) = cycle_through(name, materials) {
            c.fail(
                format!("materials.{name}"),
                format!("a blend cannot contain itself: {}", cycle.join(" -> ")),
            );
            return;
        }
    }
}

/// A chain of blend parts from `start` back to `start`, if there is one.
fn cycle_through(start: &str, materials: &BTreeMap<String, MaterialDesc>) -> Option<Vec<String>> {
    // Depth-first over (material, index of its next part to visit).
    let mut stack: Vec<(&str, usize)> = vec![(start, 0)];
    while let Some((name, next)) = stack.last().copied() {
        let parts = materials
            .get(name)
            .map(MaterialDesc::parts)
            .unwrap_or_default();
        let Some(part) = parts.get(next).copied() else {
            stack.pop();
            continue;
        };
        if let Some(top) = stack.last_mut() {
            top.1 += 1;
        }
        if part == start {
            let mut chain: Vec<String> = stack.iter().map(|(n, _)| n.to_string()).collect();
            chain.push(start.to_string());
            return Some(chain);
        }
        // Chains longer than the number of materials repeat one that is not `start`: that
        // material's own check reports it.
        if !stack.iter().any(|(n, _)| *n == part) {
            stack.push((part, 0));
        }
    }
    None
}

/// Every material of `descs` in name order (the order of material ids), each blend from its
/// parts.
pub fn build_all(
    b: &Builder,
    descs: &BTreeMap<String, MaterialDesc>,
) -> Result<Vec<Material>, SceneError> {
    let mut built: BTreeMap<&str, Material> = BTreeMap::new();
    for name in descs.keys() {
        build_into(b, descs, name, &mut built, 0)?;
    }
    Ok(descs
        .keys()
        .filter_map(|name| built.remove(name.as_str()))
        .collect())
}

fn build_into<'a>(
    b: &Builder,
    descs: &'a BTreeMap<String, MaterialDesc>,
    name: &'a str,
    built: &mut BTreeMap<&'a str, Material>,
    depth: usize,
) -> Result<(), SceneError> {
    if built.contains_key(name) {
        return Ok(());
    }
    let key = format!("materials.{name}");
    let Some(desc) = descs.get(name) else {
        return Err(b.source.invalid(&key, "no such material"));
    };
    // Validation refuses cycles; this bound keeps a scene built without it finite.
    if depth > descs.len() {
        return Err(b.source.invalid(&key, "a blend cannot contain itself"));
    }
    let m = match &desc.kind {
        MaterialKind::Lambert(m) => m.build(b, &key)?,
        MaterialKind::Mirror(m) => m.build(b, &key)?,
        MaterialKind::Glossy(m) => m.build(b, &key)?,
        MaterialKind::Conductor(m) => m.build(b, &key)?,
        MaterialKind::Dielectric(m) => m.build(b, &key)?,
        MaterialKind::Blend(m) => {
            let part = |built: &mut BTreeMap<&'a str, Material>, part: &'a str| {
                build_into(b, descs, part, built, depth + 1)?;
                built.get(part).cloned().ok_or_else(|| {
                    b.source
                        .invalid(&key, format!("no material named `{part}`"))
                })
            };
            let first = part(built, &m.first)?;
            let second = part(built, &m.second)?;
            m.build(b, &key, first, second)?
        }
    };
    built.insert(name, m);
    Ok(())
}
