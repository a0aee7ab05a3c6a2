//! Droplet fog: size distributions, the droplet optics' own consistency (visibility, liquid
//! water, phase-table normalisation, spectral interpolation), and the scene keys of media with
//! their errors (file, line and key). Cross sections against miepython values made by
//! tools/mie_reference.py (tests/data/mie-reference.csv); the full comparison (phase too) is
//! tests/python/test_mie.py.

use std::path::Path;

use brume::medium::droplets::{
    DistributionKind, DropletsDesc, SizeDistribution, ensemble, optics, phase_angles, visibility,
};
use brume::medium::{Phase, PhaseDesc};
use brume::scene::{SceneError, build, load, load_str};
use brume::spectrum::SpectralGrid;

fn fog(r_eff: f64) -> DropletsDesc {
    DropletsDesc {
        distribution: DistributionKind::Lognormal,
        effective_radius: r_eff,
        width: Some(1.5),
        alpha: None,
        gamma: None,
        number_density: None,
        liquid_water_content: None,
        visibility: Some(200.0),
        refractive_index: "water".into(),
        quadrature_step: 0.02,
    }
}

/// `∫ f(r) n(r) dr / ∫ n(r) dr` by a fine trapezoid in ln r over a wide range.
fn average(d: &SizeDistribution, f: impl Fn(f64) -> f64) -> f64 {
    let (a, b) = ((1e-3f64).ln(), (1e3f64).ln());
    let m = 200_000;
    let (mut num, mut den) = (0.0, 0.0);
    for i in 0..=m {
        let l = a + (b - a) * i as f64 / m as f64;
        let r = l.exp();
        let w = (d.ln_density(r) + l).exp(); // n(r) dr = n(r) r d(ln r)
        num += w * f(r);
        den += w;
    }
    num / den
}

#[test]
fn distributions_have_the_requested_effective_radius() {
    for d in [
        SizeDistribution::lognormal(5.0, 1.5),
        SizeDistribution::lognormal(0.3, 2.0),
        SizeDistribution::modified_gamma(5.0, 6.0, 1.0),
        SizeDistribution::modified_gamma(8.0, 3.0, 0.5),
    ] {
        let r2 = average(&d, |r| r * r);
        let r3 = average(&d, |r| r * r * r);
        assert!((r3 / r2 / d.effective_radius() - 1.0).abs() < 1e-6, "{d:?}");
        assert!((r3 / d.moment(3.0) - 1.0).abs() < 1e-6, "{d:?}: <r³>");
        let target = match d {
            SizeDistribution::LogNormal { .. } if r2 > 1.0 => 5.0,
            SizeDistribution::LogNormal { .. } => 0.3,
            SizeDistribution::ModifiedGamma { alpha, .. } if alpha > 5.0 => 5.0,
            SizeDistribution::ModifiedGamma { .. } => 8.0,
        };
        assert!((d.effective_radius() / target - 1.0).abs() < 1e-9, "{d:?}");
        // The integration range keeps all but ~1e-5 of the cross-section weight <r²>.
        let (lo, hi) = d.range();
        let inside = average(&d, |r| if r >= lo && r <= hi { r * r } else { 0.0 });
        assert!(inside / r2 > 1.0 - 2e-5, "{d:?}: {}", 1.0 - inside / r2);
    }
}

