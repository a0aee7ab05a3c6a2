//! Surface materials. All directions point away from the surface; `wo` points towards the viewer
//! (or the previous path vertex), `wi` is the other direction. `eval` returns f without the cosine.
//!
//! Reflective materials are two-sided: they reflect on whichever side `wo` is, and only into that
//! side (judged by the geometric normal, so shading normals cannot leak light through).

mod blend;
mod conductor;
mod dielectric;
mod fresnel;
mod glossy;
mod metals;
mod texture;

use std::f32::consts::FRAC_1_PI;
use std::sync::Arc;

use glam::{Vec2, Vec3};

use crate::geometry::Hit;
use crate::geometry::sampling::{Frame, cosine_hemisphere};
use crate::spectrum::Spectrum;

pub use blend::{Blend, BlendWeight};
pub use conductor::{Conductor, ConductorFresnel, SMOOTH_ALPHA};
pub use dielectric::Dielectric;
pub use fresnel::{fresnel_conductor, fresnel_dielectric, reflect, refract, schlick};
pub use glossy::{Glossy, MIN_ROUGHNESS};
pub use metals::{is_metal, metal_index, metal_names};
pub use texture::{Encoding, Texture, TextureError, Wrap};

/// Which lobe produced a sample; the integrator gathers only at diffuse events.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LobeKind {
    Diffuse,
    Glossy,
    Specular,
}

/// A sampled direction with `weight` = f |cos| / pdf (for the lobe that was sampled; see each
/// sampling method) and `pdf` the density of the sampling method that produced it (for specular
/// lobes: the discrete probability of the choice).
#[derive(Clone, Copy, Debug)]
pub struct BsdfSample {
    pub wi: Vec3,
    pub weight: Spectrum,
    pub pdf: f32,
    pub kind: LobeKind,
}

/// Reflectance that is a constant spectrum or a texture looked up at the hit's uv.
#[derive(Clone, Debug)]
#[allow(clippy::large_enum_variant)] // constant albedo is the common case; keep it inline
pub enum Albedo {
    Constant(Spectrum),
    Texture(Arc<Texture>),
}

impl Albedo {
    #[inline]
    pub fn at(&self, uv: Vec2) -> Spectrum {
        match self {
            Albedo::Constant(s) => *s,
            Albedo::Texture(t) => t.lookup(uv),
        }
    }
}

impl From<Spectrum> for Albedo {
    fn from(s: Spectrum) -> Self {
        Albedo::Constant(s)
    }
}

impl From<Arc<Texture>> for Albedo {
    fn from(t: Arc<Texture>) -> Self {
        Albedo::Texture(t)
    }
}

#[derive(Clone, Debug)]
pub enum Material {
    Lambert {
        albedo: Albedo,
    },
    Mirror {
        reflectance: Spectrum,
    },
    Glossy(Glossy),
    /// A metal: GGX microfacet reflection with a spectral Fresnel factor (boxed: its two
    /// spectra would double every material's size).
    Conductor(Box<Conductor>),
    Dielectric(Dielectric),
    /// (1 - w) first + w second.
    Blend(Box<Blend>),
}

/// Local frame on `wo`'s side of the surface, or None if `wo` lies in the surface.
#[inline]
fn side_frame(wo: Vec3, hit: &Hit) -> Option<Frame> {
    let s = wo.dot(hit.ng);
    if s == 0.0 {
        return None;
    }
    let n = if s > 0.0 { hit.ns } else { -hit.ns };
    Some(Frame::new(n))
}

/// Both directions on the same geometric side, and above the shading frame.
#[inline]
fn reflects(wo: Vec3, wi: Vec3, hit: &Hit, f: &Frame) -> Option<(Vec3, Vec3)> {
    if wo.dot(hit.ng) * wi.dot(hit.ng) <= 0.0 {
        return None;
    }
    let (lo, li) = (f.to_local(wo), f.to_local(wi));
    (lo.z > 0.0 && li.z > 0.0).then_some((lo, li))
}

impl Material {
    pub fn lambert(albedo: Spectrum) -> Material {
        Material::Lambert {
            albedo: Albedo::Constant(albedo),
        }
    }

    pub fn lambert_textured(tex: Arc<Texture>) -> Material {
        Material::Lambert {
            albedo: Albedo::Texture(tex),
        }
    }

    pub fn mirror(reflectance: Spectrum) -> Material {
        Material::Mirror { reflectance }
    }

