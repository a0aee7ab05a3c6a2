//! From a validated description to the runtime scene the integrator traces.

use std::collections::BTreeMap;
use std::sync::Arc;

use glam::{Vec2, Vec3};

use super::LoadedScene;
use super::desc::{LightKind, MaterialKind, ShapeKindDesc, SpectrumRef};
use super::error::{KeyText, Origin, SceneError};
use super::spectra::SpectrumResolver;
use crate::camera::Camera;
use crate::geometry::{self, Geometry, ShapeKind, Transform};
use crate::integrator::Integrator;
use crate::light::{Light, LightSet};
use crate::material::{Albedo, Material, Texture};
use crate::medium::HomogeneousMedium;
use crate::scene::desc::Projection;
use crate::spectrum::Spectrum;
use crate::world::Scene;

fn err(scene: &LoadedScene, key: String, message: String) -> SceneError {
    SceneError::Invalid {
        origin: Origin::File {
            file: scene.file.clone(),
            line: None,
        },
        key: KeyText(key),
        message,
    }
}

fn v3(a: [f32; 3]) -> Vec3 {
    Vec3::from_array(a)
}

pub fn build(scene: &LoadedScene) -> Result<Scene, SceneError> {
    let d = &scene.desc;
    let grid = d.film.grid();
    let n = grid.n;
    let spectra = SpectrumResolver::new(scene, grid);

    // Resolve every named spectrum once, so that a bad file is reported even if unused.
    for name in d.spectra.keys() {
        spectra.unbounded(
            &SpectrumRef::Named(name.clone()),
            &format!("spectra.{name}"),
        )?;
    }
    let media_ids: BTreeMap<&str, u32> = d
        .media
        .keys()
        .enumerate()
        .map(|(i, k)| (k.as_str(), i as u32))
        .collect();
    let media = d
        .media
        .iter()
        .map(|(name, m)| {
            let key = format!("media.{name}");
            let ss = spectra.unbounded(&m.sigma_s, &format!("{key}.sigma_s"))?;
            let sa = spectra.unbounded(&m.sigma_a, &format!("{key}.sigma_a"))?;
            HomogeneousMedium::new(&ss, &sa, m.g, n)
                .map_err(|e| err(scene, key.clone(), e.to_string()))
        })
        .collect::<Result<Vec<_>, SceneError>>()?;

    let material_ids: BTreeMap<&str, u32> = d
        .materials
        .keys()
        .enumerate()
        .map(|(i, k)| (k.as_str(), i as u32))
        .collect();
    let materials = d
        .materials
        .iter()
        .map(|(name, m)| {
            let key = format!("materials.{name}");
            let albedo = |what: &str| -> Result<Spectrum, SceneError> {
                match &m.albedo {
                    Some(a) => spectra.reflectance(a, &format!("{key}.{what}")),
                    None => Ok(Spectrum::splat(1.0, n)),
                }
            };
            // A texture multiplies the albedo: fold the albedo into each texel.
            let albedo_value = albedo("albedo")?;
            let texture = match &m.texture {
                Some(t) => {
                    let path = scene.resolve(t);
                    // Surfaces a broken upsampling table as an error before texels are converted.
                    spectra.reflectance(&SpectrumRef::Rgb([0.5; 3]), &format!("{key}.texture"))?;
                    let convert = |rgb: [f32; 3]| spectra.rgb_reflectance(rgb) * albedo_value;
                    let tex = Texture::load(&path, n, &convert)
                        .map_err(|e| err(scene, format!("{key}.texture"), e.to_string()))?;
                    Some(Arc::new(tex))
                }
                None => None,
            };
            let surface: Albedo = match texture {
                Some(t) => t.into(),
                None => albedo_value.into(),
            };
            let ior = match &m.ior {
                Some(i) => spectra.unbounded(i, &format!("{key}.ior"))?,
                None => Spectrum::splat(1.5, n),
            };
            Ok(match m.kind {
                MaterialKind::Lambert => Material::Lambert { albedo: surface },
                MaterialKind::Mirror => Material::mirror(albedo_value),
                MaterialKind::Glossy => {
                    Material::glossy(surface, ior[0], m.roughness.unwrap_or(0.1), n)
                }
                MaterialKind::Dielectric => Material::dielectric(ior, n),
            })
        })
        .collect::<Result<Vec<_>, SceneError>>()?;

    let outside = d.medium.as_deref().and_then(|m| media_ids.get(m).copied());
    let mut shapes = Vec::with_capacity(d.shapes.len());
    let mut area_lights = Vec::new();
    for (i, s) in d.shapes.iter().enumerate() {
        let key = format!("shapes.{i}");
        let kind = match s.kind {
            ShapeKindDesc::Quad => {
                let v = s.size.clone().unwrap_or_default();
                ShapeKind::Quad {
                    size: Vec2::new(v[0], v[1]),
                }
            }
            ShapeKindDesc::Box => {
                let v = s.size.clone().unwrap_or_default();
                ShapeKind::Box {
                    size: Vec3::new(v[0], v[1], v[2]),
                }
            }
            ShapeKindDesc::Sphere => ShapeKind::Sphere {
                radius: s.radius.unwrap_or(1.0),
            },
            ShapeKindDesc::Disc => ShapeKind::Disc {
                radius: s.radius.unwrap_or(1.0),
            },
            ShapeKindDesc::Mesh => {
                let file = s.file.clone().unwrap_or_default();
                geometry::load_obj(&scene.resolve(&file))
                    .map_err(|e| err(scene, format!("{key}.file"), e.to_string()))?
            }
        };
        let light = match &s.emit {
            Some(e) => {
                let radiance = spectra.emission(e, &format!("{key}.emit"))? * s.emit_scale;
                area_lights.push((i as u32, radiance));
                Some((area_lights.len() - 1) as u32)
            }
            None => None,
        };
        let t = &s.transform;
        shapes.push(geometry::ShapeDesc {
            kind,
            transform: Transform::new(v3(t.translate), v3(t.rotate), v3(t.scale)),
            material: s
                .material
                .as_deref()
                .and_then(|m| material_ids.get(m).copied()),
            interior: s
                .interior
                .as_deref()
                .and_then(|m| media_ids.get(m).copied()),
            exterior: match &s.exterior {
                Some(m) => media_ids.get(m.as_str()).copied(),
                None => outside,
            },
            light,
        });
    }
    let mut open = vec![true; media.len()];
    for s in &shapes {
        if s.material.is_some() {
            for m in [s.interior, s.exterior].into_iter().flatten() {
                open[m as usize] = false;
            }
        }
    }
    if let Some(m) = outside {
        // A medium filling all space has no outside to gather from.
        open[m as usize] = false;
    }
    let open_media = open.iter().any(|&o| o);
    let geometry = Geometry::new(shapes).map_err(|e| err(scene, "shapes".into(), e.to_string()))?;

    let mut lights: Vec<Light> = area_lights
        .into_iter()
        .map(|(shape, radiance)| Light::area(shape, radiance, false))
        .collect();
    for (i, l) in d.lights.iter().enumerate() {
        let key = format!("lights.{i}");
        let shape = match &l.spectrum {
            Some(s) => spectra.emission(s, &format!("{key}.spectrum"))?,
            None => spectra.emission(&SpectrumRef::Named("D65".into()), &key)?,
        };
        // Normalise the shape so that its integral over the spectral range is 1 (per nm).
        let integral = shape.sum() as f64 * grid.width();
        if integral <= 0.0 {
            return Err(err(
                scene,
                format!("{key}.spectrum"),
                "the spectrum is zero over the film's range".into(),
            ));
        }
        let unit = shape * (1.0 / integral as f32);
        let pos = l.position.map(v3).unwrap_or(Vec3::ZERO);
        let dir = l
            .direction
            .map(|d| v3(d).normalize())
            .unwrap_or(Vec3::NEG_Y);
        let power = unit * l.power.unwrap_or(0.0);
        lights.push(match l.kind {
            LightKind::Directional => Light::directional(dir, unit * l.irradiance.unwrap_or(0.0))
                .with_beam_margin(d.integrator.radius),
            LightKind::Point => Light::point(pos, power),
            LightKind::Spot => Light::spot(
                pos,
                dir,
                power,
                l.angle.unwrap_or(30.0),
                l.soft_edge.unwrap_or(0.0),
            ),
            LightKind::Laser => Light::laser(pos, dir, l.radius.unwrap_or(1e-3), power),
        });
    }
    let lights = LightSet::new(lights, &geometry);

    let c = &d.camera;
    let camera = match c.projection {
        Projection::Orthographic => Camera::orthographic(
            c.width,
            c.height,
            v3(c.position),
            v3(c.look_at),
            v3(c.up),
            c.view_width,
            c.view_height,
        ),
        Projection::Perspective => Camera::perspective(
            c.width,
            c.height,
            v3(c.position),
            v3(c.look_at),
            v3(c.up),
            c.fov,
        ),
    };
    let b = geometry.bounds();
    let (mut world_min, mut world_max) = (b.min.min(v3(c.position)), b.max.max(v3(c.position)));
    let margin = (world_max - world_min).max_element().max(1e-3) * 0.05 + d.integrator.radius;
    world_min -= Vec3::splat(margin);
    world_max += Vec3::splat(margin);

    let mut scene_out = Scene {
        grid,
        camera,
        geometry,
        materials,
        media,
        lights,
        camera_medium: outside,
        open,
        open_media,
        outside_medium: outside,
        world_min,
        world_max,
    };
    scene_out.camera_medium = scene_out.medium_at(v3(c.position));
    Ok(scene_out)
}

/// The integrator the scene file's `[integrator]` table describes, for its built `scene`.
pub fn build_integrator(loaded: &LoadedScene, scene: &Scene) -> Result<Integrator, SceneError> {
    Integrator::from_desc(&loaded.desc.integrator, scene)
        .map_err(|e| err(loaded, "integrator.q".into(), e.to_string()))
}
