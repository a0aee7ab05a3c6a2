//! From a validated description to the runtime scene the integrator traces.

use std::collections::BTreeMap;
use std::sync::Arc;

use glam::{Vec2, Vec3};

use super::LoadedScene;
use super::desc::{LightKind, MaterialKind, ShapeKindDesc, SpectrumRef};
use super::error::{KeyText, Origin, SceneError};
use super::spectra::SpectrumResolver;
use crate::camera::Camera;
use crate::geometry::{self, Geometry, Ray, ShapeKind, Transform};
use crate::light::{Light, LightSet};
use crate::material::{Albedo, Material, Texture};
use crate::medium::{BuiltMedium, HomogeneousMedium, MediumParts, MultiSphereWalk};
use crate::scene::desc::{IntegratorDesc, Projection, SceneDesc};
use crate::spectrum::{SpectralGrid, Spectrum};

/// Everything a render needs, built once and shared read-only by all workers.
pub struct Scene {
    pub grid: SpectralGrid,
    pub camera: Camera,
    pub geometry: Geometry,
    pub materials: Vec<Material>,
    pub media: Vec<HomogeneousMedium>,
    pub lights: LightSet,
    /// Medium around the camera (ray start).
    pub camera_medium: Option<u32>,
    /// Medium outside every shape.
    pub outside_medium: Option<u32>,
    /// Per medium: bounded only by index-matched (null) boundaries, so that its integration
    /// volumes may gather forward rays outside it (method note 8).
    pub open: Vec<bool>,
    /// Whether any medium is open.
    pub open_media: bool,
    /// The world box: paths that leave it end (media are taken to stop there).
    pub world_min: Vec3,
    pub world_max: Vec3,
    pub settings: IntegratorDesc,
    /// The camera-side multi-sphere walk with the scene's q.
    pub walk: MultiSphereWalk,
    pub desc: SceneDesc,
}

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

/// Builds medium `name` (spectra resolved here, the rest in `medium::build_medium`). A phase
/// that varies per spectral bin (droplets, per-wavelength tables) is refused for now: the
/// renderer still evaluates one phase for all bins (issue 17's integrator part), and would
/// silently render the bins' average instead. `summary` builds media on its own for `info`.
pub fn build_medium(
    scene: &LoadedScene,
    spectra: &SpectrumResolver,
    name: &str,
) -> Result<BuiltMedium, SceneError> {
    let m = &scene.desc.media[name];
    let key = format!("media.{name}");
    let ss = match &m.sigma_s {
        Some(s) => Some(spectra.unbounded(s, &format!("{key}.sigma_s"))?),
        None => None,
    };
    let sa = spectra.unbounded(&m.sigma_a, &format!("{key}.sigma_a"))?;
    let parts = MediumParts {
        sigma_s: ss.as_ref(),
        sigma_a: &sa,
        g: m.g,
        phase: m.phase.as_ref(),
        droplets: m.droplets.as_ref(),
    };
    let built = crate::medium::build_medium(parts, &scene.desc.film.grid(), &|f| scene.resolve(f))
        .map_err(|e| {
            let k = format!("{key}.{}", e.key);
            match e.error {
                crate::medium::MediumError::PhaseFile {
                    file,
                    line,
                    message,
                } => SceneError::Invalid {
                    origin: Origin::File {
                        file,
                        line: Some((line, 1)),
                    },
                    key: KeyText(k),
                    message,
                },
                other => err(scene, k, other.to_string()),
            }
        })?;
    Ok(built)
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
        .keys()
        .map(|name| {
            let b = build_medium(scene, &spectra, name)?;
            if b.medium.phase.varies_per_bin() {
                let key = match b.droplets {
                    Some(_) => "droplets",
                    None => "phase",
                };
                return Err(err(
                    scene,
                    format!("media.{name}.{key}"),
                    "its phase function varies per spectral bin, which the renderer does not \
                     use yet (it would render the bins' average phase): `brume info` shows the \
                     medium; render it with a phase that is the same in every bin for now"
                        .into(),
                ));
            }
            Ok(b.medium)
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
        settings: d.integrator.clone(),
        walk: MultiSphereWalk::new(d.integrator.q)
            .map_err(|e| err(scene, "integrator.q".into(), e.to_string()))?,
        desc: d.clone(),
    };
    scene_out.camera_medium = scene_out.medium_at(v3(c.position));
    Ok(scene_out)
}

impl Scene {
    /// The medium containing point `p`: found from the first boundary a ray from `p` meets
    /// (inside that shape if the ray leaves through it), else the scene's outside medium.
    pub fn medium_at(&self, p: Vec3) -> Option<u32> {
        // Outside every shape's bounds nothing encloses p (e.g. a directional light's rays
        // start there): no ray needed.
        let b = self.geometry.bounds();
        let (lo, hi) = (b.min, b.max);
        if p.cmplt(lo).any() || p.cmpgt(hi).any() {
            return self.outside_medium;
        }
        // An irrational-ish direction avoids grazing axis-aligned edges.
        let d = Vec3::new(0.301, 0.812, 0.5).normalize();
        match self.geometry.intersect(&Ray { o: p, d }, f32::INFINITY) {
            Some(h) => {
                let shape = self.geometry.shape(h.shape);
                if d.dot(h.ng) > 0.0 {
                    shape.interior
                } else {
                    shape.exterior
                }
            }
            None => self.outside_medium,
        }
    }

    pub fn open_medium(&self, m: u32) -> bool {
        self.open.get(m as usize).copied().unwrap_or(false)
    }

    /// Distance along `ray` to the world box's far side (0 if it starts outside and misses).
    pub fn world_exit(&self, ray: &Ray) -> f32 {
        let inv = ray.d.recip();
        let t0 = (self.world_min - ray.o) * inv;
        let t1 = (self.world_max - ray.o) * inv;
        let far = t0.max(t1).min_element();
        if far.is_finite() { far.max(0.0) } else { 0.0 }
    }
}
