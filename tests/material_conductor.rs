//! The rough conductor: exact conductor Fresnel against an independent real-arithmetic form,
//! the alpha -> 0 limit against the mirror, energy (directional albedo never above 1), the
//! visible-normal sampling against the evaluated pdf (chi-square) and against f |cos|
//! (Monte Carlo), pdf normalisation by quadrature, reciprocity; and the scene keys. Monte-Carlo
//! comparisons use fixed seeds and |z| < 4; the chi-square statistic's Wilson-Hilferty z < 4.

use std::f64::consts::PI;
use std::path::Path;

use brume::geometry::Hit;
use brume::material::{
    Conductor, ConductorFresnel, LobeKind, Material, fresnel_conductor, fresnel_dielectric,
};
use brume::scene::load_str;
use brume::spectrum::Spectrum;
use glam::{Vec2, Vec3};
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64Mcg;

const NB: usize = 4;
const Z: f64 = 4.0;

fn hit() -> Hit {
    Hit {
        t: 1.0,
        p: Vec3::ZERO,
        ng: Vec3::Z,
        ns: Vec3::Z,
        uv: Vec2::ZERO,
        shape: 0,
    }
}

/// Direction at polar angle `theta` (degrees) and azimuth `phi` (radians) about +Z.
fn dir(theta_deg: f64, phi: f64) -> Vec3 {
    let t = theta_deg.to_radians();
    Vec3::new(
        (t.sin() * phi.cos()) as f32,
        (t.sin() * phi.sin()) as f32,
        t.cos() as f32,
    )
}

/// Gold-like, silver-like, chromium-like and a weakly absorbing index, one per bin.
fn metal() -> ConductorFresnel {
    ConductorFresnel::Complex {
        eta: Spectrum::from_slice(&[0.42, 0.06, 3.18, 1.5]),
        k: Spectrum::from_slice(&[2.47, 3.6, 3.33, 0.2]),
    }
}

fn white() -> ConductorFresnel {
    ConductorFresnel::Schlick {
        f0: Spectrum::splat(1.0, NB),
    }
}

fn conductor(a: [f32; 2], fresnel: ConductorFresnel) -> Material {
    Material::conductor(a, fresnel, NB)
}

/// Mean and standard error of the sample weights of `m` at `wo` per bin (a lost sample counts 0).
fn albedo(m: &Material, wo: Vec3, n: usize, seed: u64) -> [(f64, f64); NB] {
    let mut rng = Pcg64Mcg::seed_from_u64(seed);
    let (mut s, mut s2) = ([0.0f64; NB], [0.0f64; NB]);
    for _ in 0..n {
        let u = Vec3::new(rng.random(), rng.random(), rng.random());
        if let Some(smp) = m.sample(wo, &hit(), u) {
            for j in 0..NB {
                let w = smp.weight[j] as f64;
                s[j] += w;
                s2[j] += w * w;
            }
        }
    }
    std::array::from_fn(|j| {
        let mean = s[j] / n as f64;
        (
            mean,
            ((s2[j] / n as f64 - mean * mean).max(0.0) / n as f64).sqrt(),
        )
    })
}

/// Born and Wolf's real form of the conductor reflectance (independent of the complex one).
fn fresnel_real(cos: f64, n: f64, k: f64) -> f64 {
    let sin2 = 1.0 - cos * cos;
    let t = n * n - k * k - sin2;
    let a2b2 = (t * t + 4.0 * n * n * k * k).sqrt();
    let a = (0.5 * (a2b2 + t)).sqrt();
    let rs = (a2b2 - 2.0 * a * cos + cos * cos) / (a2b2 + 2.0 * a * cos + cos * cos);
    let st = sin2 / cos; // sin * tan
    let rp = rs * (a2b2 - 2.0 * a * st + st * st) / (a2b2 + 2.0 * a * st + st * st);
    0.5 * (rs + rp)
}

