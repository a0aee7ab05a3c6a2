//! Phase functions. Henyey–Greenstein: normalisation, exact sampling (mean cosine and binned
//! CDF), robustness for g -> 0 and |g| -> 1, parameter validation. Every variant of `Phase`:
//! normalisation by quadrature, chi-square of its sampler against its own evaluation, mean
//! cosine; tabulated tables against analytic HG, per-bin lanes and the mixture sampler.

#[path = "estimator_stats.rs"]
mod stats;

use std::path::Path;

use brume::medium::{
    ChannelPick, Draine, HenyeyGreenstein, HgDraine, Phase, PhaseCsv, Rayleigh, TwoTermHg,
    channel_probabilities,
};
use brume::spectrum::{SpectralGrid, Spectrum};
use glam::Vec3;
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64Mcg;
use stats::simpson;

const GS: [f32; 9] = [-0.99, -0.9, -0.5, -1e-3, 0.0, 1e-3, 0.5, 0.9, 0.99];

/// Exact HG CDF in cos, in f64.
fn cdf(g: f64, mu: f64) -> f64 {
    if g.abs() < 1e-9 {
        return 0.5 * (mu + 1.0);
    }
    (1.0 - g * g) / (2.0 * g) * ((1.0 + g * g - 2.0 * g * mu).powf(-0.5) - 1.0 / (1.0 + g))
}

#[test]
fn normalised_over_the_sphere() {
    for g in GS {
        let hg = HenyeyGreenstein::new(g).unwrap();
        // ∫ f dω = 2π ∫ f(μ) dμ; the peak at |g| = 0.99 needs a fine grid.
        let i = 2.0
            * std::f64::consts::PI
            * simpson(-1.0, 1.0, 400_000, |mu| hg.eval(mu as f32) as f64);
        assert!((i - 1.0).abs() < 2e-4, "g={g}: ∫f dω = {i}");
    }
}

#[test]
fn sampled_mean_cosine_is_g() {
    let mut rng = Pcg64Mcg::seed_from_u64(11);
    let n = 400_000;
    for g in GS {
        let hg = HenyeyGreenstein::new(g).unwrap();
        let (mut s, mut s2) = (0.0f64, 0.0f64);
        for _ in 0..n {
            let c = hg.sample_cos(rng.random()) as f64;
            assert!((-1.0..=1.0).contains(&c));
            s += c;
            s2 += c * c;
        }
        let m = s / n as f64;
        let se = ((s2 / n as f64 - m * m) / n as f64).sqrt();
        let z = (m - g as f64) / se;
        assert!(z.abs() < 4.0, "g={g}: E[cos]={m} z={z}");
    }
}

/// Binned chi-square of sampled cosines against the exact CDF (bins of equal probability).
#[test]
fn sampled_cosines_follow_the_cdf() {
    let mut rng = Pcg64Mcg::seed_from_u64(12);
    let n = 200_000usize;
    let bins = 50usize;
    for g in GS {
        let hg = HenyeyGreenstein::new(g).unwrap();
        let mut counts = vec![0usize; bins];
        for _ in 0..n {
            let c = hg.sample_cos(rng.random()) as f64;
            let f = cdf(g as f64, c).clamp(0.0, 1.0 - 1e-12);
            counts[(f * bins as f64) as usize] += 1;
        }
        let e = n as f64 / bins as f64;
        let chi2: f64 = counts.iter().map(|&k| (k as f64 - e).powi(2) / e).sum();
        // 49 dof: mean 49, sd ~9.9; 100 is > 5 sd.
        assert!(chi2 < 100.0, "g={g}: chi2={chi2}");
    }
}

/// The sampled cosine must equal the exact inverse CDF (computed in f64) for every g, in
/// particular where the textbook formula cancels (tiny g) or divides by ~0 (|g| -> 1).
#[test]
fn inverse_cdf_is_accurate_for_extreme_g() {
    for g in [1e-7f32, -1e-5, 1e-3, 0.3, -0.7, 0.999, -0.999, 0.99999] {
        let hg = HenyeyGreenstein::new(g).unwrap();
        for k in 0..=100 {
            let xi = (k as f32 / 100.0).min(0.999_999);
            let c = hg.sample_cos(xi);
            assert!(c.is_finite());
            let back = cdf(g as f64, c as f64);
            // cos is f32, and dF/dcos can be huge for |g| -> 1: compare in cos via the cdf slope.
            let slope = hg.eval(c) as f64 * 2.0 * std::f64::consts::PI;
            let err = (back - xi as f64).abs() / slope.max(1.0);
            assert!(err < 2e-6, "g={g} xi={xi}: cos={c} F(cos)={back}");
        }
    }
}

