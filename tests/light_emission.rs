//! Lights: forward rays carry the declared power, distributed as declared. Monte-Carlo checks use
//! fixed seeds and |z| < 4.
#![allow(clippy::needless_range_loop)] // per-bin loops index several spectra at once

use std::f32::consts::PI;

use brume::geometry::{Geometry, ShapeDesc, ShapeKind, Transform};
use brume::light::{Light, LightSet};
use brume::spectrum::{SpectralGrid, Spectrum};
use glam::{Vec2, Vec3};
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64Mcg;

const NB: usize = 4;

fn spec() -> Spectrum {
    Spectrum::from_slice(&[1.0, 2.5, 0.5, 4.0])
}

fn u4(rng: &mut Pcg64Mcg) -> [f32; 4] {
    [rng.random(), rng.random(), rng.random(), rng.random()]
}

fn geometry() -> Geometry {
    Geometry::new(vec![
        ShapeDesc::new(
            ShapeKind::Box {
                size: Vec3::new(4.0, 3.0, 2.0),
            },
            Transform::IDENTITY,
        ),
        ShapeDesc::new(
            ShapeKind::Quad {
                size: Vec2::new(2.0, 1.0),
            },
            Transform::new(
                Vec3::new(0.0, 0.0, 1.5),
                Vec3::new(20.0, -30.0, 0.0),
                Vec3::ONE,
            ),
        ),
        ShapeDesc::new(
            ShapeKind::Sphere { radius: 0.5 },
            Transform::new(Vec3::new(1.0, 1.0, 0.0), Vec3::ZERO, Vec3::splat(2.0)),
        ),
    ])
    .unwrap()
}

/// Bernoulli-weighted estimate: fraction `k/n` of samples that each carry `flux`; returns
/// (estimate, standard error) of the flux through the region.
fn z_of(k: usize, n: usize, expected_fraction: f64) -> f64 {
    let f = k as f64 / n as f64;
    let se = (expected_fraction * (1.0 - expected_fraction) / n as f64)
        .sqrt()
        .max(1e-9);
    (f - expected_fraction) / se
}

#[test]
fn point_light_is_isotropic_with_declared_power() {
    let geo = geometry();
    let p = Vec3::new(0.5, -0.5, 0.2);
    let l = Light::point(p, spec());
    assert_eq!(l.power(&geo), spec());
    let mut rng = Pcg64Mcg::seed_from_u64(900);
    let axis = Vec3::new(1.0, 2.0, -0.5).normalize();
    let n = 200_000;
    let mut k = 0;
    for _ in 0..n {
        let s = l.sample_emission(&geo, u4(&mut rng));
        assert_eq!(s.ray.o, p);
        assert_eq!(s.flux, spec()); // each ray carries the whole power: E[flux] = power
        k += (s.ray.d.dot(axis) > 30f32.to_radians().cos()) as usize;
    }
    // Flux into a 30-degree cone: power x solid angle / 4 pi.
    let frac = (1.0 - 30f64.to_radians().cos()) / 2.0;
    assert!(z_of(k, n, frac).abs() < 4.0);
}

