//! Which light a next-event sample goes to (`integrator.light_pick`).
//!
//! Picking lights in proportion to their total power starves a light that is weak in total but
//! strong where the receiver is: a 4 W spot on a wall beside a directional fill whose "power" is
//! its irradiance times the whole scene's cross-section got 4 % of the samples, and its spot on
//! the wall rendered as salt and pepper (smoke-plume: 77 % of the image's squared error in 1 %
//! of the pixels). `"local"` (the default) picks each light in proportion to an estimate of
//! what it sends to the receiver, unshadowed and unattenuated:
//!
//! - at a point x (surface gathers, sensors): a parallel light's irradiance E; a point or spot
//!   light's intensity towards x over distance², I(x)/d²; an area light of power Φ and area A
//!   as a disc seen on axis, Φ / (π d² + A) (d from its centre);
//! - along a camera segment (single scattering): the integral of the same over the segment
//!   (the scattering coefficient is common to every light): E len for a parallel light, and
//!   for the others I (θ_b - θ_a) / h, the integral of I / r² along the line at distance h from
//!   the light (the equiangular sampler's normalisation), over the part of the segment inside a
//!   spot's cone, with a spot's mean intensity in its cone, and h² + A/π for an area light.
//!
//! The estimate ignores occlusion and media, so a floor `FLOOR / L` is mixed in for each of the
//! L handled lights: every light keeps a positive probability wherever it is handled, which is
//! all the estimator's unbiasedness needs (each sample is divided by its light's probability at
//! that receiver); the estimate only decides the variance. The probability is a function of the
//! receiver alone, so MIS weights that need it ([`Direct::emission_weight`]) recompute it at the
//! same point.

use std::f32::consts::PI;

use glam::Vec3;

use super::Direct;
use super::sampling::cone_interval;
use crate::geometry::{Geometry, Ray};
use crate::integrator::settings::LightPick;
use crate::light::Light;
use crate::spectrum::SpectralGrid;
use crate::world::Scene;

/// Share of the picks spread evenly over the handled lights whatever the estimate says.
pub const FLOOR: f32 = 0.1;

/// Where the light of a next-event sample is received.
#[derive(Clone, Copy, Debug)]
pub enum Receiver {
    /// A point: a surface gather or an illuminance sensor.
    Point(Vec3),
    /// A camera segment `o + d t`, `t` in `[0, len]`.
    Segment { o: Vec3, d: Vec3, len: f32 },
}

impl Receiver {
    /// The segment of `ray` from its origin to `len`.
    pub fn along(ray: &Ray, len: f32) -> Self {
        Receiver::Segment {
            o: ray.o,
            d: ray.d,
            len,
        }
    }
}

/// What the local estimate needs of one handled light, computed once per render.
#[derive(Clone, Debug)]
pub(super) enum Reach {
    /// A parallel light of (spectrally summed) irradiance `e`.
    Parallel { e: f32 },
    /// A point or spot light of total power `power` at `position`; a spot's intensity comes
    /// from the scene's light, its cone from `cone` (axis, cosine of the edge) and its mean
    /// intensity in the cone is `mean` (power over the cone's solid angle).
    Point {
        position: Vec3,
        power: f32,
        cone: Option<(Vec3, f32)>,
        mean: f32,
    },
    /// An area light as a disc at `centre`: on-axis intensity `intensity` (Φ/π), `r2` = A/π.
    Surface {
        centre: Vec3,
        intensity: f32,
        r2: f32,
    },
    /// A light next-event estimation cannot sample (a laser): its power, the same everywhere.
    Fixed { w: f32 },
}