#[test]
fn sampled_direction_has_the_right_cosine_and_is_unit() {
    let mut rng = Pcg64Mcg::seed_from_u64(13);
    let hg = HenyeyGreenstein::new(0.7).unwrap();
    let w = Vec3::new(0.3, -0.5, 0.8).normalize();
    let n = 200_000;
    let (mut s, mut s2) = (0.0f64, 0.0f64);
    let mut perp = Vec3::ZERO;
    for _ in 0..n {
        let d = hg.sample_dir(w, rng.random(), rng.random());
        assert!((d.length() - 1.0).abs() < 1e-5);
        let c = d.dot(w) as f64;
        s += c;
        s2 += c * c;
        perp += d - w * d.dot(w);
    }
    let m = s / n as f64;
    let se = ((s2 / n as f64 - m * m) / n as f64).sqrt();
    assert!(((m - 0.7) / se).abs() < 4.0, "E[cos]={m}");
    // Azimuth uniform: the perpendicular parts average out (each component sd <= ~0.7/sqrt(n)).
    assert!((perp / n as f32).length() < 4.0 * 0.72 / (n as f32).sqrt());
}

#[test]
fn camera_convention_uses_minus_u_dot_v() {
    let hg = HenyeyGreenstein::new(0.8).unwrap();
    let u = Vec3::Z;
    // Light travelling straight at the camera (v = -u) is forward scattering into -u: the peak.
    assert_eq!(hg.eval_uv(u, -u), hg.eval(1.0));
    assert_eq!(hg.eval_uv(u, u), hg.eval(-1.0));
    assert!(hg.eval(1.0) > hg.eval(-1.0));
}

#[test]
fn rejects_invalid_g() {
    for g in [1.0f32, -1.0, 1.5, f32::NAN, f32::INFINITY] {
        assert!(HenyeyGreenstein::new(g).is_err(), "g={g}");
    }
}

/// One of each variant, with peaked and flat parameters.
fn every_phase() -> Vec<(String, Phase)> {
    let mut v = vec![
        ("hg 0.9".into(), Phase::hg(0.9).unwrap()),
        ("hg -0.3".into(), Phase::hg(-0.3).unwrap()),
        (
            "two-term-hg".into(),
            Phase::TwoTermHg(TwoTermHg::new(0.85, -0.4, 0.8).unwrap()),
        ),
        ("rayleigh".into(), Phase::Rayleigh(Rayleigh)),
        (
            "draine g=0.6 a=1".into(),
            Phase::Draine(Draine::new(0.6, 1.0).unwrap()),
        ),
        (
            "draine g=0.01 a=250".into(),
            Phase::Draine(Draine::new(0.01, 250.0).unwrap()),
        ),
        (
            "draine g=-0.7 a=5".into(),
            Phase::Draine(Draine::new(-0.7, 5.0).unwrap()),
        ),
    ];
    for d in [0.05f32, 0.8, 3.0, 10.0, 50.0] {
        v.push((
            format!("hg-draine d={d}"),
            Phase::HgDraine(HgDraine::new(d).unwrap()),
        ));
    }
    v.push(("tabulated hg 0.7".into(), hg_table(0.7, 0.5)));
    // A coarse table with steep segments, where sampling inside a segment is what is tested.
    let csv = "angle_deg,value\n0,10\n45,4\n90,0\n135,0.5\n180,2\n";
    let grid = SpectralGrid::new(4, 400.0, 700.0);
    let t = PhaseCsv::parse(csv, Path::new("coarse.csv"))
        .and_then(|c| c.table(&grid, Path::new("coarse.csv")))
        .unwrap();
    v.push((
        "tabulated coarse".into(),
        Phase::Tabulated(brume::medium::phase_intern(t)),
    ));
    v
}

