//! Smooth dielectric: Fresnel split against an independent formula, R + T = 1, Snell's law,
//! the radiance (n_i/n_t)^2 factor, and per-bin unbiasedness with dispersion. |z| < 4, fixed seeds.

use brume::geometry::Hit;
use brume::material::{LobeKind, Material};
use brume::spectrum::Spectrum;
use glam::{Vec2, Vec3};
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64Mcg;

const NB: usize = 8;

fn hit() -> Hit {
    let n = Vec3::new(0.2, -0.1, 1.0).normalize();
    Hit {
        t: 1.0,
        p: Vec3::ZERO,
        ng: n,
        ns: n,
        uv: Vec2::ZERO,
        shape: 0,
    }
}

fn dir_at(n: Vec3, theta_deg: f32, inside: bool) -> Vec3 {
    let t = n.cross(Vec3::X).normalize();
    let th = theta_deg.to_radians();
    let d = n * th.cos() + t * th.sin();
    if inside { -d } else { d }
}

/// Textbook unpolarised Fresnel reflectance from n1 into n2 at incidence angle theta.
fn fresnel_reference(theta: f64, n1: f64, n2: f64) -> f64 {
    let s = n1 / n2 * theta.sin();
    if s >= 1.0 {
        return 1.0;
    }
    let (ci, ct) = (theta.cos(), (1.0 - s * s).sqrt());
    let rs = (n1 * ci - n2 * ct) / (n1 * ci + n2 * ct);
    let rp = (n2 * ci - n1 * ct) / (n2 * ci + n1 * ct);
    0.5 * (rs * rs + rp * rp)
}

#[test]
fn fresnel_split_energy_and_snell() {
    let ior = 1.5f32;
    let m = Material::dielectric(Spectrum::splat(ior, NB), NB);
    assert!(!m.is_dispersive());
    let h = hit();
    let mut rng = Pcg64Mcg::seed_from_u64(700);
    for (theta, inside) in [
        (0.0f32, false),
        (30.0, false),
        (56.3, false),
        (75.0, false),
        (20.0, true),
        (40.0, true),
        (60.0, true),
    ] {
        let wo = dir_at(h.ng, theta, inside);
        let (n1, n2) = if inside { (ior, 1.0) } else { (1.0, ior) };
        let r_ref = fresnel_reference((theta as f64).to_radians(), n1 as f64, n2 as f64);
        let n = 200_000;
        let (mut refl, mut sum_w, mut sum_w_rad) = (0usize, 0.0f64, 0.0f64);
        for _ in 0..n {
            let u = Vec3::new(rng.random(), rng.random(), rng.random());
            let s = m
                .sample(wo, &h, u)
                .expect("a smooth dielectric always scatters");
            let r = m.sample_nondiffuse(wo, &h, u).unwrap();
            assert_eq!(s.kind, LobeKind::Specular);
            let cos_o = wo.dot(h.ng);
            let cos_i = s.wi.dot(h.ng);
            if cos_i * cos_o > 0.0 {
                refl += 1;
                assert!((cos_i - cos_o).abs() < 1e-5, "mirror angle");
            } else {
                // Snell: n1 sin(theta_i) = n2 sin(theta_t), in the plane of incidence.
                let (si, st) = (wo.cross(h.ng).length(), s.wi.cross(h.ng).length());
                assert!((n1 * si - n2 * st).abs() < 1e-4, "Snell at {theta}");
                assert!(s.wi.dot(wo.cross(h.ng)).abs() < 1e-5);
            }
            sum_w += s.weight[0] as f64;
            sum_w_rad += r.weight[0] as f64;
            for i in 1..NB {
                assert_eq!(s.weight[i], s.weight[0]);
            }
            assert_eq!(s.weight[NB], 0.0, "lanes past the bin count stay zero");
        }
        let frac = refl as f64 / n as f64;
        let se = (r_ref * (1.0 - r_ref) / n as f64).sqrt().max(1e-6);
        assert!(
            ((frac - r_ref) / se).abs() < 4.0,
            "theta {theta} inside {inside}: R {frac} vs {r_ref}"
        );
        // R + T = 1: flux weights average to one (each sample carries exactly 1 here).
        assert!(
            (sum_w / n as f64 - 1.0).abs() < 1e-6,
            "R + T = {}",
            sum_w / n as f64
        );
        // Radiance mode: R + T (n1/n2)^2.
        let expect = r_ref + (1.0 - r_ref) * (n1 as f64 / n2 as f64).powi(2);
        let got = sum_w_rad / n as f64;
        let sd = ((1.0 - (n1 as f64 / n2 as f64).powi(2)).abs()
            * (r_ref * (1.0 - r_ref) / n as f64).sqrt())
        .max(1e-6);
        assert!(
            ((got - expect) / sd).abs() < 4.0,
            "radiance weight {got} vs {expect}"
        );
    }
    // Normal incidence closed form and total internal reflection beyond the critical angle.
    assert!((fresnel_reference(0.0, 1.0, 1.5) - 0.04).abs() < 1e-9);
    let wo = dir_at(h.ng, 45.0, true); // critical angle 41.8 deg
    for k in 0..100 {
        let s = m
            .sample(wo, &h, Vec3::new(0.5, 0.5, k as f32 / 100.0))
            .unwrap();
        assert!(s.wi.dot(h.ng) < 0.0, "TIR keeps the ray inside");
    }
}