impl Reach {
    /// The summary of `light` for the local estimate.
    pub(super) fn of(light: &Light, geometry: &Geometry, grid: &SpectralGrid) -> Reach {
        let sum = |s| grid.weighted_sum(s) as f32;
        match light {
            Light::Directional { irradiance, .. } => Reach::Parallel { e: sum(irradiance) },
            Light::Point { position, power } => Reach::Point {
                position: *position,
                power: sum(power),
                cone: None,
                mean: sum(power) / (4.0 * PI),
            },
            Light::Spot {
                position,
                frame,
                power,
                profile,
            } => {
                let cos = profile.cos_edge();
                let solid = 2.0 * PI * (1.0 - cos);
                Reach::Point {
                    position: *position,
                    power: sum(power),
                    cone: profile.cone_cos().map(|c| (frame.n, c)),
                    mean: if solid > 0.0 { sum(power) / solid } else { 0.0 },
                }
            }
            Light::Area { shape, .. } => {
                // The centre as the mean of a 4 x 4 lattice of area samples: any shape, no
                // shape-specific code, and exact for the flat shapes lights usually are.
                let mut c = Vec3::ZERO;
                for i in 0..16 {
                    let u =
                        glam::Vec2::new(((i % 4) as f32 + 0.5) / 4.0, ((i / 4) as f32 + 0.5) / 4.0);
                    c += geometry.sample_point(*shape, u).0;
                }
                let area = geometry.area(*shape);
                Reach::Surface {
                    centre: c / 16.0,
                    intensity: sum(&light.power(geometry)) / PI,
                    r2: area / PI,
                }
            }
            Light::Laser { power, .. } => Reach::Fixed { w: sum(power) },
        }
    }

    /// The estimate of what this light (scene light `light`) sends to `r`; 0 where it sends
    /// nothing, non-negative, possibly infinite (a segment through a point light).
    fn estimate(&self, light: &Light, r: &Receiver) -> f32 {
        match (self, *r) {
            (Reach::Parallel { e }, Receiver::Point(_)) => *e,
            (Reach::Parallel { e }, Receiver::Segment { len, .. }) => *e * len,
            (
                Reach::Point {
                    position, power, ..
                },
                Receiver::Point(x),
            ) => {
                let v = x - *position;
                let d2 = v.length_squared();
                let fraction = match light {
                    Light::Spot { frame, profile, .. } if d2 > 0.0 => {
                        profile.fraction(frame.to_local(v / d2.sqrt()))
                    }
                    Light::Spot { .. }
                    | Light::Point { .. }
                    | Light::Directional { .. }
                    | Light::Laser { .. }
                    | Light::Area { .. } => 1.0 / (4.0 * PI),
                };
                *power * fraction / d2
            }
            (
                Reach::Point {
                    position,
                    cone,
                    mean,
                    ..
                },
                Receiver::Segment { o, d, len },
            ) => {
                let (a, b) = match cone {
                    Some((axis, cos)) => {
                        match cone_interval(o, d, 0.0, len, *position, *axis, *cos) {
                            Some(ab) => ab,
                            None => return 0.0,
                        }
                    }
                    None => (0.0, len),
                };
                *mean * inverse_square_integral(o, d, (a, b), *position, 0.0)
            }
            (
                Reach::Surface {
                    centre,
                    intensity,
                    r2,
                },
                Receiver::Point(x),
            ) => *intensity / (x.distance_squared(*centre) + *r2),
            (
                Reach::Surface {
                    centre,
                    intensity,
                    r2,
                },
                Receiver::Segment { o, d, len },
            ) => *intensity * inverse_square_integral(o, d, (0.0, len), *centre, *r2),
            (Reach::Fixed { w }, Receiver::Point(_) | Receiver::Segment { .. }) => *w,
        }
    }
}

/// `∫_a^b dt / (|o + d t - c|² + r2)`: with the line's closest approach `t0` and distance `h`
/// (`h² + r2` floored so a segment through a point light stays finite),
/// `(atan((b - t0)/h') - atan((a - t0)/h')) / h'`.
fn inverse_square_integral(o: Vec3, d: Vec3, (a, b): (f32, f32), c: Vec3, r2: f32) -> f32 {
    let v = c - o;
    let t0 = v.dot(d);
    let scale = v.length() + b.abs();
    let h2 = ((v.length_squared() - t0 * t0).max(0.0) + r2).max((1e-6 * scale).powi(2));
    let h = h2.sqrt();
    (((b - t0) / h).atan() - ((a - t0) / h).atan()).max(0.0) / h
}

/// The picks of one receiver: the sum of the lights' estimates there, computed once for all
/// of its samples.
pub(crate) struct Picking<'a> {
    direct: &'a Direct,
    scene: &'a Scene,
    r: Receiver,
    /// The sum of the estimates; None where the power pick applies (the `power` rule, one
    /// light, or a degenerate sum).
    total: Option<f32>,
}