#[test]
fn conductor_fresnel_matches_independent_forms() {
    for &(n, k) in &[
        (0.42, 2.47),
        (0.06, 3.6),
        (3.18, 3.33),
        (1.5, 0.2),
        (1.2, 7.0),
    ] {
        let normal = ((n - 1.0) * (n - 1.0) + k * k) / ((n + 1.0) * (n + 1.0) + k * k);
        let f = fresnel_conductor(1.0, n as f32, k as f32) as f64;
        assert!(
            (f - normal).abs() < 1e-6,
            "normal incidence {n}+{k}i: {f} vs {normal}"
        );
        for deg in [10.0, 45.0, 70.0, 85.0, 89.5] {
            let c: f64 = f64::to_radians(deg).cos();
            let f = fresnel_conductor(c as f32, n as f32, k as f32) as f64;
            let r = fresnel_real(c, n, k);
            assert!((f - r).abs() < 1e-5, "{n}+{k}i at {deg} deg: {f} vs {r}");
        }
        assert_eq!(fresnel_conductor(0.0, n as f32, k as f32), 1.0, "grazing");
    }
    // No absorption: the dielectric's reflectance.
    for c in [0.1f32, 0.5, 0.9] {
        let d = fresnel_dielectric(c, 1.5);
        assert!((fresnel_conductor(c, 1.5, 0.0) - d).abs() < 1e-6);
    }
}

/// Roughness below the smooth threshold is the mirror's delta reflection with the Fresnel
/// factor; as alpha -> 0 the rough lobe's albedo converges to the same value.
#[test]
fn alpha_to_zero_matches_the_mirror_with_fresnel() {
    let mirror = Material::mirror(Spectrum::splat(1.0, NB));
    let smooth = conductor([0.0, 0.0], metal());
    assert!(smooth.is_specular() && !smooth.has_glossy());
    for theta in [0.0, 30.0, 60.0, 85.0] {
        let wo = dir(theta, 0.4);
        let u = Vec3::new(0.3, 0.6, 0.9);
        let m = mirror.sample_nondiffuse(wo, &hit(), u).expect("mirror");
        for s in [
            smooth.sample(wo, &hit(), u).expect("forward"),
            smooth.sample_nondiffuse(wo, &hit(), u).expect("camera"),
        ] {
            assert_eq!(s.kind, LobeKind::Specular);
            assert!((s.wi - m.wi).length() < 1e-6);
            for j in 0..NB {
                let f = metal_fresnel(wo.z, j);
                assert!(
                    (s.weight[j] - m.weight[j] * f).abs() < 1e-6,
                    "{theta} bin {j}"
                );
            }
        }
    }
    // The rough lobe's directional albedo tends to F(cos theta_o): within 4 standard errors
    // plus 0.01 * alpha / 0.002 (the lobe's own spread of F and masking at this alpha).
    for alpha in [0.02f32, 0.002] {
        let m = conductor([alpha, alpha], metal());
        assert!(!m.is_specular() && m.has_glossy());
        for theta in [0.0, 45.0, 75.0] {
            let wo = dir(theta, 1.0);
            let a = albedo(&m, wo, 20_000, 7);
            for (j, (mean, se)) in a.iter().enumerate() {
                let f = metal_fresnel(wo.z, j) as f64;
                let tol = Z * se + 0.01 * alpha as f64 / 0.002;
                assert!(
                    (mean - f).abs() < tol,
                    "alpha {alpha} {theta} bin {j}: {mean} vs {f}"
                );
            }
        }
    }
}

fn metal_fresnel(cos: f32, j: usize) -> f32 {
    let ConductorFresnel::Complex { eta, k } = metal() else {
        unreachable!()
    };
    fresnel_conductor(cos, eta[j], k[j])
}