#[test]
fn visibility_and_liquid_water_are_consistent() {
    let grid = SpectralGrid::new(3, 400.0, 700.0); // centre bin at 550 nm
    let o = optics(&fog(2.0), &grid, &|f| f.into()).unwrap();
    assert!((visibility(o.sigma_ext[1]) / 200.0 - 1.0).abs() < 1e-6);
    // The same fog by liquid water content gives the same droplets.
    let mut lwc = fog(2.0);
    (lwc.visibility, lwc.liquid_water_content) = (None, Some(o.liquid_water_content));
    let o2 = optics(&lwc, &grid, &|f| f.into()).unwrap();
    assert!((o2.number_density / o.number_density - 1.0).abs() < 1e-9);
    for l in 0..3 {
        assert!(o.sigma_sca[l] <= o.sigma_ext[l] && o.sigma_abs[l] >= 0.0);
        // Two-sided: an extinction sum off by any factor shows.
        let balance = (o.sigma_sca[l] + o.sigma_abs[l]) / o.sigma_ext[l] - 1.0;
        assert!(
            balance.abs() < 1e-6,
            "bin {l}: (sca + abs) / ext - 1 = {balance:e}"
        );
        assert!(o.g[l] > 0.7 && o.g[l] < 0.9, "g = {}", o.g[l]);
    }
}

/// Size-averaged extinction, scattering and asymmetry of lognormal and modified-gamma water
/// droplets against miepython (tests/data/mie-reference.csv, made by tools/mie_reference.py
/// with its own distributions and a 4x finer size integral, at the index it records): within
/// 1e-4 at the default step (measured: 1.4e-5 at most).
#[test]
fn ensemble_matches_miepython() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/mie-reference.csv");
    let text = std::fs::read_to_string(&path).unwrap();
    let mut rows = 0;
    for line in text.lines().filter(|l| !l.starts_with('#')).skip(1) {
        let f: Vec<&str> = line.split(',').collect();
        let num = |i: usize| f[i].parse::<f64>().unwrap();
        let dist = match f[0] {
            "lognormal" => SizeDistribution::lognormal(num(1), num(2)),
            _ => SizeDistribution::modified_gamma(num(1), num(3), num(4)),
        };
        let m = num_complex::Complex::new(num(6), num(7));
        let o = ensemble(&dist, num(5) / 1000.0, m, &[1.0], 0.02).unwrap();
        for (what, got, want) in [
            ("C_ext", o.c_ext, num(8)),
            ("C_sca", o.c_sca, num(9)),
            ("g", o.g, num(10)),
        ] {
            let rel = got / want - 1.0;
            eprintln!("{line}: {what} {got:.6e} vs {want:.6e} ({rel:.1e})");
            assert!(rel.abs() < 1e-4, "{line}: {what} {got} vs miepython {want}");
        }
        assert!((o.c_sca + o.c_abs) / o.c_ext - 1.0 < 1e-9 && o.c_abs >= 0.0);
        rows += 1;
    }
    assert_eq!(rows, 8, "every reference row is compared");
}

/// The runtime table (linear in cos θ between `phase_angles`) keeps the Lorenz–Mie
/// normalisation and mean cosine to 1e-3, and each lane is a normalised, samplable phase.
#[test]
fn phase_table_keeps_the_mie_normalisation() {
    let grid = SpectralGrid::new(3, 400.0, 700.0);
    let desc = fog(4.0);
    let o = optics(&desc, &grid, &|f| f.into()).unwrap();
    let mu: Vec<f64> = [0.0f64, 30.0, 90.0, 140.0, 180.0]
        .iter()
        .map(|a| a.to_radians().cos())
        .collect();
    let index = brume::medium::droplets::RefractiveIndex::water().unwrap();
    let direct = ensemble(&desc.size(), 0.55, index.at(550.0), &mu, 0.02).unwrap();
    for (j, &m) in mu.iter().enumerate() {
        let t = o.table.eval_lane(1, m as f32) as f64;
        assert!(
            (t / direct.phase[j] - 1.0).abs() < 1e-3,
            "mu={m}: table {t} vs {}",
            direct.phase[j]
        );
    }
    assert!((o.table.g_lane(1) as f64 - direct.g).abs() < 1e-3);
    assert!(phase_angles().windows(2).all(|w| w[0] < w[1]));
}