/// `∫ f dω` in θ (Simpson), where the forward peaks are well resolved.
fn integral(f: impl Fn(f64) -> f64) -> f64 {
    2.0 * std::f64::consts::PI
        * simpson(0.0, std::f64::consts::PI, 400_000, |t| f(t.cos()) * t.sin())
}

/// A CSV of HG(g) at every `step` degrees, read as a one-lane table.
fn hg_csv(g: f64, step: f64) -> String {
    let hg = |mu: f64| {
        (1.0 - g * g) / (4.0 * std::f64::consts::PI * (1.0 + g * g - 2.0 * g * mu).powf(1.5))
    };
    let rows = (180.0 / step).round() as usize;
    let mut text = String::from("# HG table\nangle_deg,value\n");
    for i in 0..=rows {
        let a = i as f64 * 180.0 / rows as f64;
        text += &format!("{a},{}\n", hg(a.to_radians().cos()) * 3.0); // unnormalised on purpose
    }
    text
}

fn hg_table(g: f64, step: f64) -> Phase {
    let grid = SpectralGrid::new(4, 400.0, 700.0);
    let csv = PhaseCsv::parse(&hg_csv(g, step), Path::new("hg.csv")).unwrap();
    let t = csv.table(&grid, Path::new("hg.csv")).unwrap();
    Phase::Tabulated(brume::medium::phase_intern(t))
}

#[test]
fn every_phase_is_normalised() {
    for (name, p) in every_phase() {
        let i = integral(|mu| p.eval(mu as f32) as f64);
        assert!((i - 1.0).abs() < 1e-4, "{name}: ∫p dω = {i}");
        // Its mean cosine is the one it reports.
        let g = integral(|mu| mu * p.eval(mu as f32) as f64);
        assert!(
            (g - p.g() as f64).abs() < 1e-4,
            "{name}: ∫mu p dω = {g}, g() = {}",
            p.g()
        );
    }
}

/// Chi-square of `n` sampled cosines against the density (its cumulative trapezoid on a fine
/// θ-spaced grid, not the sampler's own CDF), over `bins` bins of about equal probability.
/// Sampled cosines are f32, which near a sharp forward peak (g = 0.998) have only tens of
/// values across the peak; so each bin edge is moved to the midpoint between two adjacent f32
/// values, where it separates rounded samples exactly, and the expected count of each bin is
/// the density's probability between its snapped edges.
fn chi_square(p: &Phase, n: usize, bins: usize, seed: u64) -> f64 {
    let m = 400_000;
    let nodes: Vec<f64> = (0..=m)
        .map(|k| (std::f64::consts::PI * (m - k) as f64 / m as f64).cos())
        .collect();
    let mut cdf = vec![0.0; m + 1];
    for k in 1..=m {
        let (a, b) = (nodes[k - 1], nodes[k]);
        let fa = p.eval(a as f32) as f64;
        let fb = p.eval(b as f32) as f64;
        cdf[k] = cdf[k - 1] + std::f64::consts::PI * (b - a) * (fa + fb);
    }
    let total = cdf[m];
    let at = |mu: f64| {
        let k = nodes.partition_point(|&x| x <= mu).clamp(1, m);
        let t = ((mu - nodes[k - 1]) / (nodes[k] - nodes[k - 1])).clamp(0.0, 1.0);
        (cdf[k - 1] + t * (cdf[k] - cdf[k - 1])) / total
    };
    let mut edges = vec![-1.0f64];
    for b in 1..bins {
        let k = cdf
            .partition_point(|&c| c / total < b as f64 / bins as f64)
            .min(m);
        let c = nodes[k] as f32;
        let mid = 0.5 * (c as f64 + f32::from_bits(c.to_bits() + 1) as f64);
        if mid > edges[edges.len() - 1] && mid < 1.0 {
            edges.push(mid);
        }
    }
    edges.push(1.0);
    let mut rng = Pcg64Mcg::seed_from_u64(seed);
    let mut counts = vec![0usize; edges.len() - 1];
    for _ in 0..n {
        let c = p.sample_cos(rng.random()) as f64;
        assert!((-1.0..=1.0).contains(&c));
        let b = edges.partition_point(|&e| e < c).clamp(1, edges.len() - 1);
        counts[b - 1] += 1;
    }
    let mut chi2 = 0.0;
    for (b, &k) in counts.iter().enumerate() {
        let e = n as f64 * (at(edges[b + 1]) - at(edges[b]));
        chi2 += (k as f64 - e).powi(2) / e;
    }
    chi2
}

