//! Lambert, mirror, glossy and blend: white furnace, sampling against independent quadrature,
//! pdfs, reciprocity. Monte-Carlo comparisons use fixed seeds and |z| < 4.

use std::f32::consts::{PI, TAU};
use std::sync::Arc;

use brume::geometry::Hit;
use brume::material::{BlendWeight, LobeKind, Material, Texture};
use brume::spectrum::Spectrum;
use glam::{Vec2, Vec3};
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64Mcg;

const NB: usize = 8;
const Z: f64 = 4.0;

fn hit(n: Vec3) -> Hit {
    let n = n.normalize();
    Hit {
        t: 1.0,
        p: Vec3::ZERO,
        ng: n,
        ns: n,
        uv: Vec2::new(0.3, 0.7),
        shape: 0,
    }
}

/// Direction at polar angle `theta_deg` from `n`, on `n`'s side (or the other side if `below`).
fn dir_at(n: Vec3, theta_deg: f32, below: bool) -> Vec3 {
    let n = n.normalize();
    let t = n.cross(Vec3::new(0.6, 0.8, 0.0)).normalize();
    let th = theta_deg.to_radians();
    let d = n * th.cos() + t * th.sin();
    if below { -d } else { d }
}

/// Running mean and standard error per bin.
#[derive(Default)]
struct Stats {
    n: f64,
    s: [f64; NB],
    s2: [f64; NB],
}
impl Stats {
    fn add(&mut self, v: &Spectrum) {
        self.n += 1.0;
        for i in 0..NB {
            let x = v[i] as f64;
            self.s[i] += x;
            self.s2[i] += x * x;
        }
    }
    fn add_zero(&mut self) {
        self.n += 1.0;
    }
    fn mean(&self, i: usize) -> f64 {
        self.s[i] / self.n
    }
    fn se(&self, i: usize) -> f64 {
        let m = self.mean(i);
        ((self.s2[i] / self.n - m * m).max(0.0) / self.n).sqrt()
    }
}

/// Independent estimate of the integral of g(wi) over the sphere: uniform directions.
fn sphere_quadrature(rng: &mut Pcg64Mcg, n: usize, g: impl Fn(Vec3) -> Spectrum) -> Stats {
    let mut st = Stats::default();
    for _ in 0..n {
        let z = 1.0 - 2.0 * rng.random::<f32>();
        let phi = TAU * rng.random::<f32>();
        let s = (1.0 - z * z).max(0.0).sqrt();
        let d = Vec3::new(s * phi.cos(), s * phi.sin(), z);
        st.add(&(g(d) * (4.0 * PI)));
    }
    st
}

fn albedo() -> Spectrum {
    Spectrum::from_slice(&[0.1, 0.2, 0.35, 0.5, 0.6, 0.75, 0.9, 1.0])
}

fn assert_z(a: f64, sa: f64, b: f64, sb: f64, what: &str) {
    let se = (sa * sa + sb * sb).sqrt().max(1e-9);
    let z = (a - b) / se;
    assert!(z.abs() < Z, "{what}: {a} vs {b}, z = {z}");
}

/// E[weight] of `sample` against the quadrature of f |cos| (and pdf consistency).
fn check_sampling(m: &Material, h: &Hit, wo: Vec3, seed: u64, n: usize, label: &str) {
    let mut rng = Pcg64Mcg::seed_from_u64(seed);
    let q = sphere_quadrature(&mut rng, n, |wi| m.eval(wo, wi, h) * wi.dot(h.ns).abs());
    let mut st = Stats::default();
    let mut produced = 0usize;
    let pdf_q = sphere_quadrature(&mut rng, n, |wi| Spectrum::splat(m.pdf(wo, wi, h), 1));
    for _ in 0..n {
        let u = glam::Vec3::new(rng.random(), rng.random(), rng.random());
        match m.sample(wo, h, u) {
            Some(s) => {
                produced += 1;
                let p = m.pdf(wo, s.wi, h);
                assert!(
                    (p - s.pdf).abs() <= 1e-3 * p.max(1e-3),
                    "{label}: pdf {p} vs {}",
                    s.pdf
                );
                st.add(&s.weight);
            }
            None => st.add_zero(),
        }
    }
    for i in 0..NB {
        assert_z(
            st.mean(i),
            st.se(i),
            q.mean(i),
            q.se(i),
            &format!("{label} bin {i}"),
        );
    }
    // The pdf integrates to the probability that sampling produces a direction.
    let frac = produced as f64 / n as f64;
    let frac_se = (frac * (1.0 - frac) / n as f64).sqrt();
    assert_z(
        pdf_q.mean(0),
        pdf_q.se(0),
        frac,
        frac_se,
        &format!("{label} pdf normalisation"),
    );
}

