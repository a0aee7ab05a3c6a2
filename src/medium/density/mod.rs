//! Where a medium is: its density field `rho(x)`, which multiplies the medium's spectral
//! coefficients, `sigma_t(x, lambda) = rho(x) sigma_t(lambda)` (method note 10). One spatial
//! field and per-bin cross-sections keep the albedo and the phase function independent of the
//! position, so the paper's coloured estimators stay exact.
//!
//! The kinds here have a closed-form optical depth along any ray, `D(s) = ∫_0^s rho`, which is
//! monotone and so invertible: in the variable `u = D(s)` a segment is the homogeneous medium
//! at `rho = 1`, and every estimator of the homogeneous case holds in `u` (a sphere sampled at
//! `u` sits at `s(u)`; the `rho` of a point cancels between the scattering coefficient and the
//! distance density). [`Along`] is that change of variable for one ray: the transport code
//! walks, flies and samples in `u` and places points at `distance(u)`, and never asks which
//! kind of field it is in. The uniform field is the identity, so homogeneous media keep their
//! numbers bit for bit. docs/media.md derives each kind's formulas.
//!
//! One file per kind: a kind gives its density along its `up` axis and the integral and
//! inverse integral of that profile ([`Profile`]).

mod desc;
pub mod grid;
mod height;
mod layer;
pub mod noise;

use std::sync::Arc;

use glam::Vec3;

pub use desc::{DensityDesc, DensityError, GridTransform};
pub use grid::{GridField, GridRay};
pub use height::Height;
pub use layer::Layer;

/// Lengths (m) a density accepts: what f32 scene geometry resolves.
pub(crate) const MAX_LENGTH: f32 = 1e7;
pub(crate) const MIN_LENGTH: f32 = 1e-4;

/// A medium's density field.
#[derive(Clone, Debug, PartialEq)]
pub enum Density {
    /// `rho = 1` everywhere: the homogeneous medium.
    Uniform,
    Height(Height),
    Layer(Layer),
    /// Samples on a grid (shared: media and scenes are cloned, grids can be large).
    Grid(Arc<GridField>),
}

/// A field that varies along one axis only: the density at height `h` and its integral.
pub trait Profile {
    /// The unit axis heights are measured along.
    fn up(&self) -> Vec3;
    /// Density at height `h`.
    fn rho(&self, h: f64) -> f64;
    /// `∫_a^b rho(h) dh` (negative for `b < a`), accurate also for `b` close to `a`.
    fn integral(&self, a: f64, b: f64) -> f64;
    /// The `b` at which `∫_a^b rho = g` going from `a` in the direction of `sign(g)`
    /// (`g` of either sign), or None when the integral never reaches `g` that way (the field
    /// thins out to nothing).
    fn solve(&self, a: f64, g: f64) -> Option<f64>;
    /// Least and greatest density over heights `[lo, hi]`.
    fn range(&self, lo: f64, hi: f64) -> (f64, f64);
}

impl Density {
    /// True for the homogeneous medium.
    pub fn is_uniform(&self) -> bool {
        matches!(self, Density::Uniform)
    }

    /// The field in words, for `brume info`.
    pub fn describe(&self) -> String {
        match self {
            Density::Uniform => "uniform".into(),
            Density::Height(f) => f.describe(),
            Density::Layer(f) => f.describe(),
            Density::Grid(g) => g.describe(),
        }
    }

    /// Bytes the field keeps (its samples for a grid).
    pub fn bytes(&self) -> usize {
        match self {
            Density::Uniform | Density::Height(_) | Density::Layer(_) => {
                std::mem::size_of_val(self)
            }
            Density::Grid(g) => g.bytes(),
        }
    }

    /// `∫_0^s rho` along the ray `o + d s`: `along(o, d).depth(s)`, without building a grid
    /// ray's pieces (for one-off depths).
    pub fn depth_to(&self, o: Vec3, d: Vec3, s: f32) -> f32 {
        match self {
            Density::Grid(g) => g.depth(o, d, s),
            Density::Uniform | Density::Height(_) | Density::Layer(_) => self.along(o, d).depth(s),
        }
    }

    /// The density at `p`.
    pub fn at(&self, p: Vec3) -> f32 {
        match self {
            Density::Uniform => 1.0,
            Density::Height(f) => rho_at(f, p),
            Density::Layer(f) => rho_at(f, p),
            Density::Grid(g) => g.at(p),
        }
    }

    /// The change of variable `s -> u = D(s)` along the ray `o + d s` (`d` unit).
    #[inline]
    pub fn along(&self, o: Vec3, d: Vec3) -> Along {
        match self {
            Density::Uniform => Along::Identity,
            Density::Height(f) => Along::Height(Vertical::new(*f, o, d)),
            Density::Layer(f) => Along::Layer(Vertical::new(*f, o, d)),
            Density::Grid(g) => Along::Grid(g.along(o, d)),
        }
    }