#[test]
fn every_sampler_matches_its_evaluation() {
    for (i, (name, p)) in every_phase().into_iter().enumerate() {
        let chi2 = chi_square(&p, 200_000, 50, 100 + i as u64);
        // 49 degrees of freedom: mean 49, sd 9.9; 100 is more than 5 sd above.
        assert!(chi2 < 100.0, "{name}: chi2 = {chi2}");
    }
}

/// The chi-square test must catch a sampler that is slightly off (mutation check of the test).
#[test]
fn chi_square_detects_a_wrong_sampler() {
    let right = Phase::hg(0.5).unwrap();
    let wrong = Phase::hg(0.52).unwrap();
    let chi2 = {
        // Sample `wrong` but judge it against `right`'s density.
        struct Pair(Phase, Phase);
        let Pair(r, w) = Pair(right, wrong);
        let mixed = |xi: f32| w.sample_cos(xi);
        let mut rng = Pcg64Mcg::seed_from_u64(5);
        let n = 200_000usize;
        let mut counts = [0usize; 50];
        for _ in 0..n {
            let c = mixed(rng.random()) as f64;
            let f = cdf(r.g() as f64, c).clamp(0.0, 1.0 - 1e-12);
            counts[(f * 50.0) as usize] += 1;
        }
        let e = n as f64 / 50.0;
        counts
            .iter()
            .map(|&k| (k as f64 - e).powi(2) / e)
            .sum::<f64>()
    };
    assert!(chi2 > 100.0, "chi2 = {chi2}");
}

#[test]
fn hg_variant_is_bit_identical_to_hg() {
    let hg = HenyeyGreenstein::new(0.5).unwrap();
    let p = Phase::Hg(hg);
    let w = Vec3::new(0.2, 0.9, -0.3).normalize();
    let mut rng = Pcg64Mcg::seed_from_u64(3);
    for _ in 0..1000 {
        let (a, b, c): (f32, f32, f32) = (rng.random(), rng.random(), rng.random());
        assert_eq!(p.sample_dir(w, a, b), hg.sample_dir(w, a, b));
        assert_eq!(p.eval(2.0 * c - 1.0), hg.eval(2.0 * c - 1.0));
        let s = p.sample_bins(w, &Spectrum::splat(0.25, 4), 4, [c, a, b]);
        assert_eq!(s.dir, hg.sample_dir(w, a, b));
        assert_eq!(s.weight, Spectrum::splat(1.0, 4));
    }
}

#[test]
fn tabulated_reproduces_an_analytic_hg_table() {
    for g in [0.0f64, 0.5, -0.6, 0.9] {
        let t = hg_table(g, 0.25);
        let exact = HenyeyGreenstein::new(g as f32).unwrap();
        let mut rng = Pcg64Mcg::seed_from_u64(8);
        for _ in 0..20_000 {
            let mu: f32 = 2.0 * rng.random::<f32>() - 1.0;
            let (a, b) = (t.eval(mu) as f64, exact.eval(mu) as f64);
            assert!(((a - b) / b).abs() < 1e-3, "g={g} mu={mu}: {a} vs {b}");
        }
        assert!((t.g() as f64 - g).abs() < 1e-3, "g={g}: table g {}", t.g());
    }
}