impl Picking<'_> {
    /// A handled light from a uniform `u`: (index, probability).
    pub(crate) fn pick(&self, u: f32) -> (u32, f32) {
        let d = self.direct;
        if d.picks.len() == 1 {
            return (d.picks[0].0, 1.0);
        }
        let Some(total) = self.total else {
            return d.pick(u);
        };
        let mut acc = 0.0;
        let last = d.picks.len() - 1;
        for (k, &(j, _)) in d.picks.iter().enumerate() {
            let p = d.local_probability(self.scene, &self.r, j, total);
            acc += p;
            if u < acc || k == last {
                return (j, p);
            }
        }
        unreachable!("the loop returns at its last light")
    }

    /// The probability that [`Self::pick`] picks light `light`.
    pub(crate) fn probability(&self, light: u32) -> f32 {
        let d = self.direct;
        if !d.handles(light) {
            return 0.0;
        }
        if d.picks.len() == 1 {
            return 1.0;
        }
        match self.total {
            Some(total) => d.local_probability(self.scene, &self.r, light, total),
            None => d.probability(light),
        }
    }
}

impl Direct {
    /// The picks of samples received at `r`.
    pub(crate) fn picking<'a>(&'a self, scene: &'a Scene, r: Receiver) -> Picking<'a> {
        let total = match self.pick {
            LightPick::Local if self.picks.len() > 1 => {
                Some(self.local_total(scene, &r)).filter(|t| *t > 0.0 && t.is_finite())
            }
            LightPick::Local | LightPick::Power => None,
        };
        Picking {
            direct: self,
            scene,
            r,
            total,
        }
    }

    /// The probability that [`Picking::pick`] picks light `light` for a sample at `r`.
    pub(crate) fn probability_at(&self, scene: &Scene, r: &Receiver, light: u32) -> f32 {
        self.picking(scene, *r).probability(light)
    }

    /// The sum of the handled lights' estimates at `r`.
    fn local_total(&self, scene: &Scene, r: &Receiver) -> f32 {
        let lights = scene.lights.lights();
        self.picks
            .iter()
            .map(|&(j, _)| self.reach[j as usize].estimate(&lights[j as usize], r))
            .sum()
    }

    /// `(1 - FLOOR) w_j / total + FLOOR / L` for handled light `j`.
    fn local_probability(&self, scene: &Scene, r: &Receiver, j: u32, total: f32) -> f32 {
        let w = self.reach[j as usize].estimate(&scene.lights.lights()[j as usize], r);
        (1.0 - FLOOR) * (w / total) + FLOOR / self.picks.len() as f32
    }
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    use rand::{Rng as _, SeedableRng};

    use super::*;
    use crate::integrator::settings::IntegratorDesc;

    /// Four handled lights of every kind the estimate distinguishes, and a spot that points
    /// away from the receivers below.
    const LIGHTS: &str = r#"
[camera]
type = "perspective"
position = [0, 1, 4]
look_at = [0, 1, 0]
[media.fog]
sigma_s = 0.2
[[shapes]]
type = "box"
size = [4, 2, 4]
interior = "fog"
transform = { translate = [0, 1, 0] }
[[shapes]]
type = "quad"
size = [0.5, 0.5]
emit = 2.0
transform = { rotate = [90, 0, 0], translate = [1.5, 2.5, 0] }
[[lights]]
type = "point"
position = [0, 2, 0]
power = 50.0
[[lights]]
type = "spot"
position = [-1.5, 2, 0]
direction = [1.5, -2, 0]
angle = 20.0
power = 20.0
[[lights]]
type = "directional"
direction = [0.3, -1, 0.2]
irradiance = 1.0
[[lights]]
type = "spot"
position = [0, 2, -1.9]
direction = [0, 1, 0]
angle = 10.0
power = 20.0
"#;

    fn setup() -> (crate::world::Scene, Direct) {
        let loaded = crate::scene::load_str(LIGHTS, Path::new("pick.toml"), &[]).expect("loads");
        let scene = crate::scene::build(&loaded).expect("builds");
        let direct = Direct::from_desc(&IntegratorDesc::default(), &scene).expect("nee");
        (scene, direct)
    }