#[test]
fn lambert_furnace_equals_albedo_and_sampling_matches_eval() {
    let m = Material::lambert(albedo());
    for (k, (n, theta, below)) in [
        (Vec3::Z, 0.0, false),
        (Vec3::new(0.3, -0.2, 1.0), 60.0, false),
        (Vec3::new(-0.5, 0.1, 0.4), 85.0, true),
    ]
    .into_iter()
    .enumerate()
    {
        let h = hit(n);
        let wo = dir_at(n, theta, below);
        let mut rng = Pcg64Mcg::seed_from_u64(100 + k as u64);
        let q = sphere_quadrature(&mut rng, 400_000, |wi| {
            m.eval(wo, wi, &h) * wi.dot(h.ns).abs()
        });
        for i in 0..NB {
            assert_z(
                q.mean(i),
                q.se(i),
                albedo()[i] as f64,
                0.0,
                "lambert furnace",
            );
        }
        check_sampling(&m, &h, wo, 200 + k as u64, 200_000, "lambert");
        assert_eq!(m.diffuse_probability(wo, &h), 1.0);
        assert!(m.sample_nondiffuse(wo, &h, Vec3::splat(0.5)).is_none());
        let s = m.sample(wo, &h, Vec3::new(0.2, 0.9, 0.1)).unwrap();
        assert_eq!(s.kind, LobeKind::Diffuse);
        assert!(
            s.wi.dot(h.ng) * wo.dot(h.ng) > 0.0,
            "reflects into wo's side"
        );
    }
}

#[test]
fn glossy_furnace_never_exceeds_one() {
    let white = Spectrum::splat(1.0, NB);
    for (k, rough) in [0.02f32, 0.1, 0.3, 0.6, 1.0].into_iter().enumerate() {
        let m = Material::glossy(white, 1.5, rough, NB);
        let h = hit(Vec3::Z);
        for theta in [0.0f32, 30.0, 60.0, 80.0, 89.0] {
            let wo = dir_at(Vec3::Z, theta, false);
            let mut rng = Pcg64Mcg::seed_from_u64(300 + k as u64);
            let mut st = Stats::default();
            for _ in 0..100_000 {
                let u = Vec3::new(rng.random(), rng.random(), rng.random());
                match m.sample(wo, &h, u) {
                    Some(s) => st.add(&s.weight),
                    None => st.add_zero(),
                }
            }
            let (r, se) = (st.mean(0), st.se(0));
            assert!(
                r < 1.0 + Z * se,
                "roughness {rough}, theta {theta}: R = {r} +- {se}"
            );
            // Nor absorbing much: single-scattering GGX loses some energy at grazing angles.
            eprintln!("glossy furnace: roughness {rough} theta {theta}: R = {r:.3} +- {se:.3}");
            assert!(
                theta > 60.0 || r > 0.7,
                "roughness {rough}, theta {theta}: R = {r}"
            );
        }
    }
}

#[test]
fn glossy_sampling_matches_eval() {
    for (k, rough) in [0.15f32, 0.4, 0.8].into_iter().enumerate() {
        let m = Material::glossy(albedo(), 1.5, rough, NB);
        let n = Vec3::new(0.2, 0.1, 1.0);
        let h = hit(n);
        for (j, theta) in [10.0f32, 45.0, 75.0].into_iter().enumerate() {
            let wo = dir_at(n, theta, j == 2);
            check_sampling(
                &m,
                &h,
                wo,
                400 + 10 * k as u64 + j as u64,
                400_000,
                &format!("glossy {rough} {theta}"),
            );
        }
    }
}

#[test]
fn glossy_split_into_diffuse_and_nondiffuse_parts() {
    let m = Material::glossy(albedo(), 1.5, 0.3, NB);
    let h = hit(Vec3::Z);
    let wo = dir_at(Vec3::Z, 40.0, false);
    let mut rng = Pcg64Mcg::seed_from_u64(500);
    let spec = sphere_quadrature(&mut rng, 400_000, |wi| {
        (m.eval(wo, wi, &h) - m.eval_diffuse(wo, wi, &h)) * wi.z.abs()
    });
    let mut st = Stats::default();
    for _ in 0..200_000 {
        let u = Vec3::new(rng.random(), rng.random(), rng.random());
        match m.sample_nondiffuse(wo, &h, u) {
            Some(s) => {
                assert_eq!(s.kind, LobeKind::Glossy);
                st.add(&s.weight)
            }
            None => st.add_zero(),
        }
    }
    for i in 0..NB {
        assert_z(
            st.mean(i),
            st.se(i),
            spec.mean(i),
            spec.se(i),
            "glossy nondiffuse",
        );
    }
    let p = m.diffuse_probability(wo, &h);
    assert!(p > 0.0 && p < 1.0);
}