    /// `specular_ior` sets the coating's normal-incidence reflectance; `roughness` is the GGX
    /// alpha (clamped to [`MIN_ROUGHNESS`, 1]); `n_bins` is the scene's bin count (the achromatic coating
    /// fills exactly these lanes).
    pub fn glossy(
        albedo: impl Into<Albedo>,
        specular_ior: f32,
        roughness: f32,
        n_bins: usize,
    ) -> Material {
        Material::Glossy(Glossy::new(albedo.into(), specular_ior, roughness, n_bins))
    }

    /// GGX alphas along the two tangent axes (equal: isotropic; both below [`SMOOTH_ALPHA`]: a
    /// delta mirror) and the Fresnel factor's source, over the scene's `n_bins`.
    pub fn conductor(alpha: [f32; 2], fresnel: ConductorFresnel, n_bins: usize) -> Material {
        Material::Conductor(Box::new(Conductor::new(
            alpha[0], alpha[1], fresnel, n_bins,
        )))
    }

    /// `ior` per bin (constant => no dispersion) over the scene's `n_bins`.
    pub fn dielectric(ior: Spectrum, n_bins: usize) -> Material {
        Material::Dielectric(Dielectric::new(ior, n_bins))
    }

    /// `(1 - weight) first + weight second`; `weight` is clamped to [0, 1] where it is used.
    pub fn blend(first: Material, second: Material, weight: BlendWeight) -> Material {
        Material::Blend(Box::new(Blend {
            first,
            second,
            weight,
        }))
    }

    pub fn is_dispersive(&self) -> bool {
        match self {
            Material::Dielectric(d) => d.dispersive,
            Material::Blend(b) => b.first.is_dispersive() || b.second.is_dispersive(),
            Material::Lambert { .. }
            | Material::Mirror { .. }
            | Material::Glossy(_)
            | Material::Conductor(_) => false,
        }
    }

    /// Can light pass through the surface (a dielectric, alone or blended)?
    pub fn transmits(&self) -> bool {
        match self {
            Material::Dielectric(_) => true,
            Material::Blend(b) => b.first.transmits() || b.second.transmits(),
            Material::Lambert { .. }
            | Material::Mirror { .. }
            | Material::Glossy(_)
            | Material::Conductor(_) => false,
        }
    }

    /// Has the material a delta (specular) part only?
    pub fn is_specular(&self) -> bool {
        match self {
            Material::Mirror { .. } | Material::Dielectric(_) => true,
            Material::Conductor(c) => c.smooth,
            Material::Blend(b) => b.first.is_specular() && b.second.is_specular(),
            Material::Lambert { .. } | Material::Glossy(_) => false,
        }
    }

    /// Has the material a glossy (non-delta, non-diffuse) part, which next-event estimation
    /// can reach with a sampled direction?
    pub fn has_glossy(&self) -> bool {
        match self {
            Material::Glossy(_) => true,
            Material::Conductor(c) => !c.smooth,
            Material::Lambert { .. } | Material::Mirror { .. } | Material::Dielectric(_) => false,
            Material::Blend(b) => b.first.has_glossy() || b.second.has_glossy(),
        }
    }

    /// Has the material a part that [`Self::sample_nondiffuse`] samples?
    pub fn has_nondiffuse(&self) -> bool {
        match self {
            Material::Lambert { .. } => false,
            Material::Mirror { .. }
            | Material::Glossy(_)
            | Material::Conductor(_)
            | Material::Dielectric(_) => true,
            Material::Blend(b) => b.first.has_nondiffuse() || b.second.has_nondiffuse(),
        }
    }

    /// Full BSDF value f (no cosine). Zero for delta lobes.
    pub fn eval(&self, wo: Vec3, wi: Vec3, hit: &Hit) -> Spectrum {
        match self {
            Material::Lambert { .. } => self.eval_diffuse(wo, wi, hit),
            Material::Glossy(g) => {
                let Some(f) = side_frame(wo, hit) else {
                    return Spectrum::ZERO;
                };
                match reflects(wo, wi, hit, &f) {
                    Some((lo, li)) => g.f_diffuse(lo, li, hit.uv) + g.f_specular(lo, li),
                    None => Spectrum::ZERO,
                }
            }
            Material::Conductor(c) => c.eval(wo, wi, hit),
            Material::Mirror { .. } | Material::Dielectric(_) => Spectrum::ZERO,
            Material::Blend(b) => b.eval(wo, wi, hit),
        }
    }