/// Bins between the solved wavelengths are interpolated linearly; measured against solving at
/// the bin centre itself.
#[test]
fn spectral_interpolation_is_accurate() {
    let grid = SpectralGrid::new(16, 380.0, 780.0);
    let desc = fog(3.0);
    let o = optics(&desc, &grid, &|f| f.into()).unwrap();
    assert_eq!(o.samples.len(), 8);
    let index = brume::medium::droplets::RefractiveIndex::water().unwrap();
    let bin = 6; // centre 542.5 nm, between two samples
    let lam = grid.centre(bin);
    let direct = ensemble(
        &desc.size(),
        lam / 1000.0,
        index.at(lam),
        &[1.0, -1.0],
        0.02,
    )
    .unwrap();
    let sigma = direct.c_ext * o.number_density * 1e-6;
    println!(
        "bin {bin}: interpolated sigma_ext {:.3e} relative, g {:.3e} absolute",
        o.sigma_ext[bin] / sigma - 1.0,
        o.g[bin] - direct.g
    );
    assert!(
        (o.sigma_ext[bin] / sigma - 1.0).abs() < 2e-3,
        "{} vs {sigma}",
        o.sigma_ext[bin]
    );
    assert!((o.g[bin] - direct.g).abs() < 2e-3);
}

/// A spectral line's bin holds the droplets' optics at the line itself: the line is solved
/// along with the evenly spaced wavelengths, not interpolated between them.
#[test]
fn a_line_bin_is_solved_at_its_line() {
    let grid = SpectralGrid::with_lines(9, 380.0, 780.0, &[532.0]).unwrap();
    let desc = fog(3.0);
    let o = optics(&desc, &grid, &|f| f.into()).unwrap();
    assert!(grid.n > 8 && o.samples.len() == 9 && o.samples.contains(&532.0));
    let index = brume::medium::droplets::RefractiveIndex::water().unwrap();
    let direct = ensemble(&desc.size(), 0.532, index.at(532.0), &[1.0, -1.0], 0.02).unwrap();
    let bin = grid.line_bin(532.0).unwrap();
    let sigma = direct.c_ext * o.number_density * 1e-6;
    assert!(
        (o.sigma_ext[bin] / sigma - 1.0).abs() < 1e-9,
        "{} vs {sigma}",
        o.sigma_ext[bin]
    );
    assert!((o.g[bin] - direct.g).abs() < 1e-9);
}

const SCENE: &str = r#"
[camera]
width = 8
height = 8

[film]
bins = 4

[media.fog]
sigma_s = 0.5
g = 0.5

[[shapes]]
type = "box"
size = [1, 1, 1]
interior = "fog"
"#;

fn fails(text: &str, dir: &Path) -> SceneError {
    let file = dir.join("test.toml");
    std::fs::write(&file, text).unwrap();
    match load(&file, &[]).and_then(|l| build(&l).map(|_| ())) {
        Ok(()) => panic!("scene unexpectedly accepted:\n{text}"),
        Err(e) => e,
    }
}

#[test]
fn existing_hg_scenes_load_as_hg() {
    let s = load_str(SCENE, Path::new("t.toml"), &[]).unwrap();
    let scene = build(&s).unwrap();
    assert_eq!(scene.media[0].phase, Phase::hg(0.5).unwrap());
    let s = load_str(&SCENE.replace("g = 0.5\n", ""), Path::new("t.toml"), &[]).unwrap();
    assert_eq!(build(&s).unwrap().media[0].phase, Phase::hg(0.0).unwrap());
}