#[test]
fn reciprocity() {
    let mut rng = Pcg64Mcg::seed_from_u64(600);
    let mats = [
        Material::lambert(albedo()),
        Material::glossy(albedo(), 1.6, 0.25, NB),
        Material::glossy(albedo(), 1.3, 0.8, NB),
    ];
    let h = hit(Vec3::new(0.1, 0.3, 1.0));
    let mut nonzero = 0;
    for _ in 0..10_000 {
        let a = dir_at(h.ng, rng.random::<f32>() * 89.0, false);
        let b = glam::Quat::from_axis_angle(h.ng, rng.random::<f32>() * TAU)
            * dir_at(h.ng, rng.random::<f32>() * 89.0, false);
        for m in &mats {
            let (f1, f2) = (m.eval(a, b, &h), m.eval(b, a, &h));
            for i in 0..NB {
                assert!(
                    (f1[i] - f2[i]).abs() <= 1e-4 * f1[i].abs().max(1e-3),
                    "{m:?}: {} vs {}",
                    f1[i],
                    f2[i]
                );
            }
            nonzero += (f1[0] > 0.0) as usize;
        }
    }
    assert!(nonzero > 25_000);
}

#[test]
fn mirror_reflects_exactly_and_reciprocally() {
    let r = albedo();
    let m = Material::mirror(r);
    let n = Vec3::new(0.3, -0.4, 1.0).normalize();
    let h = hit(n);
    for (theta, below) in [(0.0, false), (35.0, false), (80.0, true)] {
        let wo = dir_at(n, theta, below);
        let s = m.sample(wo, &h, Vec3::splat(0.3)).unwrap();
        assert_eq!(s.kind, LobeKind::Specular);
        assert_eq!(s.weight, r);
        assert!((s.wi.dot(n) - wo.dot(n)).abs() < 1e-6, "equal angles");
        assert!(
            (s.wi + wo).cross(n).length() < 1e-5,
            "in the plane of incidence"
        );
        let back = m.sample_nondiffuse(s.wi, &h, Vec3::splat(0.7)).unwrap();
        assert!((back.wi - wo).length() < 1e-5, "reciprocal path");
        assert_eq!(m.eval(wo, s.wi, &h), Spectrum::ZERO);
        assert_eq!(m.diffuse_probability(wo, &h), 0.0);
    }
}

fn blend(a: Material, b: Material, w: f32) -> Material {
    Material::blend(a, b, BlendWeight::Constant(w))
}

/// E[weight] of camera-side non-diffuse sampling against the quadrature of the non-diffuse f.
fn check_nondiffuse(m: &Material, h: &Hit, wo: Vec3, seed: u64, n: usize, label: &str) {
    let mut rng = Pcg64Mcg::seed_from_u64(seed);
    let q = sphere_quadrature(&mut rng, n, |wi| {
        (m.eval(wo, wi, h) - m.eval_diffuse(wo, wi, h)) * wi.dot(h.ns).abs()
    });
    let mut st = Stats::default();
    for _ in 0..n {
        let u = Vec3::new(rng.random(), rng.random(), rng.random());
        match m.sample_nondiffuse(wo, h, u) {
            Some(s) => st.add(&s.weight),
            None => st.add_zero(),
        }
    }
    for i in 0..NB {
        assert_z(
            st.mean(i),
            st.se(i),
            q.mean(i),
            q.se(i),
            &format!("{label} non-diffuse bin {i}"),
        );
    }
}

/// A blend's forward sampling against its evaluation (quadrature, per-sample pdf, pdf
/// normalisation), and its camera-side split (non-diffuse sampling against the non-diffuse f):
/// the two sides of the integrator see one BSDF. A weight the sampling forgot, or a pdf
/// missing the other part, fails here.
#[test]
fn blend_sampling_matches_eval_on_both_sides() {
    let cases = [
        (
            blend(
                Material::lambert(albedo()),
                Material::glossy(albedo(), 1.5, 0.3, NB),
                0.35,
            ),
            "lambert + glossy",
        ),
        (
            blend(
                Material::glossy(albedo(), 1.4, 0.15, NB),
                Material::glossy(Spectrum::splat(0.6, NB), 1.7, 0.7, NB),
                0.6,
            ),
            "glossy + glossy",
        ),
        (
            blend(
                Material::lambert(Spectrum::splat(0.3, NB)),
                blend(
                    Material::lambert(albedo()),
                    Material::glossy(albedo(), 1.5, 0.2, NB),
                    0.5,
                ),
                0.7,
            ),
            "nested",
        ),
    ];
    let n = Vec3::new(0.2, -0.1, 1.0);
    let h = hit(n);
    for (k, (m, label)) in cases.iter().enumerate() {
        for (j, theta) in [15.0f32, 65.0].into_iter().enumerate() {
            let wo = dir_at(n, theta, j == 1);
            let seed = 700 + 10 * k as u64 + j as u64;
            check_sampling(m, &h, wo, seed, 400_000, label);
            check_nondiffuse(m, &h, wo, seed + 5, 400_000, label);
        }
    }
}