#[test]
fn spot_light_profile_and_power() {
    let geo = geometry();
    let axis = Vec3::new(0.0, -1.0, -1.0).normalize();
    let (half, soft) = (30.0f32, 10.0f32);
    let l = Light::spot(Vec3::ZERO, axis, spec(), half, soft);
    // Independent check of the declared intensity: its integral over the sphere is the power.
    let steps = 20_000;
    let mut integral = 0.0f64;
    let mut ring_fluxes = Vec::new();
    let rings = [0.0f32, 10.0, 20.0, 25.0, 28.0, 30.0, 40.0];
    for i in 0..steps {
        let th = PI * (i as f32 + 0.5) / steps as f32;
        let d = Vec3::new(th.sin(), 0.0, th.cos());
        let frame_dir = brume::geometry::sampling::Frame::new(axis).to_world(d);
        let dw = 2.0 * PI * th.sin() * PI / steps as f32;
        integral += (l.intensity(frame_dir)[1] * dw) as f64;
    }
    assert!(
        (integral - spec()[1] as f64).abs() < 1e-3 * spec()[1] as f64,
        "{integral}"
    );
    // Expected flux fraction between consecutive ring angles, by quadrature of the intensity.
    for w in rings.windows(2) {
        let (a, b) = (w[0].to_radians(), w[1].to_radians());
        let mut f = 0.0f64;
        for i in 0..2000 {
            let th = a + (b - a) * (i as f32 + 0.5) / 2000.0;
            let d = brume::geometry::sampling::Frame::new(axis).to_world(Vec3::new(
                th.sin(),
                0.0,
                th.cos(),
            ));
            f += (l.intensity(d)[0] / spec()[0] * 2.0 * PI * th.sin() * (b - a) / 2000.0) as f64;
        }
        ring_fluxes.push(f);
    }
    let mut rng = Pcg64Mcg::seed_from_u64(901);
    let n = 200_000;
    let mut counts = vec![0usize; rings.len() - 1];
    for _ in 0..n {
        let s = l.sample_emission(&geo, u4(&mut rng));
        assert_eq!(s.flux, spec());
        let th = s.ray.d.dot(axis).clamp(-1.0, 1.0).acos().to_degrees();
        assert!(th <= half + 1e-3, "no light outside the shade");
        if let Some(r) = rings.windows(2).position(|w| th >= w[0] && th < w[1]) {
            counts[r] += 1;
        }
    }
    for (r, &c) in counts.iter().enumerate() {
        assert!(
            z_of(c, n, ring_fluxes[r]).abs() < 4.0,
            "ring {r}: {} vs {}",
            c as f64 / n as f64,
            ring_fluxes[r]
        );
    }
}

#[test]
fn directional_light_irradiance_through_a_patch() {
    let geo = geometry();
    let dir = Vec3::new(0.3, -0.2, -1.0).normalize();
    let e = spec();
    let margin = 0.05;
    let l = Light::directional(dir, e).with_beam_margin(margin);
    let frame = brume::geometry::sampling::Frame::new(dir);
    let b = geo.bounds();
    let (lo, hi) = (b.min - Vec3::splat(margin), b.max + Vec3::splat(margin));
    let ext = hi - lo;
    // The beam covers exactly the silhouette of the grown bounding box: its area seen along
    // the light is sum_i |d_i| (area of the face normal to axis i).
    let silhouette =
        dir.x.abs() * ext.y * ext.z + dir.y.abs() * ext.x * ext.z + dir.z.abs() * ext.x * ext.y;
    assert!((l.power(&geo)[3] - e[3] * silhouette).abs() < 1e-4 * e[3] * silhouette);
    // A 1 m x 0.5 m patch on a plane normal to the light, offset from the box centre but inside
    // its silhouette.
    let centre = 0.5 * (lo + hi);
    let patch_c = centre + frame.s * 0.7 - frame.t * 0.4;
    let (hw, hh) = (0.5f32, 0.25f32);
    let mut rng = Pcg64Mcg::seed_from_u64(902);
    let n = 400_000;
    let mut flux_sum = Spectrum::ZERO;
    let mut k = 0;
    for _ in 0..n {
        let s = l.sample_emission(&geo, u4(&mut rng));
        assert!((s.ray.d - dir).length() < 1e-6);
        // Starts outside the box and enters it: no ray is spent on empty space.
        let inv = dir.recip();
        let (t0, t1) = ((lo - s.ray.o) * inv, (hi - s.ray.o) * inv);
        let (near, far) = (t0.min(t1).max_element(), t0.max(t1).min_element());
        assert!(
            near > 0.0 && far >= near - 1e-4,
            "{:?} misses the box",
            s.ray.o
        );
        let t = (patch_c - s.ray.o).dot(dir);
        let q = s.ray.o + dir * t - patch_c;
        if q.dot(frame.s).abs() < hw && q.dot(frame.t).abs() < hh {
            flux_sum += s.flux;
            k += 1;
        }
    }
    let area = 4.0 * hw * hh;
    let frac = area as f64 / silhouette as f64;
    assert!(z_of(k, n, frac).abs() < 4.0);
    for i in 0..NB {
        let irr = flux_sum[i] as f64 / n as f64 / area as f64;
        let se = e[i] as f64 * (frac * (1.0 - frac) / n as f64).sqrt() / frac;
        assert!(
            ((irr - e[i] as f64) / se).abs() < 4.0,
            "bin {i}: E = {irr} vs {}",
            e[i]
        );
    }
}