#[test]
fn phase_keys_build_their_phase() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("p.csv"),
        "angle_deg,value\n0,2\n90,1\n180,1\n",
    )
    .unwrap();
    for (text, want) in [
        ("{ type = \"rayleigh\" }", "rayleigh"),
        ("{ type = \"hg-draine\", diameter = 10.0 }", "hg-draine"),
        (
            "{ type = \"two-term-hg\", g1 = 0.8, g2 = -0.3, weight = 0.9 }",
            "two-term-hg",
        ),
        ("{ type = \"draine\", g = 0.3, alpha = 1.0 }", "draine"),
        ("{ type = \"tabulated\", file = \"p.csv\" }", "tabulated"),
    ] {
        let t = SCENE.replace("g = 0.5", &format!("phase = {text}"));
        let file = dir.path().join("ok.toml");
        std::fs::write(&file, t).unwrap();
        let scene = build(&load(&file, &[]).unwrap()).unwrap();
        assert!(scene.media[0].phase.describe().starts_with(want), "{want}");
    }
    // The description round-trips through --set (which re-serialises the scene).
    let s = load_str(
        SCENE,
        Path::new("t.toml"),
        &[
            "media.fog.phase={type=\"rayleigh\"}".into(),
            "media.fog.g=0.1".into(),
        ],
    );
    assert!(s.is_err(), "g and phase together are refused");
    let _ = PhaseDesc::Rayleigh;
}

/// Each bad medium names its file, line and key.
#[test]
fn bad_media_name_file_line_and_key() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let at = |e: &SceneError, file: &str, line: usize, key: &str| {
        let text = e.to_string();
        let want = format!("{}:{line}:", d.join(file).display());
        assert!(text.starts_with(&want), "{text}\n(want {want})");
        assert_eq!(e.key(), Some(key), "{text}");
    };
    let e = fails(&SCENE.replace("g = 0.5", "phase = { type = \"mie\" }"), d);
    at(&e, "test.toml", 11, "media.fog.phase.type");
    assert!(e.to_string().contains("unknown variant"), "{e}");

    std::fs::write(d.join("neg.csv"), "angle_deg,value\n0,1\n90,-0.5\n180,1\n").unwrap();
    let e = fails(
        &SCENE.replace(
            "g = 0.5",
            "phase = { type = \"tabulated\", file = \"neg.csv\" }",
        ),
        d,
    );
    at(&e, "neg.csv", 3, "media.fog.phase.file");
    assert!(e.to_string().contains("negative"), "{e}");

    std::fs::write(
        d.join("order.csv"),
        "angle_deg,value\n0,1\n90,1\n45,1\n180,1\n",
    )
    .unwrap();
    let e = fails(
        &SCENE.replace(
            "g = 0.5",
            "phase = { type = \"tabulated\", file = \"order.csv\" }",
        ),
        d,
    );
    at(&e, "order.csv", 4, "media.fog.phase.file");

    std::fs::write(d.join("short.csv"), "angle_deg,value\n0,1\n").unwrap();
    let e = fails(
        &SCENE.replace(
            "g = 0.5",
            "phase = { type = \"tabulated\", file = \"short.csv\" }",
        ),
        d,
    );
    at(&e, "short.csv", 2, "media.fog.phase.file");

    let droplets = "[media.fog.droplets]\ndistribution = \"lognormal\"\neffective_radius = 0.0\nvisibility = 100.0\n";
    let e = fails(&SCENE.replace("sigma_s = 0.5\ng = 0.5\n", droplets), d);
    at(&e, "test.toml", 12, "media.fog.droplets.effective_radius");

    let e = fails(
        &SCENE.replace(
            "g = 0.5",
            "phase = { type = \"hg-draine\", diameter = -2.0 }",
        ),
        d,
    );
    at(&e, "test.toml", 11, "media.fog.phase.diameter");

    let e = fails(
        &SCENE.replace("g = 0.5", "phase = { type = \"rayleigh\" }\ng = 0.3"),
        d,
    );
    at(&e, "test.toml", 12, "media.fog.g");
}

