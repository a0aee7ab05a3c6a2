//! The runtime scene: what light transport reads (geometry, materials, media, lights, camera and
//! the spectral grid), built from a scene file by `scene::build` and shared read-only by every
//! worker. It holds content only: how it is rendered is the `integrator`'s.

use glam::Vec3;

use crate::camera::Camera;
use crate::film::FilmExtras;
use crate::geometry::{Geometry, Ray};
use crate::light::LightSet;
use crate::material::Material;
use crate::medium::Medium;
use crate::spectrum::SpectralGrid;

pub struct Scene {
    pub grid: SpectralGrid,
    pub camera: Camera,
    pub geometry: Geometry,
    pub materials: Vec<Material>,
    pub media: Vec<Medium>,
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
    /// What the film keeps beside the image: the scene's sensors (`[[sensors]]`, in file
    /// order; the integrator splats illuminance sensors by their index here) and, with
    /// `film.light_layers`, one layer name per light (in `lights` order).
    pub film_extras: FilmExtras,
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