    /// The change of variable along the ray `o + d s` as far as distance `s_max` or depth
    /// `u_max` reaches, whichever is nearer (a grid ray builds only its pieces up to there;
    /// `GridRay::until` says what its `depth` and `distance` give beyond). The closed-form
    /// fields have nothing to build and give the whole ray.
    #[inline]
    pub fn along_until(&self, o: Vec3, d: Vec3, reach: (f32, f32)) -> Along {
        match self {
            Density::Grid(g) => Along::Grid(g.along_until(o, d, reach)),
            Density::Uniform | Density::Height(_) | Density::Layer(_) => self.along(o, d),
        }
    }

    /// Least and greatest density over the box `[lo, hi]`.
    pub fn range(&self, lo: Vec3, hi: Vec3) -> (f32, f32) {
        let heights = |up: Vec3| {
            let corners = (0..8).map(|i| {
                let c = Vec3::new(
                    if i & 1 == 0 { lo.x } else { hi.x },
                    if i & 2 == 0 { lo.y } else { hi.y },
                    if i & 4 == 0 { lo.z } else { hi.z },
                );
                up.dot(c) as f64
            });
            corners.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), h| {
                (a.min(h), b.max(h))
            })
        };
        let (a, b) = match self {
            Density::Uniform => (1.0, 1.0),
            Density::Grid(g) => return g.range(lo, hi),
            Density::Height(f) => {
                let (l, h) = heights(f.up());
                f.range(l, h)
            }
            Density::Layer(f) => {
                let (l, h) = heights(f.up());
                f.range(l, h)
            }
        };
        (a as f32, b as f32)
    }
}

fn rho_at(f: &impl Profile, p: Vec3) -> f32 {
    f.rho(f.up().dot(p) as f64) as f32
}

/// The change of variable of one ray (see the module's comment): `depth(s) = ∫_0^s rho` and its
/// inverse `distance(u)`.
#[derive(Clone, Debug)]
pub enum Along {
    Identity,
    Height(Vertical<Height>),
    Layer(Vertical<Layer>),
    Grid(GridRay),
}

impl Along {
    /// True when `u = s` (a uniform medium).
    #[inline]
    pub fn is_identity(&self) -> bool {
        matches!(self, Along::Identity)
    }

    /// Optical depth in units of the `rho = 1` coefficients from the ray's origin to `s`
    /// (`+inf` stays `+inf` only where the field does not thin out).
    #[inline]
    pub fn depth(&self, s: f32) -> f32 {
        match self {
            Along::Identity => s,
            Along::Height(v) => v.depth(s),
            Along::Layer(v) => v.depth(s),
            Along::Grid(g) => g.depth(s),
        }
    }

    /// The distance at which the depth reaches `u`: `+inf` where it never does.
    #[inline]
    pub fn distance(&self, u: f32) -> f32 {
        match self {
            Along::Identity => u,
            Along::Height(v) => v.distance(u),
            Along::Layer(v) => v.distance(u),
            Along::Grid(g) => g.distance(u),
        }
    }

    /// The density at distance `s`.
    #[inline]
    pub fn rho(&self, s: f32) -> f32 {
        match self {
            Along::Identity => 1.0,
            Along::Height(v) => v.rho(s),
            Along::Layer(v) => v.rho(s),
            Along::Grid(g) => g.rho(s),
        }
    }
}

/// A ray through a field that varies along `up` only: its height at the origin `h0` and the
/// rate `c = up . d` at which the height changes along it. In f64: depths are differences of
/// integrals.
#[derive(Clone, Copy, Debug)]
pub struct Vertical<P> {
    profile: P,
    h0: f64,
    c: f64,
}

impl<P: Profile> Vertical<P> {
    fn new(profile: P, o: Vec3, d: Vec3) -> Self {
        let up = profile.up();
        Self {
            profile,
            h0: up.dot(o) as f64,
            c: up.dot(d) as f64,
        }
    }

    fn depth(&self, s: f32) -> f32 {
        let s = s as f64;
        if s <= 0.0 {
            return 0.0;
        }
        if self.c == 0.0 || s.is_infinite() {
            // A level ray sees one density; an endless one its limit.
            let rho = if self.c == 0.0 {
                self.profile.rho(self.h0)
            } else {
                let far = if self.c > 0.0 {
                    f64::INFINITY
                } else {
                    f64::NEG_INFINITY
                };
                return (self.profile.integral(self.h0, far) / self.c) as f32;
            };
            return (rho * s) as f32;
        }
        (self.profile.integral(self.h0, self.h0 + self.c * s) / self.c) as f32
    }

    fn distance(&self, u: f32) -> f32 {
        let u = u as f64;
        if u <= 0.0 {
            return 0.0;
        }
        if self.c == 0.0 {
            let rho = self.profile.rho(self.h0);
            return if rho > 0.0 {
                (u / rho) as f32
            } else {
                f32::INFINITY
            };
        }
        match self.profile.solve(self.h0, self.c * u) {
            Some(h) => (((h - self.h0) / self.c).max(0.0)) as f32,
            None => f32::INFINITY,
        }
    }

    fn rho(&self, s: f32) -> f32 {
        self.profile.rho(self.h0 + self.c * s as f64) as f32
    }
}

/// The unit vector along `up` (checked nonzero by [`DensityDesc::check`]).
fn unit(up: Vec3) -> Vec3 {
    up.try_normalize().unwrap_or(Vec3::Y)
}

#[cfg(test)]
mod tests;
