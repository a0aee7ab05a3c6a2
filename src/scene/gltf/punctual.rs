//! `KHR_lights_punctual` lights and glTF cameras as brume's: point and spot lights keep their
//! intensity in candela, directional lights their illuminance in lux; a light shines down its
//! node's -Z axis, a camera looks down -Z with +Y up.

use glam::{Mat4, Vec3};

use super::Notes;
use super::file::Fault;
use crate::scene::desc::{
    CameraDesc, DirectionalDesc, LightCommon, LightDesc, LightKind, PointDesc, Projection,
    SpectrumRef, SpotDesc,
};

/// The brume light of glTF light `l` placed by its node's `world` matrix (scale ignored, as
/// glTF says); None (noted) for a light that emits nothing.
pub fn light(
    l: &gltf::khr_lights_punctual::Light,
    world: Mat4,
    notes: &mut Notes,
) -> Result<Option<LightDesc>, Fault> {
    use gltf::khr_lights_punctual::Kind;
    let at = format!("extensions.KHR_lights_punctual.lights[{}]", l.index());
    let intensity = l.intensity();
    if !(intensity.is_finite() && intensity >= 0.0) {
        return Err(Fault::at(
            format!("{at}.intensity"),
            format!("{intensity} is not a finite number >= 0"),
        ));
    }
    let colour = l.color();
    if colour.iter().any(|c| !(c.is_finite() && *c >= 0.0)) || colour.iter().all(|c| *c <= 0.0) {
        return Err(Fault::at(
            format!("{at}.color"),
            format!("{colour:?} is not a colour >= 0 that emits"),
        ));
    }
    if intensity == 0.0 {
        notes.add("lights of intensity 0 (left out)", &at);
        return Ok(None);
    }
    if l.range().is_some() {
        notes.add(
            "light range (brume's lights fall off with the inverse square, unbounded)",
            &at,
        );
    }
    let position = world.transform_point3(Vec3::ZERO).to_array();
    let direction = axis(world, Vec3::NEG_Z).to_array();
    let kind = match l.kind() {
        Kind::Point => LightKind::Point(PointDesc {
            power: None,
            luminous_flux: None,
            intensity: Some(intensity),
            position,
            profile: None,
            direction: None,
            profile_c0: None,
        }),
        Kind::Spot {
            inner_cone_angle,
            outer_cone_angle,
        } => {
            let inner = inner_cone_angle.clamp(0.0, outer_cone_angle);
            LightKind::Spot(SpotDesc {
                power: None,
                luminous_flux: None,
                intensity: Some(intensity),
                position,
                direction,
                angle: Some(outer_cone_angle.to_degrees()),
                soft_edge: (outer_cone_angle - inner).to_degrees(),
                profile: None,
                profile_c0: None,
            })
        }
        Kind::Directional => LightKind::Directional(DirectionalDesc {
            irradiance: None,
            illuminance: Some(intensity),
            direction,
        }),
    };
    // White is brume's default D65 white; other colours are upsampled as emission.
    let spectrum = (colour != [1.0; 3]).then(|| SpectrumRef::Rgb(colour.map(|c| c as f64)));
    Ok(Some(LightDesc {
        common: LightCommon {
            spectrum,
            direct: Default::default(),
            importance: 1.0,
        },
        kind,
    }))
}

/// The scene camera of glTF camera `c` at its node's `world` matrix; `base` gives the image
/// size (the TOML's).
pub fn camera(c: &gltf::Camera, world: Mat4, base: &CameraDesc) -> CameraDesc {
    let position = world.transform_point3(Vec3::ZERO);
    let forward = axis(world, Vec3::NEG_Z);
    let up = axis(world, Vec3::Y);
    let mut d = CameraDesc {
        position: position.to_array(),
        look_at: (position + forward).to_array(),
        up: up.to_array(),
        ..base.clone()
    };
    match c.projection() {
        gltf::camera::Projection::Perspective(p) => {
            d.projection = Projection::Perspective;
            d.fov = Some(p.yfov().to_degrees());
        }
        gltf::camera::Projection::Orthographic(o) => {
            d.projection = Projection::Orthographic;
            d.view_width = Some(2.0 * o.xmag());
            d.view_height = Some(2.0 * o.ymag());
        }
    }
    d
}

/// The world direction of a local axis (the matrix's rotation; scale and shear only change
/// its length, which is normalised away).
fn axis(world: Mat4, local: Vec3) -> Vec3 {
    let v = world.transform_vector3(local);
    if v == local {
        local
    } else {
        v.normalize_or(local)
    }
}