#[test]
fn laser_is_a_collimated_uniform_disc() {
    let geo = geometry();
    let (p, d, radius) = (
        Vec3::new(-2.0, 0.0, 1.0),
        Vec3::new(1.0, 0.2, 0.0).normalize(),
        0.01f32,
    );
    let l = Light::laser(p, d, radius, spec());
    let mut rng = Pcg64Mcg::seed_from_u64(903);
    let n = 100_000;
    let mut inner = 0;
    for _ in 0..n {
        let s = l.sample_emission(&geo, u4(&mut rng));
        assert_eq!(s.ray.d, d);
        assert_eq!(s.flux, spec());
        let off = s.ray.o - p;
        assert!(off.dot(d).abs() < 1e-6 && off.length() <= radius * 1.0001);
        inner += (off.length() < 0.5 * radius) as usize;
    }
    assert!(
        z_of(inner, n, 0.25).abs() < 4.0,
        "uniform over the beam's cross-section"
    );
}

#[test]
fn area_lights_are_lambertian_with_declared_power() {
    let geo = geometry();
    let radiance = spec();
    // One-sided quad: power L pi A, outward hemisphere only, cosine distributed, uniform positions.
    let quad = Light::area(1, radiance, false);
    assert!((geo.area(1) - 2.0).abs() < 1e-5);
    assert!((quad.power(&geo)[0] - radiance[0] * PI * 2.0).abs() < 1e-4);
    let t = Transform::new(
        Vec3::new(0.0, 0.0, 1.5),
        Vec3::new(20.0, -30.0, 0.0),
        Vec3::ONE,
    );
    let n_out = t.normal(Vec3::Z);
    let mut rng = Pcg64Mcg::seed_from_u64(904);
    let n = 200_000;
    let (mut narrow, mut left, mut corner) = (0, 0, 0);
    for _ in 0..n {
        let s = quad.sample_emission(&geo, u4(&mut rng));
        assert_eq!(s.flux, quad.power(&geo));
        let c = s.ray.d.dot(n_out);
        assert!(c > 0.0, "one-sided emits outward only");
        narrow += (c > 45f32.to_radians().cos()) as usize;
        let lp = t.inv_point(s.ray.o);
        assert!(lp.z.abs() < 1e-3 && lp.x.abs() <= 1.0 + 1e-3 && lp.y.abs() <= 0.5 + 1e-3);
        left += (lp.x < 0.0) as usize;
        corner += (lp.x > 0.5 && lp.y > 0.25) as usize;
    }
    // Lambertian: the fraction of flux within 45 degrees of the normal is sin^2(45) = 1/2.
    assert!(z_of(narrow, n, 0.5).abs() < 4.0);
    assert!(z_of(left, n, 0.5).abs() < 4.0);
    assert!(z_of(corner, n, 0.0625).abs() < 4.0);

    // Two-sided sphere (radius 0.5 scaled by 2): power 2 L pi A, half the flux goes inward.
    let sph = Light::area(2, radiance, true);
    assert!((geo.area(2) - 4.0 * PI).abs() < 1e-4);
    assert!((sph.power(&geo)[2] - 2.0 * radiance[2] * PI * 4.0 * PI).abs() < 1e-3);
    let centre = Vec3::new(1.0, 1.0, 0.0);
    let mut inward = 0;
    let mut upper = 0;
    for _ in 0..n {
        let s = sph.sample_emission(&geo, u4(&mut rng));
        let nrm = (s.ray.o - centre).normalize();
        assert!(((s.ray.o - centre).length() - 1.0).abs() < 1e-3);
        inward += (s.ray.d.dot(nrm) < 0.0) as usize;
        upper += (nrm.z > 0.5) as usize;
    }
    assert!(z_of(inward, n, 0.5).abs() < 4.0);
    // Uniform over the sphere: area fraction of the cap z > 0.5 is 1/4.
    assert!(z_of(upper, n, 0.25).abs() < 4.0);

    // Radiance seen by camera rays: only on the emitting side of a one-sided light.
    let h = brume::geometry::Hit {
        t: 1.0,
        p: Vec3::ZERO,
        ng: n_out,
        ns: n_out,
        uv: Vec2::ZERO,
        shape: 1,
    };
    assert_eq!(quad.radiance(&h, n_out), radiance);
    assert_eq!(quad.radiance(&h, -n_out), Spectrum::ZERO);
    assert_eq!(sph.radiance(&h, -n_out), radiance);
    assert_eq!(
        Light::point(Vec3::ZERO, spec()).radiance(&h, n_out),
        Spectrum::ZERO
    );
}