/// Droplet sizes and amounts outside what can be solved or exists are refused before any
/// solving, with the key and the valid range: 1 nm droplets (were an internal Lorenz-Mie
/// message about angular-table orders), 1 mm droplets (were solved for hours without a sign),
/// more liquid water than water's own density (was accepted), and a number density that
/// implies it.
#[test]
fn droplets_out_of_range_are_refused_with_their_key() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let with = |keys: &str| {
        let block = format!("[media.fog.droplets]\ndistribution = \"lognormal\"\n{keys}\n");
        SCENE.replace("sigma_s = 0.5\ng = 0.5\n", &block)
    };
    let e = fails(&with("effective_radius = 1e-3\nvisibility = 100.0"), d);
    assert_eq!(e.key(), Some("media.fog.droplets.effective_radius"), "{e}");
    assert!(
        e.to_string().contains("in [0.01, 1000] µm, got 0.001"),
        "{e}"
    );

    let e = fails(
        &with("effective_radius = 2.0\nliquid_water_content = 2e6"),
        d,
    );
    assert_eq!(
        e.key(),
        Some("media.fog.droplets.liquid_water_content"),
        "{e}"
    );
    assert!(
        e.to_string().contains("below the density of liquid water"),
        "{e}"
    );

    let e = fails(&with("effective_radius = 0.5\nnumber_density = 1e13"), d);
    assert!(
        e.to_string().contains("more than liquid water itself"),
        "{e}"
    );

    let start = std::time::Instant::now();
    let e = fails(
        &with("effective_radius = 1000.0\nwidth = 5.0\nvisibility = 100.0"),
        d,
    );
    let text = e.to_string();
    assert!(
        start.elapsed().as_secs_f64() < 10.0,
        "refused only after solving"
    );
    assert_eq!(e.key(), Some("media.fog.droplets"), "{e}");
    assert!(
        text.contains("effective_radius 1000 µm would need") && text.contains("smaller droplets"),
        "{e}"
    );
}

/// The smallest droplets in the narrowest distribution are solved over at least 64 radii
/// (the default spacing would give two, and a solution with more terms than its angular
/// table); their optics are checked against miepython in `ensemble_matches_miepython`.
#[test]
fn the_smallest_droplets_are_solved_over_enough_radii() {
    let index = brume::medium::droplets::RefractiveIndex::water().unwrap();
    let dist = SizeDistribution::lognormal(0.01, 1.01);
    let mu: Vec<f64> = phase_angles()
        .iter()
        .map(|a| a.to_radians().cos())
        .collect();
    let o = ensemble(&dist, 0.38, index.at(380.0), &mu, 0.02).unwrap();
    assert!(o.nodes >= 65, "{} radii", o.nodes);
    assert!(o.c_sca > 0.0 && o.phase.iter().all(|p| p.is_finite() && *p > 0.0));
}

/// A droplet fog (a phase per spectral bin) builds and renders: finite, lit pixels; `info`
/// describes it.
#[test]
fn droplet_fog_builds_and_renders() {
    let dir = tempfile::tempdir().unwrap();
    let droplets = "[media.fog.droplets]\ndistribution = \"lognormal\"\neffective_radius = 1.0\nnumber_density = 100.0\n";
    let light = "\n[[lights]]\ntype = \"point\"\nposition = [0, 0, 0]\npower = 10.0\n";
    let text = SCENE.replace("sigma_s = 0.5\ng = 0.5\n", droplets) + light;
    let file = dir.path().join("test.toml");
    std::fs::write(&file, &text).unwrap();
    let loaded = load(&file, &["camera.width=8".into(), "camera.height=8".into()]).unwrap();
    let scene = brume::scene::build(&loaded).expect("a droplet fog builds");
    assert!(scene.media[0].phase.varies_per_bin());
    let integrator = brume::scene::build_integrator(&loaded, &scene).unwrap();
    let mut r = brume::integrator::Renderer::new(&scene, integrator, 3);
    r.run(brume::integrator::Budget::Passes(1), |_, _| {});
    let img = r.image();
    assert!(img.data.iter().all(|v| v.is_finite()));
    assert!(img.data.iter().any(|v| *v > 0.0), "the image is black");
    let s = brume::scene::summary::summarise(&load(&file, &[]).unwrap());
    let text = s.to_string();
    assert!(
        text.contains("medium fog: phase tabulated (Lorenz-Mie"),
        "{text}"
    );
    assert!(text.contains("visibility (m)"), "{text}");
}