/// With F = 1 the directional albedo is E[G2 / G1] <= 1 whatever alpha and angle: single
/// scattering only loses energy. Every weight is at most 1 (exactly), and the mean is checked
/// against an independent quadrature of f |cos| over the sphere.
#[test]
fn energy_never_exceeds_one_over_alpha_and_angle() {
    let alphas: [[f32; 2]; 7] = [
        [0.01, 0.01],
        [0.1, 0.1],
        [0.3, 0.3],
        [0.6, 0.6],
        [1.0, 1.0],
        [0.05, 0.5],
        [0.8, 0.2],
    ];
    let mut rng = Pcg64Mcg::seed_from_u64(11);
    for (i, a) in alphas.iter().enumerate() {
        let m = conductor(*a, white());
        for theta in [0.0, 30.0, 60.0, 80.0, 89.0] {
            let wo = dir(theta, 0.7);
            let mut sum = 0.0;
            let mut sum2 = 0.0;
            let n = 20_000;
            for _ in 0..n {
                let u = Vec3::new(rng.random(), rng.random(), rng.random());
                let w = m.sample(wo, &hit(), u).map_or(0.0, |s| s.weight[0] as f64);
                assert!(w <= 1.0 + 1e-6, "{a:?} {theta}: weight {w}");
                sum += w;
                sum2 += w * w;
            }
            let mean = sum / n as f64;
            let se = ((sum2 / n as f64 - mean * mean).max(0.0) / n as f64).sqrt();
            assert!(mean - Z * se <= 1.0, "{a:?} {theta}: albedo {mean} +- {se}");
            // Independent: f |cos| integrated over directions (rougher lobes only, where
            // uniform quadrature resolves the lobe).
            if a[0].min(a[1]) >= 0.1 && theta < 89.0 {
                let (q, qse) = quadrature(&m, wo, 200_000, 100 + i as u64);
                let z = (mean - q) / (se * se + qse * qse).sqrt();
                assert!(
                    z.abs() < Z,
                    "{a:?} {theta}: sampled {mean} vs quadrature {q}, z {z}"
                );
            }
        }
    }
}

/// Monte-Carlo integral of f(wo, wi) cos over the hemisphere, cosine-distributed directions.
fn quadrature(m: &Material, wo: Vec3, n: usize, seed: u64) -> (f64, f64) {
    let mut rng = Pcg64Mcg::seed_from_u64(seed);
    let (mut s, mut s2) = (0.0, 0.0);
    for _ in 0..n {
        let (u1, u2): (f64, f64) = (rng.random(), rng.random());
        let r = u1.sqrt();
        let wi = Vec3::new(
            (r * (2.0 * PI * u2).cos()) as f32,
            (r * (2.0 * PI * u2).sin()) as f32,
            (1.0 - u1).sqrt() as f32,
        );
        // f cos / (cos / pi)
        let v = m.eval(wo, wi, &hit())[0] as f64 * PI;
        s += v;
        s2 += v * v;
    }
    let mean = s / n as f64;
    (
        mean,
        ((s2 / n as f64 - mean * mean).max(0.0) / n as f64).sqrt(),
    )
}

/// Midpoint quadrature over the hemisphere of g, in s = sqrt(1 - cos theta) (cells crowd
/// towards the pole, where the narrow lobes of the normals are) and phi, with `n` x 4n cells.
fn hemisphere(n: usize, g: impl Fn(Vec3) -> f64) -> f64 {
    let m = 4 * n;
    let mut total = 0.0;
    for i in 0..n {
        let s = (i as f64 + 0.5) / n as f64;
        let z = 1.0 - s * s;
        let r = (1.0 - z * z).max(0.0).sqrt();
        for k in 0..m {
            let phi = 2.0 * PI * (k as f64 + 0.5) / m as f64;
            let w = Vec3::new((r * phi.cos()) as f32, (r * phi.sin()) as f32, z as f32);
            // d(cos theta) = 2 s ds
            total += g(w) * 2.0 * s;
        }
    }
    total * 2.0 * PI / (n * m) as f64
}

