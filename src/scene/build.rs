//! From a validated description to the runtime scene the integrator traces. Each kind of
//! light, shape and material builds itself (see `lights/`, `shapes/`, `materials/`); this file
//! holds the loops, the media and what depends on the whole scene (medium ids, world box).

use glam::Vec3;

use super::builder::{Builder, Inputs};
use super::desc::{SceneDesc, ShapeDesc, SpectrumRef};
use super::error::{SceneError, SceneWarning};
use super::loaded::LoadedScene;
use super::materials;
use super::media;
use super::shapes;
use crate::camera::Camera;
use crate::film::FilmExtras;
use crate::geometry::{Geometry, GeometryError};
use crate::integrator::Integrator;
use crate::integrator::radius::auto_radius;
use crate::light::{Light, LightSet};
use crate::material::Material;
use crate::spectrum::Spectrum;
use crate::world::Scene;

/// An integration radius above this fraction of the scene's bounding-box diagonal draws a
/// warning: such volumes blur the image and straddle surfaces (light is lost beyond them).
/// The shipped scenes use 0.5 % or less.
pub const LARGE_RADIUS: f32 = 0.05;

/// The runtime scene of a loaded scene file (its warnings dropped: see
/// [`build_with_warnings`]).
pub fn build(scene: &LoadedScene) -> Result<Scene, SceneError> {
    build_with_warnings(scene).map(|(s, _)| s)
}

/// The runtime scene and what in it is allowed but probably not meant (no light, a radius as
/// large as the scene): the command line prints those before rendering.
pub fn build_with_warnings(scene: &LoadedScene) -> Result<(Scene, Vec<SceneWarning>), SceneError> {
    let d = &scene.desc;
    let grid = scene.grid()?;
    let b = Builder::new(
        scene.source(),
        Inputs {
            grid: grid.clone(),
            spectra: &d.spectra,
            materials: d.materials.keys().map(String::as_str).collect(),
            media: d.media.keys().map(String::as_str).collect(),
            outside: d.medium.as_deref(),
            // Resolved below once the camera and geometry exist (lights need it).
            radius: d.integrator.radius.value().unwrap_or(0.0),
        },
    );
    // Resolve every named spectrum once, so that a bad file is reported even if unused.
    for name in d.spectra.keys() {
        b.spectra.unbounded(
            &SpectrumRef::Named(name.clone()),
            &format!("spectra.{name}"),
        )?;
    }
    let materials: Vec<Material> = materials::build_all(&b, &d.materials)?;
    let (geometry, area_lights) = build_shapes(&b, &d.shapes)?;
    // After the shapes: a noise density is sampled over the box of those holding its medium.
    let media = media::build_all(b.source, &b.spectra, &b.grid, &d.media, &geometry)?;
    let open = open_media(&geometry, media.len(), b.outside_medium());
    let camera = d.camera.build();
    let mut b = b;
    b.radius = match d.integrator.radius.value() {
        Some(r) => r,
        None => auto_radius(&camera, &geometry),
    };
    // Volumes reach as far as the larger of the two radii (`integrator::Radii`).
    let mut radius_key = "integrator.radius";
    if let Some(ri) = d.integrator.radius_indirect_value()
        && ri.is_finite()
        && ri > b.radius
    {
        b.radius = ri;
        radius_key = "integrator.radius_indirect";
    }
    let lights = build_lights(&b, d, &geometry, area_lights)?;
    let (world_min, world_max) = world_box(&geometry, &camera, b.radius);
    let mut warnings = scene.warnings.clone();
    warnings.extend(warnings_of(
        scene,
        &geometry,
        &lights,
        (radius_key, b.radius),
    ));
    warnings.extend(shut_in_warnings(
        scene, &geometry, &materials, &lights, &camera,
    ));
    let outside = b.outside_medium();
    let mut built = Scene {
        grid,
        camera,
        geometry,
        materials,
        media,
        lights,
        camera_medium: outside,
        open_media: open.iter().any(|&o| o),
        open,
        outside_medium: outside,
        world_min,
        world_max,
        film_extras: film_extras(d),
    };
    built.camera_medium = built.medium_at(camera.position());
    Ok((built, warnings))
}

/// Area lights first (in shape order), then `[[lights]]`; each keeps its `direct` choice and
/// its importance. An emitter given by its luminous flux is scaled here, its area known.
fn build_lights(
    b: &Builder,
    d: &SceneDesc,
    geometry: &Geometry,
    area_lights: Vec<(u32, Spectrum)>,
) -> Result<LightSet, SceneError> {
    let mut direct = Vec::new();
    let mut importance = Vec::new();
    let mut lights = Vec::new();
    for (shape, radiance) in area_lights {
        let s = &d.shapes[shape as usize].common;
        let radiance = match s.luminous_flux {
            Some(lm) => {
                let key = format!("shapes.{shape}");
                shapes::scale_to_flux(b, &key, radiance, lm, geometry.area(shape))?
            }
            None => radiance,
        };
        lights.push(Light::area(shape, radiance, false));
        direct.push(s.direct);
        importance.push(s.importance);
    }
    for (i, l) in d.lights.iter().enumerate() {
        lights.push(l.build(b, &format!("lights.{i}"))?);
        direct.push(l.common.direct);
        importance.push(l.common.importance);
    }
    Ok(LightSet::new(lights, geometry, &b.grid)
        .with_direct(direct)
        .with_importance(importance))
}