/// Two columns (450 and 650 nm): bins at the columns take them, bins between mix them, and
/// the mixture sampler's weights `p_l / p_mix` give every bin its own mean cosine.
#[test]
fn per_bin_table_and_mixture_sampling() {
    let hg = |g: f64, mu: f64| (1.0 - g * g) / (1.0 + g * g - 2.0 * g * mu).powf(1.5);
    let mut text = String::from("angle_deg,450,650nm\n");
    for i in 0..=720 {
        let a = i as f64 * 0.25;
        let mu = a.to_radians().cos();
        text += &format!("{a},{},{}\n", hg(0.2, mu), hg(0.8, mu));
    }
    // Bins of 25 nm centred on 437.5 .. 662.5: the first and last lie beyond the columns.
    let grid = SpectralGrid::new(10, 425.0, 675.0);
    let t = PhaseCsv::parse(&text, Path::new("two.csv"))
        .and_then(|c| c.table(&grid, Path::new("two.csv")))
        .unwrap();
    assert_eq!(t.lanes(), 10);
    let p = Phase::Tabulated(brume::medium::phase_intern(t));
    assert!(p.varies_per_bin());
    let g = p.g_bins(10);
    assert!(
        (g[0] - 0.2).abs() < 1e-3 && (g[9] - 0.8).abs() < 1e-3,
        "{g:?}"
    );
    for l in 1..10 {
        assert!(g[l] > g[l - 1], "mean cosine rises with wavelength: {g:?}");
    }
    // Each lane is a normalised phase.
    for l in [0, 4, 9] {
        let i = integral(|mu| p.eval_bins(mu as f32, 10)[l] as f64);
        assert!((i - 1.0).abs() < 1e-4, "lane {l}: {i}");
    }
    let w = Vec3::new(0.0, 0.6, 0.8);
    let mut weights = Spectrum::ZERO;
    for l in 0..10 {
        weights[l] = (l + 1) as f32;
    }
    let pick = channel_probabilities(ChannelPick::Throughput, &weights, 10, 0.1);
    let mut rng = Pcg64Mcg::seed_from_u64(21);
    let mut acc = stats::Acc::new(10);
    for _ in 0..300_000 {
        let s = p.sample_bins(w, &pick, 10, [rng.random(), rng.random(), rng.random()]);
        let c = s.dir.dot(w);
        let x: Vec<f64> = (0..10).map(|l| (s.weight[l] * c) as f64).collect();
        acc.add(&x);
    }
    for l in 0..10 {
        let z = acc.z(l, g[l] as f64);
        assert!(
            z.abs() < 4.0,
            "bin {l}: E[w cos] = {} vs g {} (z {z})",
            acc.mean(l),
            g[l]
        );
    }
}

#[test]
fn phase_table_errors_name_file_and_line() {
    let f = Path::new("p.csv");
    let err = |t: &str| PhaseCsv::parse(t, f).unwrap_err().to_string();
    let e = err("angle_deg,value\n0,1\n90,-0.5\n180,1\n");
    assert!(e.starts_with("p.csv:3:") && e.contains("negative"), "{e}");
    let e = err("angle_deg,value\n0,1\n90,1\n60,1\n180,1\n");
    assert!(e.starts_with("p.csv:4:") && e.contains("increase"), "{e}");
    let e = err("# only one row\nangle_deg,value\n0,1\n");
    assert!(e.starts_with("p.csv:3:") && e.contains("two rows"), "{e}");
    let e = err("angle_deg,value\n0,1\n90,1\n");
    assert!(e.starts_with("p.csv:3:") && e.contains("180"), "{e}");
    let e = err("angle_deg,value\n0,1\n90,abc\n180,1\n");
    assert!(e.starts_with("p.csv:3:"), "{e}");
    let e = err("angle_deg,red,blue\n0,1,1\n180,1,1\n");
    assert!(e.starts_with("p.csv:1:") && e.contains("wavelength"), "{e}");
    let grid = SpectralGrid::new(4, 400.0, 700.0);
    let zero = PhaseCsv::parse("angle_deg,value\n0,0\n180,0\n", f).unwrap();
    let e = zero.table(&grid, f).unwrap_err().to_string();
    assert!(e.starts_with("p.csv:1:") && e.contains("zero"), "{e}");
}

#[test]
fn rejects_invalid_parameters() {
    assert!(TwoTermHg::new(0.5, -0.5, 1.5).is_err());
    assert!(TwoTermHg::new(1.0, -0.5, 0.5).is_err());
    assert!(Draine::new(0.5, -1.0).is_err());
    assert!(Draine::new(f32::NAN, 1.0).is_err());
    for d in [0.0f32, -1.0, 51.0, f32::NAN] {
        assert!(HgDraine::new(d).is_err(), "d={d}");
    }
}