    fn receivers() -> Vec<Receiver> {
        vec![
            Receiver::Point(Vec3::ZERO),
            Receiver::Point(Vec3::new(1.4, 2.2, 0.1)),
            Receiver::Point(Vec3::new(-1.4, 1.9, 0.0)),
            Receiver::Segment {
                o: Vec3::new(0.0, 1.0, 2.0),
                d: Vec3::NEG_Z,
                len: 4.0,
            },
            // Through the point light itself: the estimate must stay finite.
            Receiver::Segment {
                o: Vec3::new(-1.0, 2.0, 0.0),
                d: Vec3::X,
                len: 2.0,
            },
        ]
    }

    /// The probabilities at a receiver sum to 1, none is below the floor, and a light that
    /// sends nothing (the spot pointing up, at points below it) gets exactly the floor.
    #[test]
    fn probabilities_sum_to_one_above_the_floor() {
        let (scene, direct) = setup();
        let l = direct.picks.len();
        assert_eq!(l, 5, "four lights and the emitting quad");
        for r in receivers() {
            let p: Vec<f32> = (0..5)
                .map(|j| direct.probability_at(&scene, &r, j))
                .collect();
            let sum: f32 = p.iter().sum();
            assert!((sum - 1.0).abs() < 1e-5, "{r:?}: {p:?}");
            for &x in &p {
                assert!(
                    x.is_finite() && x >= FLOOR / l as f32 * (1.0 - 1e-6),
                    "{r:?}: {p:?}"
                );
            }
        }
        let below = Receiver::Point(Vec3::new(0.0, 0.0, -1.0));
        let up = direct.probability_at(&scene, &below, 4);
        assert!((up - FLOOR / l as f32).abs() < 1e-7, "{up}");
    }

    /// Pearson chi-square of 200 000 picks per receiver against `probability_at`, with the
    /// probability `Picking::pick` returns equal to it (4 degrees of freedom: the 1e-4 level is 23.5).
    #[test]
    fn picks_follow_their_probabilities() {
        let (scene, direct) = setup();
        let mut rng = rand::rngs::SmallRng::seed_from_u64(3);
        let n = 200_000;
        for r in receivers() {
            let p: Vec<f64> = (0..5)
                .map(|j| direct.probability_at(&scene, &r, j) as f64)
                .collect();
            let mut count = [0u64; 5];
            let picking = direct.picking(&scene, r);
            for _ in 0..n {
                let (j, pj) = picking.pick(rng.random());
                assert!((pj as f64 - p[j as usize]).abs() < 1e-6);
                count[j as usize] += 1;
            }
            let chi2: f64 = (0..5)
                .map(|j| {
                    let e = p[j] * n as f64;
                    (count[j] as f64 - e).powi(2) / e
                })
                .sum();
            assert!(chi2 < 23.5, "{r:?}: chi2 {chi2}, counts {count:?}, p {p:?}");
        }
        // The power picks are the same everywhere: the local ones are not.
        let (a, b) = (receivers()[0], receivers()[1]);
        assert!(
            (direct.probability_at(&scene, &a, 0) - direct.probability_at(&scene, &b, 0)).abs()
                > 0.1
        );
    }

    /// The closed form of the inverse-square integral against midpoint quadrature.
    #[test]
    fn inverse_square_integral_matches_quadrature() {
        let c = Vec3::new(0.3, 1.0, -0.2);
        let o = Vec3::new(-1.0, 0.2, 0.5);
        let d = Vec3::new(1.0, 0.3, -0.4).normalize();
        for (a, b, r2) in [(0.0, 3.0, 0.0), (0.5, 1.2, 0.0), (0.0, 3.0, 0.08)] {
            let got = inverse_square_integral(o, d, (a, b), c, r2) as f64;
            let k = 100_000;
            let h = (b - a) as f64 / k as f64;
            let want: f64 = (0..k)
                .map(|i| {
                    let t = a as f64 + (i as f64 + 0.5) * h;
                    let x = o + d * t as f32;
                    h / (x.distance_squared(c) as f64 + r2 as f64)
                })
                .sum();
            assert!(
                (got / want - 1.0).abs() < 1e-4,
                "{a} {b} {r2}: {got} vs {want}"
            );
        }
    }
}