/// The visible-normal density integrates to 1 over the hemisphere of normals, and the density
/// of sampled directions to 1 minus the visible normals that reflect below the surface.
#[test]
fn pdf_integrates_to_one_by_quadrature() {
    for a in [[0.1f32, 0.1], [0.4, 0.4], [1.0, 1.0], [0.15, 0.6]] {
        let c = Conductor::new(a[0], a[1], white(), NB);
        let m = conductor(a, white());
        for theta in [0.0, 40.0, 80.0] {
            let wo = dir(theta, 0.3);
            let n = 1200;
            let vn = hemisphere(n, |h| c.visible_normal_pdf(wo, h) as f64);
            assert!(
                (vn - 1.0).abs() < 2e-3,
                "{a:?} {theta}: visible normals {vn}"
            );
            let lost = hemisphere(n, |h| {
                let wi = 2.0 * wo.dot(h) * h - wo;
                if wi.z <= 0.0 {
                    c.visible_normal_pdf(wo, h) as f64
                } else {
                    0.0
                }
            });
            let dirs = hemisphere(n, |wi| m.pdf(wo, wi, &hit()) as f64);
            assert!(
                (dirs + lost - 1.0).abs() < 3e-3,
                "{a:?} {theta}: directions {dirs} + lost {lost}"
            );
        }
    }
}

/// Chi-square of sampled directions binned in (cos theta, phi) against the pdf integrated over
/// each bin (midpoint rule, 8 x 8 points per bin), with the lost samples as one more bin.
#[test]
fn vndf_sampling_matches_pdf_chi_square() {
    let (nt, np, sub) = (10usize, 20usize, 8usize);
    let n = 200_000usize;
    for (case, (a, theta)) in [
        ([0.3f32, 0.3], 40.0),
        ([0.15, 0.5], 65.0),
        ([0.8, 0.8], 80.0),
    ]
    .into_iter()
    .enumerate()
    {
        let m = conductor(a, metal());
        let wo = dir(theta, 0.5);
        let mut observed = vec![0.0f64; nt * np + 1];
        let mut rng = Pcg64Mcg::seed_from_u64(1000 + case as u64);
        for _ in 0..n {
            let u = Vec3::new(rng.random(), rng.random(), rng.random());
            let cell = match m.sample(wo, &hit(), u) {
                Some(s) => {
                    let it = ((s.wi.z as f64 * nt as f64) as usize).min(nt - 1);
                    let phi = (s.wi.y as f64).atan2(s.wi.x as f64).rem_euclid(2.0 * PI);
                    let ip = ((phi / (2.0 * PI) * np as f64) as usize).min(np - 1);
                    it * np + ip
                }
                None => nt * np,
            };
            observed[cell] += 1.0;
        }
        let mut expected = vec![0.0f64; nt * np + 1];
        for it in 0..nt {
            for ip in 0..np {
                let mut s = 0.0;
                for a_ in 0..sub {
                    let z = (it as f64 + (a_ as f64 + 0.5) / sub as f64) / nt as f64;
                    let r = (1.0 - z * z).sqrt();
                    for b in 0..sub {
                        let phi =
                            2.0 * PI * (ip as f64 + (b as f64 + 0.5) / sub as f64) / np as f64;
                        let wi =
                            Vec3::new((r * phi.cos()) as f32, (r * phi.sin()) as f32, z as f32);
                        s += m.pdf(wo, wi, &hit()) as f64;
                    }
                }
                let cell_area = 2.0 * PI / (nt * np) as f64;
                expected[it * np + ip] = s / (sub * sub) as f64 * cell_area * n as f64;
            }
        }
        let inside: f64 = expected[..nt * np].iter().sum();
        expected[nt * np] = (n as f64 - inside).max(0.0);
        // Bins expecting fewer than 5 samples are pooled into one.
        let (mut chi2, mut dof, mut pool_o, mut pool_e) = (0.0, 0usize, 0.0, 0.0);
        for (o, e) in observed.iter().zip(&expected) {
            if *e < 5.0 {
                pool_o += o;
                pool_e += e;
            } else {
                chi2 += (o - e) * (o - e) / e;
                dof += 1;
            }
        }
        if pool_e >= 5.0 {
            chi2 += (pool_o - pool_e) * (pool_o - pool_e) / pool_e;
            dof += 1;
        } else {
            assert!(
                pool_o < 20.0,
                "case {case}: {pool_o} samples where {pool_e} expected"
            );
        }
        let k = (dof - 1) as f64;
        let wh = ((chi2 / k).cbrt() - (1.0 - 2.0 / (9.0 * k))) / (2.0 / (9.0 * k)).sqrt();
        assert!(wh < Z, "case {case}: chi2 {chi2} with {k} dof, z {wh}");
        assert!(dof > 50, "case {case}: only {dof} bins");
    }
}