#[test]
fn light_set_shares_rays_in_proportion_to_power() {
    let geo = geometry();
    let lights = vec![
        Light::point(Vec3::new(1.0, 0.0, 0.0), spec()),
        Light::point(Vec3::new(2.0, 0.0, 0.0), spec() * 3.0),
        Light::laser(
            Vec3::new(3.0, 0.0, 0.0),
            Vec3::X,
            0.1,
            Spectrum::from_slice(&[0.0, 0.0, 5.0, 0.0]),
        ),
        Light::point(Vec3::new(4.0, 0.0, 0.0), Spectrum::ZERO),
    ];
    let set = LightSet::new(lights.clone(), &geo, &SpectralGrid::new(NB, 400.0, 700.0));
    let total: f32 = lights.iter().map(|l| l.power(&geo).sum()).sum();
    let mut rng = Pcg64Mcg::seed_from_u64(905);
    let n = 200_000;
    let mut sums = vec![Spectrum::ZERO; 4];
    let mut counts = [0usize; 4];
    for _ in 0..n {
        let u = [
            rng.random(),
            rng.random(),
            rng.random(),
            rng.random(),
            rng.random(),
        ];
        let (_, s) = set.sample(&geo, u).unwrap();
        let i = (s.ray.o.x.round() as usize) - 1;
        sums[i] += s.flux;
        counts[i] += 1;
    }
    assert_eq!(counts[3], 0, "a dark light is never picked");
    for (i, l) in lights.iter().enumerate().take(3) {
        let p = l.power(&geo).sum() as f64 / total as f64;
        assert!(z_of(counts[i], n, p).abs() < 4.0);
        // E[flux] per light and bin equals its power.
        for b in 0..NB {
            let want = l.power(&geo)[b] as f64;
            let got = sums[i][b] as f64 / n as f64;
            let se = want * ((1.0 - p) / (p * n as f64)).sqrt();
            assert!(
                (got - want).abs() <= 4.0 * se + 1e-9,
                "light {i} bin {b}: {got} vs {want}"
            );
        }
    }
    let grid = SpectralGrid::new(NB, 400.0, 700.0);
    assert!(
        LightSet::new(vec![], &geo, &grid)
            .sample(&geo, [0.5; 5])
            .is_none()
    );
}

#[path = "light_emission/photometric.rs"]
mod photometric;

#[path = "light_emission/ies.rs"]
mod ies_profiles;