/// A part with a delta lobe: forward sampling returns, on average, (1 - w) albedo + w R, and
/// the camera side's non-diffuse sampling the mirror's share w R exactly.
#[test]
fn blend_with_a_mirror_reflects_each_share() {
    let r = Spectrum::splat(0.8, NB);
    let w = 0.25f32;
    let m = blend(Material::lambert(albedo()), Material::mirror(r), w);
    let h = hit(Vec3::Z);
    let wo = dir_at(Vec3::Z, 30.0, false);
    let mut rng = Pcg64Mcg::seed_from_u64(800);
    let mut st = Stats::default();
    let mut mirror = 0usize;
    let n = 200_000;
    for _ in 0..n {
        let u = Vec3::new(rng.random(), rng.random(), rng.random());
        match m.sample(wo, &h, u) {
            Some(s) => {
                if s.kind == LobeKind::Specular {
                    mirror += 1;
                    assert!((s.pdf - w).abs() < 1e-6, "delta pick probability {}", s.pdf);
                }
                st.add(&s.weight)
            }
            None => st.add_zero(),
        }
    }
    for i in 0..NB {
        let expect = (1.0 - w as f64) * albedo()[i] as f64 + w as f64 * r[i] as f64;
        assert_z(st.mean(i), st.se(i), expect, 0.0, "lambert + mirror");
    }
    let frac = mirror as f64 / n as f64;
    assert_z(
        frac,
        (frac * (1.0 - frac) / n as f64).sqrt(),
        w as f64,
        0.0,
        "mirror share",
    );
    // Camera side: only the mirror is non-diffuse; its sample carries w R, chosen always.
    let s = m
        .sample_nondiffuse(wo, &h, Vec3::splat(0.5))
        .expect("mirror part");
    assert!((s.weight[0] - w * r[0]).abs() < 1e-6, "{}", s.weight[0]);
    let pd = m.diffuse_probability(wo, &h);
    assert!((pd - (1.0 - w)).abs() < 1e-6, "diffuse probability {pd}");
    assert_eq!(m.eval_diffuse(wo, dir_at(Vec3::Z, 10.0, false), &h)[0], {
        (1.0 - w) * albedo()[0] * std::f32::consts::FRAC_1_PI
    });
}

/// White furnace: a blend of white, energy-conserving parts neither gains nor (with a mirror)
/// loses energy.
#[test]
fn blend_white_furnace() {
    let white = Spectrum::splat(1.0, NB);
    let h = hit(Vec3::Z);
    let exact = blend(Material::lambert(white), Material::mirror(white), 0.4);
    let coat = blend(
        Material::lambert(white),
        Material::glossy(white, 1.5, 0.3, NB),
        0.5,
    );
    for theta in [0.0f32, 45.0, 80.0] {
        let wo = dir_at(Vec3::Z, theta, false);
        let mut rng = Pcg64Mcg::seed_from_u64(900 + theta as u64);
        let (mut st, mut sc) = (Stats::default(), Stats::default());
        for _ in 0..100_000 {
            let u = Vec3::new(rng.random(), rng.random(), rng.random());
            match exact.sample(wo, &h, u) {
                Some(s) => st.add(&s.weight),
                None => st.add_zero(),
            }
            match coat.sample(wo, &h, u) {
                Some(s) => sc.add(&s.weight),
                None => sc.add_zero(),
            }
        }
        assert!(
            (st.mean(0) - 1.0).abs() < 1e-5,
            "theta {theta}: {}",
            st.mean(0)
        );
        let (r, se) = (sc.mean(0), sc.se(0));
        assert!(
            r < 1.0 + Z * se && r > 0.7,
            "theta {theta}: R = {r} +- {se}"
        );
    }
}