/// The sensors, and the light layers' names (`light<index>.<kind>`, in the order of the
/// scene's lights: emitting shapes first) when `film.light_layers` is on.
pub fn film_extras(d: &SceneDesc) -> FilmExtras {
    let size = (d.camera.width, d.camera.height);
    let sensors = d
        .sensors
        .iter()
        .enumerate()
        .map(|(i, s)| s.build(i, size))
        .collect();
    let mut light_layers = Vec::new();
    if d.film.light_layers {
        let kinds = d
            .shapes
            .iter()
            .filter(|s| s.common.emit.is_some())
            .map(|_| "area")
            .chain(d.lights.iter().map(|l| l.kind_name()));
        light_layers = kinds
            .enumerate()
            .map(|(i, k)| format!("light{i}.{k}"))
            .collect();
    }
    FilmExtras {
        sensors,
        light_layers,
    }
}

/// The integrator the scene file's `[integrator]` table describes, for its built `scene`.
pub fn build_integrator(loaded: &LoadedScene, scene: &Scene) -> Result<Integrator, SceneError> {
    Integrator::from_desc(&loaded.desc.integrator, scene)
        .map_err(|e| loaded.source().invalid("integrator.q", e.to_string()))
}

/// The geometry, and the radiance of each emitting shape by shape id.
fn build_shapes(
    b: &Builder,
    descs: &[ShapeDesc],
) -> Result<(Geometry, Vec<(u32, Spectrum)>), SceneError> {
    let mut shapes = Vec::with_capacity(descs.len());
    let mut area_lights = Vec::new();
    for (i, s) in descs.iter().enumerate() {
        let (mut shape, radiance) = s.build(b, &format!("shapes.{i}"))?;
        if let Some(radiance) = radiance {
            area_lights.push((i as u32, radiance));
            shape.light = Some((area_lights.len() - 1) as u32);
        }
        shapes.push(shape);
    }
    let geometry = Geometry::new(shapes).map_err(|e| match e {
        GeometryError::InvalidShape { shape, message } => {
            b.source.invalid(&format!("shapes.{shape}"), message)
        }
        GeometryError::Obj { .. } => b.source.invalid("shapes", e.to_string()),
    })?;
    Ok((geometry, area_lights))
}

/// Per medium: bounded only by index-matched (null) boundaries, so that its integration
/// volumes may gather forward rays outside it (method note 8).
fn open_media(geometry: &Geometry, media: usize, outside: Option<u32>) -> Vec<bool> {
    let mut open = vec![true; media];
    for s in geometry.shapes() {
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
    open
}

/// The box paths end at: the geometry and the camera, grown by 5 % and the radius.
fn world_box(geometry: &Geometry, camera: &Camera, radius: f32) -> (Vec3, Vec3) {
    let b = geometry.bounds();
    let eye = camera.position();
    let (mut lo, mut hi) = (b.min.min(eye), b.max.max(eye));
    let margin = (hi - lo).max_element().max(1e-3) * 0.05 + radius;
    lo -= Vec3::splat(margin);
    hi += Vec3::splat(margin);
    (lo, hi)
}

/// A warning for each light shut inside an opaque shape the camera is outside of
/// (`enclosed.rs`), at the light's key.
fn shut_in_warnings(
    scene: &LoadedScene,
    geometry: &Geometry,
    materials: &[Material],
    lights: &LightSet,
    camera: &Camera,
) -> Vec<SceneWarning> {
    let all = lights.lights();
    let areas = all
        .iter()
        .take_while(|l| matches!(l, Light::Area { .. }))
        .count();
    let names: Vec<&String> = scene.desc.materials.keys().collect();
    super::enclosed::shut_in(geometry, materials, all, camera.position())
        .into_iter()
        .map(|(i, shape)| {
            let (key, part) = super::gltf::in_file(&scene.desc, &format!("shapes.{shape}"));
            let material = geometry
                .shape(shape)
                .material
                .and_then(|m| names.get(m as usize))
                .map_or(String::new(), |n| format!(", material `{n}`"));
            scene.source().warning(
                &format!("lights.{}", i - areas),
                format!(
                    "the light is shut inside {key}{part}{material}, which lets no light through, \
                     and the camera is outside it: none of its light reaches the image (give the \
                     shape a material that transmits, such as a dielectric, or move the light)"
                ),
            )
        })
        .collect()
}

/// Warnings that need the built scene: no light that emits, a radius as large as the scene.
fn warnings_of(
    scene: &LoadedScene,
    geometry: &Geometry,
    lights: &LightSet,
    (radius_key, radius): (&str, f32),
) -> Vec<SceneWarning> {
    let source = scene.source();
    let mut w = Vec::new();
    let emits = (0..lights.lights().len()).any(|i| lights.pick_probability(i) > 0.0);
    if !emits {
        w.push(source.warning(
            "",
            "the scene has no light that emits ([[lights]], or shapes with `emit`): the image \
             will be black",
        ));
    }
    let bounds = geometry.bounds();
    let size = bounds.diagonal().length();
    if !bounds.is_empty() && size > 0.0 && radius > LARGE_RADIUS * size {
        w.push(source.warning(
            radius_key,
            format!(
                "{radius} m is {:.0} % of the scene's size ({size:.3} m across its bounds): \
                 integration volumes this large blur the image and lose the light they reach \
                 beyond surfaces; about 0.1-1 % of the scene is usual",
                100.0 * radius / size
            ),
        ));
    }
    w
}