    /// Density (solid angle) with which [`Self::sample`] returns `wi`; zero for delta lobes.
    pub fn pdf(&self, wo: Vec3, wi: Vec3, hit: &Hit) -> f32 {
        let local = || {
            let f = side_frame(wo, hit)?;
            reflects(wo, wi, hit, &f)
        };
        match self {
            Material::Lambert { .. } => local().map_or(0.0, |(_, li)| li.z * FRAC_1_PI),
            Material::Glossy(g) => local().map_or(0.0, |(lo, li)| {
                let pd = g.diffuse_probability(lo.z, hit.uv);
                pd * li.z * FRAC_1_PI + (1.0 - pd) * g.pdf_specular(lo, li)
            }),
            Material::Conductor(c) => c.pdf(wo, wi, hit),
            Material::Mirror { .. } | Material::Dielectric(_) => 0.0,
            Material::Blend(b) => b.pdf(wo, wi, hit),
        }
    }

    /// Samples the whole BSDF, for forward (flux-carrying) rays. For the glossy material one lobe
    /// is chosen and `weight` is that lobe's f |cos| divided by (choice probability x its pdf),
    /// so `kind` tells exactly which part of the BSDF the weight belongs to.
    pub fn sample(&self, wo: Vec3, hit: &Hit, u: Vec3) -> Option<BsdfSample> {
        match self {
            Material::Lambert { albedo } => {
                let f = side_frame(wo, hit)?;
                let li = cosine_hemisphere(Vec2::new(u.x, u.y));
                let wi = f.to_world(li);
                if li.z <= 0.0 || wi.dot(hit.ng) * wo.dot(hit.ng) <= 0.0 {
                    return None;
                }
                Some(BsdfSample {
                    wi,
                    weight: albedo.at(hit.uv),
                    pdf: li.z * FRAC_1_PI,
                    kind: LobeKind::Diffuse,
                })
            }
            Material::Glossy(g) => {
                let f = side_frame(wo, hit)?;
                let lo = f.to_local(wo);
                if lo.z <= 0.0 {
                    return None;
                }
                let pd = g.diffuse_probability(lo.z, hit.uv);
                let uv2 = Vec2::new(u.x, u.y);
                let (li, kind) = if u.z < pd {
                    (cosine_hemisphere(uv2), LobeKind::Diffuse)
                } else {
                    (g.sample_specular(lo, uv2)?, LobeKind::Glossy)
                };
                let wi = f.to_world(li);
                if li.z <= 0.0 || wi.dot(hit.ng) * wo.dot(hit.ng) <= 0.0 {
                    return None;
                }
                let weight = match kind {
                    LobeKind::Diffuse => g.f_diffuse(lo, li, hit.uv) * (std::f32::consts::PI / pd),
                    LobeKind::Glossy | LobeKind::Specular => {
                        let p = (1.0 - pd) * g.pdf_specular(lo, li);
                        if p <= 0.0 {
                            return None;
                        }
                        Spectrum::splat(1.0, g.n_bins) * (g.f_specular(lo, li) * li.z / p)
                    }
                };
                Some(BsdfSample {
                    wi,
                    weight,
                    pdf: pd * li.z * FRAC_1_PI + (1.0 - pd) * g.pdf_specular(lo, li),
                    kind,
                })
            }
            Material::Mirror { .. } => self.sample_nondiffuse(wo, hit, u),
            Material::Conductor(c) => c.sample(wo, hit, Vec2::new(u.x, u.y)),
            Material::Dielectric(d) => d.sample(wo, hit, u, false),
            Material::Blend(b) => b.sample(wo, hit, u),
        }
    }

    /// Chance that a camera path stops on the diffuse part at this hit.
    pub fn diffuse_probability(&self, wo: Vec3, hit: &Hit) -> f32 {
        match self {
            Material::Lambert { .. } => 1.0,
            Material::Glossy(g) => match side_frame(wo, hit) {
                Some(f) => g.diffuse_probability(f.to_local(wo).z.max(0.0), hit.uv),
                None => 0.0,
            },
            Material::Mirror { .. } | Material::Conductor(_) | Material::Dielectric(_) => 0.0,
            Material::Blend(b) => b.diffuse_probability(wo, hit),
        }
    }