/// f(wo, wi) = f(wi, wo), isotropic and anisotropic, both Fresnel forms.
#[test]
fn eval_is_reciprocal() {
    let mut rng = Pcg64Mcg::seed_from_u64(5);
    for a in [[0.05f32, 0.05], [0.3, 0.3], [0.1, 0.7]] {
        for fresnel in [metal(), white()] {
            let m = conductor(a, fresnel);
            for _ in 0..2000 {
                let wo = dir(rng.random::<f64>() * 89.0, rng.random::<f64>() * 2.0 * PI);
                let wi = dir(rng.random::<f64>() * 89.0, rng.random::<f64>() * 2.0 * PI);
                let (f1, f2) = (m.eval(wo, wi, &hit()), m.eval(wi, wo, &hit()));
                for j in 0..NB {
                    let tol = 1e-4 * f1[j].abs().max(f2[j].abs()) + 1e-6;
                    assert!(
                        (f1[j] - f2[j]).abs() <= tol,
                        "{a:?} bin {j}: {} vs {}",
                        f1[j],
                        f2[j]
                    );
                }
            }
        }
    }
}

/// Camera paths (non-diffuse part) and forward rays see the same lobe: the same sample from
/// the same numbers, the non-diffuse eval and pdf equal to the whole's, no diffuse part.
#[test]
fn camera_and_forward_sampling_agree() {
    let m = conductor([0.2, 0.4], metal());
    let wo = dir(50.0, 1.0);
    let mut rng = Pcg64Mcg::seed_from_u64(3);
    for _ in 0..1000 {
        let u = Vec3::new(rng.random(), rng.random(), rng.random());
        let (a, b) = (m.sample(wo, &hit(), u), m.sample_nondiffuse(wo, &hit(), u));
        match (a, b) {
            (Some(a), Some(b)) => {
                assert_eq!(a.wi, b.wi);
                assert_eq!(a.weight, b.weight);
                assert_eq!(a.kind, LobeKind::Glossy);
                assert_eq!(m.pdf(wo, a.wi, &hit()), m.pdf_nondiffuse(wo, a.wi, &hit()));
                assert_eq!(
                    m.eval(wo, a.wi, &hit()),
                    m.eval_nondiffuse(wo, a.wi, &hit())
                );
                assert!(m.eval_diffuse(wo, a.wi, &hit()).is_zero());
            }
            (None, None) => {}
            _ => panic!("one sampler lost a sample the other kept"),
        }
    }
    assert_eq!(m.diffuse_probability(wo, &hit()), 0.0);
}

const SCENE: &str = r#"
[camera]
width = 16
height = 12

[materials.metal]
type = "conductor"
roughness = 0.2
eta = "gold"

[[shapes]]
type = "quad"
size = [1, 1]
material = "metal"
"#;

fn build(text: &str) -> Result<brume::world::Scene, String> {
    let s = load_str(text, Path::new("scenes/test.toml"), &[]).map_err(|e| e.to_string())?;
    brume::scene::build(&s).map_err(|e| e.to_string())
}