/// A textured weight is the texture's value at the hit: a uniform texture behaves as the
/// constant; reciprocity holds for blends.
#[test]
fn blend_weight_texture_and_reciprocity() {
    let tex = Texture::from_rgb(1, 1, &[[0.35; 3]], 1, &|c| Spectrum::splat(c[0], 1));
    let parts = || {
        (
            Material::lambert(albedo()),
            Material::glossy(albedo(), 1.5, 0.3, NB),
        )
    };
    let (a, b) = parts();
    let textured = Material::blend(a, b, BlendWeight::Texture(Arc::new(tex)));
    let (a, b) = parts();
    let constant = blend(a, b, 0.35);
    let h = hit(Vec3::new(0.1, 0.3, 1.0));
    let mut rng = Pcg64Mcg::seed_from_u64(950);
    for _ in 0..2000 {
        let wo = dir_at(h.ng, rng.random::<f32>() * 89.0, false);
        let wi = glam::Quat::from_axis_angle(h.ng, rng.random::<f32>() * TAU)
            * dir_at(h.ng, rng.random::<f32>() * 89.0, false);
        let (f1, f2) = (constant.eval(wo, wi, &h), constant.eval(wi, wo, &h));
        let ft = textured.eval(wo, wi, &h);
        for i in 0..NB {
            assert!((f1[i] - f2[i]).abs() <= 1e-4 * f1[i].abs().max(1e-3));
            assert!((f1[i] - ft[i]).abs() <= 1e-5 * f1[i].abs().max(1e-3));
        }
        let (p, pt) = (constant.pdf(wo, wi, &h), textured.pdf(wo, wi, &h));
        assert!((p - pt).abs() <= 1e-5 * p.max(1e-3));
    }
}

/// The non-diffuse part's evaluation and density, which next-event estimation weighs its light
/// samples with (MIS): `eval_nondiffuse` is the non-diffuse f (the full f minus the diffuse
/// part's, at random directions), and `pdf_nondiffuse` is the density of `sample_nondiffuse`:
/// E[h(wi) / pdf(wi)] over its samples equals the quadrature of h over the directions the
/// density covers, for h = cos^2 (|z| < 4). A density of the wrong lobe or a blend that forgot
/// its part probabilities fails.
#[test]
fn nondiffuse_eval_and_pdf_match_the_sampling() {
    let n = Vec3::new(0.1, 0.2, 1.0).normalize();
    let h = hit(n);
    let glossy = || Material::glossy(albedo(), 1.5, 0.3, NB);
    let cases = [
        ("glossy", glossy()),
        (
            "blend glossy/lambert",
            blend(glossy(), Material::lambert(albedo()), 0.4),
        ),
        (
            "blend glossy/glossy",
            blend(glossy(), Material::glossy(albedo(), 1.5, 0.05, NB), 0.7),
        ),
    ];
    let mut rng = Pcg64Mcg::seed_from_u64(91);
    for (label, m) in &cases {
        let wo = dir_at(n, 35.0, false);
        for _ in 0..200 {
            let wi = dir_at(n, rng.random_range(0.0..89.0), false);
            let full = m.eval(wo, wi, &h);
            let want = full - m.eval_diffuse(wo, wi, &h);
            let got = m.eval_nondiffuse(wo, wi, &h);
            for i in 0..NB {
                // The difference of two rounded sums: compare at the full f's scale.
                let tol = 1e-5 * full[i].abs().max(1e-3);
                assert!(
                    (got[i] - want[i]).abs() <= tol,
                    "{label}: {} vs {}",
                    got[i],
                    want[i]
                );
            }
        }
        let h2 = |wi: Vec3| wi.dot(h.ns).powi(2);
        let mut st = Stats::default();
        let count = 400_000;
        for _ in 0..count {
            let u = Vec3::new(rng.random(), rng.random(), rng.random());
            match m.sample_nondiffuse(wo, &h, u) {
                Some(s) => {
                    let p = m.pdf_nondiffuse(wo, s.wi, &h);
                    assert!(p > 0.0, "{label}: a sampled direction of zero density");
                    st.add(&Spectrum::splat(h2(s.wi) / p, NB));
                }
                None => st.add_zero(),
            }
        }
        // Over the hemisphere above the surface, where the coat's density is positive.
        let q = sphere_quadrature(&mut rng, count, |wi| {
            let covered = m.pdf_nondiffuse(wo, wi, &h) > 0.0;
            Spectrum::splat(if covered { h2(wi) } else { 0.0 }, NB)
        });
        assert_z(
            st.mean(0),
            st.se(0),
            q.mean(0),
            q.se(0),
            &format!("{label} pdf"),
        );
    }
}