    /// f of the diffuse part only (no cosine).
    pub fn eval_diffuse(&self, wo: Vec3, wi: Vec3, hit: &Hit) -> Spectrum {
        let diffuse = |wo, wi| {
            let f = side_frame(wo, hit)?;
            reflects(wo, wi, hit, &f)
        };
        match self {
            Material::Lambert { albedo } => match diffuse(wo, wi) {
                Some(_) => albedo.at(hit.uv) * FRAC_1_PI,
                None => Spectrum::ZERO,
            },
            Material::Glossy(g) => match diffuse(wo, wi) {
                Some((lo, li)) => g.f_diffuse(lo, li, hit.uv),
                None => Spectrum::ZERO,
            },
            Material::Mirror { .. } | Material::Conductor(_) | Material::Dielectric(_) => {
                Spectrum::ZERO
            }
            Material::Blend(b) => b.eval_diffuse(wo, wi, hit),
        }
    }

    /// f of the non-diffuse part only (no cosine): the glossy coat; zero for delta lobes, which
    /// no given direction can hit.
    pub fn eval_nondiffuse(&self, wo: Vec3, wi: Vec3, hit: &Hit) -> Spectrum {
        match self {
            Material::Glossy(g) => {
                let Some(f) = side_frame(wo, hit) else {
                    return Spectrum::ZERO;
                };
                match reflects(wo, wi, hit, &f) {
                    Some((lo, li)) => Spectrum::splat(g.f_specular(lo, li), g.n_bins),
                    None => Spectrum::ZERO,
                }
            }
            Material::Conductor(c) => c.eval(wo, wi, hit),
            Material::Lambert { .. } | Material::Mirror { .. } | Material::Dielectric(_) => {
                Spectrum::ZERO
            }
            Material::Blend(b) => b.eval_nondiffuse(wo, wi, hit),
        }
    }

    /// Density (solid angle) with which [`Self::sample_nondiffuse`] returns `wi`; zero for
    /// delta lobes. Next-event estimation weighs its light samples against it (multiple
    /// importance sampling).
    pub fn pdf_nondiffuse(&self, wo: Vec3, wi: Vec3, hit: &Hit) -> f32 {
        match self {
            Material::Glossy(g) => side_frame(wo, hit)
                .and_then(|f| reflects(wo, wi, hit, &f))
                .map_or(0.0, |(lo, li)| g.pdf_specular(lo, li)),
            Material::Conductor(c) => c.pdf(wo, wi, hit),
            Material::Lambert { .. } | Material::Mirror { .. } | Material::Dielectric(_) => 0.0,
            Material::Blend(b) => b.pdf_nondiffuse(wo, wi, hit),
        }
    }

    /// Samples the non-diffuse part alone, for camera paths: `weight` = f_nd |cos| / pdf, not
    /// divided by the probability of having chosen this part. Camera paths carry radiance, so
    /// dielectric transmission includes the (n_i/n_t)^2 factor here (and not in [`Self::sample`]).
    /// Transmission through a dispersive dielectric picks one bin, as in [`Self::sample`].
    pub fn sample_nondiffuse(&self, wo: Vec3, hit: &Hit, u: Vec3) -> Option<BsdfSample> {
        match self {
            Material::Lambert { .. } => None,
            Material::Mirror { reflectance } => {
                let f = side_frame(wo, hit)?;
                let wi = reflect(wo, f.n);
                if wi.dot(hit.ng) * wo.dot(hit.ng) <= 0.0 {
                    return None;
                }
                Some(BsdfSample {
                    wi,
                    weight: *reflectance,
                    pdf: 1.0,
                    kind: LobeKind::Specular,
                })
            }
            Material::Glossy(g) => {
                let f = side_frame(wo, hit)?;
                let lo = f.to_local(wo);
                if lo.z <= 0.0 {
                    return None;
                }
                let li = g.sample_specular(lo, Vec2::new(u.x, u.y))?;
                let wi = f.to_world(li);
                let p = g.pdf_specular(lo, li);
                if p <= 0.0 || wi.dot(hit.ng) * wo.dot(hit.ng) <= 0.0 {
                    return None;
                }
                Some(BsdfSample {
                    wi,
                    weight: Spectrum::splat(g.f_specular(lo, li) * li.z / p, g.n_bins),
                    pdf: p,
                    kind: LobeKind::Glossy,
                })
            }
            Material::Conductor(c) => c.sample(wo, hit, Vec2::new(u.x, u.y)),
            Material::Dielectric(d) => d.sample(wo, hit, u, true),
            Material::Blend(b) => b.sample_nondiffuse(wo, hit, u),
        }
    }
}