#[test]
fn dispersion_is_unbiased_per_bin() {
    let ior: Vec<f32> = (0..NB).map(|i| 1.45 + 0.02 * i as f32).collect();
    let m = Material::dielectric(Spectrum::from_slice(&ior), NB);
    assert!(m.is_dispersive());
    let h = hit();
    let mut rng = Pcg64Mcg::seed_from_u64(800);
    for (theta, inside) in [(10.0f32, false), (50.0, false), (35.0, true)] {
        let wo = dir_at(h.ng, theta, inside);
        let n = 400_000;
        let mut s1 = [0.0f64; NB];
        let mut s2 = [0.0f64; NB];
        let mut t_per_bin = [0.0f64; NB];
        for _ in 0..n {
            let u = Vec3::new(rng.random(), rng.random(), rng.random());
            let s = m.sample(wo, &h, u).unwrap();
            let transmitted = s.wi.dot(h.ng) * wo.dot(h.ng) < 0.0;
            if transmitted {
                let bins: Vec<usize> = (0..NB).filter(|&i| s.weight[i] != 0.0).collect();
                assert_eq!(bins.len(), 1, "dispersive transmission carries one bin");
                let k = bins[0];
                let (n1, n2) = if inside { (ior[k], 1.0) } else { (1.0, ior[k]) };
                let (si, st) = (wo.cross(h.ng).length(), s.wi.cross(h.ng).length());
                assert!((n1 * si - n2 * st).abs() < 1e-4, "Snell for bin {k}");
                t_per_bin[k] += s.weight[k] as f64;
            }
            for i in 0..NB {
                let w = s.weight[i] as f64;
                s1[i] += w;
                s2[i] += w * w;
            }
        }
        for i in 0..NB {
            let mean = s1[i] / n as f64;
            let se = ((s2[i] / n as f64 - mean * mean) / n as f64).sqrt();
            assert!(
                ((mean - 1.0) / se).abs() < 4.0,
                "bin {i}: R+T = {mean} +- {se}"
            );
            // The transmitted part alone matches 1 - R of that bin's index.
            let (n1, n2) = if inside {
                (ior[i] as f64, 1.0)
            } else {
                (1.0, ior[i] as f64)
            };
            let t_ref = 1.0 - fresnel_reference((theta as f64).to_radians(), n1, n2);
            let t = t_per_bin[i] / n as f64;
            assert!(
                (t - t_ref).abs() < 4.0 * se + 1e-9,
                "bin {i}: T = {t} vs {t_ref}"
            );
        }
    }
}