#[test]
fn scene_keys_load_and_build() {
    let s = build(SCENE).expect("gold");
    let Material::Conductor(c) = &s.materials[0] else {
        panic!("a conductor")
    };
    let ConductorFresnel::Complex { eta, k } = &c.fresnel else {
        panic!("complex index")
    };
    // Gold in the first of 32 bins of 380-780 nm (380-392.5 nm): Johnson and Christy's n = 1.46,
    // k = 1.93 at 381.5 nm and 1.47, 1.95 at 397.4 nm; in the last (767.5-780 nm), between
    // 0.14, 4.54 at 756 nm and 0.16, 5.08 at 821.1 nm.
    assert!(
        (eta[0] - 1.465).abs() < 0.01 && (k[0] - 1.94).abs() < 0.01,
        "{} {}",
        eta[0],
        k[0]
    );
    assert!(
        (eta[31] - 0.145).abs() < 0.01 && (k[31] - 4.7).abs() < 0.1,
        "{} {}",
        eta[31],
        k[31]
    );
    assert_eq!(c.alpha, Vec2::splat(0.2));
    for metal in ["aluminium", "silver", "copper", "chromium", "iron", "Gold"] {
        build(&SCENE.replace("\"gold\"", &format!("\"{metal}\""))).expect(metal);
    }
    let aniso = SCENE.replace("roughness = 0.2", "roughness = [0.1, 0.4]");
    let s = build(&aniso).expect("anisotropic");
    let Material::Conductor(c) = &s.materials[0] else {
        panic!()
    };
    assert_eq!(c.alpha, Vec2::new(0.1, 0.4));
    let own = SCENE.replace("eta = \"gold\"", "eta = 1.5\nk = \"silver\"");
    build(&own).expect("a constant eta with a metal's k");
    let f0 = SCENE.replace("eta = \"gold\"", "f0 = [1.0, 0.78, 0.34]");
    let s = build(&f0).expect("f0");
    let Material::Conductor(c) = &s.materials[0] else {
        panic!()
    };
    assert!(matches!(c.fresnel, ConductorFresnel::Schlick { .. }));
    let smooth = build(&SCENE.replace("roughness = 0.2", "roughness = 0")).expect("smooth");
    assert!(smooth.materials[0].is_specular());
}

/// Each refusal names the file, the line and the key.
#[test]
fn bad_conductor_values_are_refused_at_their_key() {
    let cases: &[(&str, &str, &str, &str)] = &[
        (
            "roughness = 0.2",
            "roughness = -0.1",
            "8:",
            "materials.metal.roughness`",
        ),
        (
            "roughness = 0.2",
            "roughness = [0.1, -1]",
            "8:",
            "materials.metal.roughness.1`",
        ),
        (
            "roughness = 0.2",
            "roughness = 1.5",
            "8:",
            "materials.metal.roughness`",
        ),
        (
            "eta = \"gold\"",
            "eta = \"unobtainium\"",
            "9:",
            "materials.metal.eta`",
        ),
        (
            "eta = \"gold\"",
            "eta = \"gold\"\nk = \"mithril\"",
            "10:",
            "materials.metal.k`",
        ),
        (
            "eta = \"gold\"",
            "eta = -1.0\nk = 2.0",
            "9:",
            "materials.metal.eta`",
        ),
        (
            "eta = \"gold\"",
            "eta = 1.0\nk = -2.0",
            "10:",
            "materials.metal.k`",
        ),
        ("eta = \"gold\"", "eta = 1.2", "6:", "materials.metal`"),
        ("eta = \"gold\"", "f0 = 1.5", "9:", "materials.metal.f0`"),
        (
            "eta = \"gold\"",
            "f0 = 0.9\neta = \"gold\"",
            "9:",
            "materials.metal.f0`",
        ),
        ("eta = \"gold\"\n", "", "6:", "materials.metal`"),
        (
            "roughness = 0.2",
            "roughness = [0.1, 0.2, 0.3]",
            "8:",
            "materials.metal.roughness`",
        ),
    ];
    for (from, to, line, key) in cases {
        assert!(SCENE.contains(from), "{from}");
        let Err(e) = build(&SCENE.replacen(from, to, 1)) else {
            panic!("{to}: accepted")
        };
        assert!(
            e.starts_with(&format!("scenes/test.toml:{line}")) && e.contains(key),
            "{to}: {e}"
        );
    }
    let Err(e) = build(&SCENE.replace("\"gold\"", "\"unobtainium\"")) else {
        panic!("unknown metal accepted")
    };
    assert!(e.contains("is not a metal (aluminium, silver, gold"), "{e}");
}
