//! Tiny end-to-end studies of a small fog scene:
//! - through the library, against a rendered (spectral) reference: the CSV has the documented
//!   schema and one row per variant, run and pass; invalid variants are skipped;
//! - through `brume study`, against EXR references: brume's own EXR (RGB with layers) and a
//!   foreign-looking one (RGB only, no chromaticities, half as bright): PNG plots exist and
//!   decode, the CSV's efficiencies equal 1 / (MSE x t) from its own columns, the fitted scale
//!   recovers the factor 2, the CPU-time budget is kept, and a value the scene refuses
//!   (`integrator.q=auto` until the automatic q lands) is reported, not fatal.

use std::path::Path;
use std::process::Command;

use brume::study::{
    Budget, CSV_HEADER, StudyConfig, expand, parse_vary, render_reference, run_study, summarise,
    write_csv, write_plots,
};

const SCENE: &str = r#"
[film]
bins = 4
[camera]
type = "orthographic"
width = 8
height = 8
position = [0.0, 0.0, 3.0]
look_at = [0.0, 0.0, 0.0]
[integrator]
radius = 0.05
forward_rays = 4000
[media.fog]
sigma_s = 0.8
sigma_a = 0.2
g = 0.5
[materials.wall]
type = "lambert"
albedo = 0.4
[[shapes]]
type = "box"
size = [1.0, 1.0, 1.0]
interior = "fog"
[[shapes]]
type = "quad"
size = [1.0, 1.0]
material = "wall"
transform = { translate = [0.0, 0.0, -0.5002] }
[[lights]]
type = "directional"
direction = [0.5, -0.5, -0.70710678]
irradiance = 1000.0
"#;

#[test]
fn tiny_study_end_to_end() {
    let dir = tempfile::tempdir().unwrap();
    let scene = dir.path().join("tiny.toml");
    std::fs::write(&scene, SCENE).unwrap();
    let variants = expand(&[
        parse_vary("integrator.q=1,0.3").unwrap(),
        parse_vary("integrator.volume=spheres,nonsense").unwrap(),
    ]);
    let cfg = StudyConfig {
        scene: scene.clone(),
        sets: vec![],
        variants: variants.clone(),
        budget: Budget::wall(0.5),
        runs: 2,
        seed: 3,
        fit_scale: false,
    };
    let sets = vec!["integrator.volume=cylinder".to_string()];
    let reference = render_reference(&scene, &sets, 1.0, 3, |_| {}).unwrap();
    assert!(reference.passes >= 1);
    let mut invalid_events = 0;
    let (rows, invalid) = run_study(&cfg, &reference, |e| {
        if let brume::study::Event::Invalid { .. } = e {
            invalid_events += 1;
        }
    })
    .unwrap();
    // "nonsense" is not a volume: 2 of the 4 combinations are reported and skipped.
    assert_eq!(invalid.len(), 2);
    assert_eq!(invalid_events, 2);
    for r in &rows {
        assert!(r.variant == 0 || r.variant == 2, "invalid variant rendered");
        assert!(r.checkpoint.total.mse.is_finite() && r.checkpoint.total.mse > 0.0);
        // A rendered reference has the layers: they are measured.
        assert!(r.checkpoint.medium.is_some() && r.checkpoint.surface.is_some());
        assert!(r.checkpoint.fit.is_none());
    }
    // Every run spends its budget and no more (issue 31: whole passes ran a 4 s budget to
    // 15.8 s): the last checkpoint is at 0.5 s, plus the moment it takes to abandon the pass
    // in flight, unless its first pass alone is longer (then it is the only one, flagged). The
    // checkpoints before it are short of 0.5 s; a run stopped inside a pass ends with a
    // checkpoint of the same passes at the whole time spent.
    let budget = Budget::wall(0.5);
    for v in [0, 2] {
        for run in 0..2 {
            let cps: Vec<_> = rows
                .iter()
                .filter(|r| r.variant == v && r.run == run)
                .map(|r| r.checkpoint)
                .collect();
            assert!(!cps.is_empty());
            let last = cps.last().unwrap();
            assert!(last.seconds >= 0.5);
            let e = brume::study::Elapsed {
                wall: last.seconds,
                cpu: last.cpu_seconds,
            };
            assert!(!budget.overrun(e) || cps.len() == 1, "{cps:?}");
            for c in &cps[..cps.len() - 1] {
                assert!(c.seconds < 0.5, "{cps:?}");
            }
            for (i, c) in cps.iter().enumerate() {
                let stopped = i + 1 == cps.len() && i > 0 && c.passes == cps[i - 1].passes;
                assert!(c.passes == i as u64 + 1 || stopped, "{cps:?}");
            }
        }
    }

    let csv = dir.path().join("study.csv");
    write_csv(&csv, &variants, &rows).unwrap();
    let text = std::fs::read_to_string(&csv).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines[0], CSV_HEADER);
    let cols = CSV_HEADER.split(',').count();
    assert_eq!(cols, 22);
    assert_eq!(lines.len(), rows.len() + 1);
    for l in &lines[1..] {
        let fields: Vec<&str> = l.split(',').collect();
        assert_eq!(fields.len(), cols, "row {l}");
        // Everything up to the CPU efficiency is measured; k and the scaled MSE are not.
        for f in &fields[4..19] {
            let v: f64 = f
                .parse()
                .unwrap_or_else(|_| panic!("not a number: {f:?} in {l}"));
            assert!(v.is_finite() || f.contains("inf"));
        }
        assert!(fields[19..].iter().all(|f| f.is_empty()), "{l}");
    }

    let s = summarise(&cfg, &reference, "test", &rows, &invalid);
    assert_eq!(s.variants.len(), 2);
    assert_eq!(s.invalid.len(), 2);
    for v in &s.variants {
        assert_eq!(v.runs, 2);
        assert_eq!(
            v.over_budget,
            s.notes
                .iter()
                .any(|n| n.starts_with(&v.label) && n.contains("NOT at equal time"))
        );
        assert!((v.efficiency - 1.0 / (v.mse * v.mean_seconds)).abs() <= 1e-9 * v.efficiency);
        assert!(v.medium_mse.is_some());
    }
    // The best of each measure is the variant with the largest mean efficiency over runs.
    let names: Vec<&str> = s.best_per_layer.iter().map(|b| b.measure.name()).collect();
    assert_eq!(names, ["image", "medium", "surface"]);
    for b in &s.best_per_layer {
        let top = s
            .variants
            .iter()
            .max_by(|x, y| {
                let e = |v: &brume::study::VariantSummary| v.efficiency_over_runs[&b.measure].mean;
                e(x).total_cmp(&e(y))
            })
            .unwrap();
        assert_eq!(b.label, top.label);
        assert!(b.efficiency.se.is_some() && b.separation_sigma.is_some());
    }
    assert_eq!(s.best, s.best_per_layer[0].label);
    assert!(serde_json::to_string(&s).is_ok());
    let plots = write_plots(dir.path(), &variants, &rows, &s).unwrap();
    // error-vs-time, efficiency, efficiency-vs-q for image, medium and surface, SVG and PNG.
    assert_eq!(plots.len(), 18, "{plots:?}");
    for p in &plots {
        assert!(p.exists(), "{}", p.display());
    }
    // The reference's noise floor is drawn on the whole image's error plot (issue 31).
    assert!(s.reference_noise_mse.is_some());
    let svg = std::fs::read_to_string(dir.path().join("error-vs-time.svg")).unwrap();
    assert!(
        svg.contains("reference noise floor"),
        "no floor on the error plot"
    );
}

/// Issue 31 item 15: `--vary integrator.q=0.5,abc` found the bad value only after the
/// reference render. Every variant is checked first: a study whose variants are all refused
/// fails before it renders anything (no reference written), and a refused value among good
/// ones is reported before the reference is rendered.
#[test]
fn variants_are_checked_before_any_rendering() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::write(d.join("tiny.toml"), SCENE).unwrap();
    let t0 = std::time::Instant::now();
    let out = brume(
        &[
            "study",
            "tiny.toml",
            "--vary",
            "integrator.q=abc,-1",
            "--time",
            "0.2",
            "--reference-time",
            "30",
            "-o",
            "bad",
            "-q",
        ],
        d,
    );
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("integrator.q") && err.contains("no valid variant"),
        "{err}"
    );
    assert!(
        !d.join("bad/reference.bin").exists(),
        "the reference was rendered"
    );
    assert!(
        t0.elapsed().as_secs_f64() < 25.0,
        "a 30 s reference was rendered first"
    );

    let cfg = StudyConfig {
        scene: d.join("tiny.toml"),
        sets: vec![],
        variants: expand(&[parse_vary("integrator.q=0.5,abc").unwrap()]),
        budget: Budget::wall(0.2),
        runs: 1,
        seed: 0,
        fit_scale: false,
    };
    let invalid = brume::study::check_variants(&cfg).unwrap();
    assert_eq!(invalid.len(), 1);
    assert_eq!(invalid[0].0, 1);
    assert!(invalid[0].1.contains("integrator.q"), "{invalid:?}");
}

/// Issue 31: the study's images are written with one exposure, so that they compare. With a
/// metered ("auto") exposure, a variant lit 4x as brightly as the reference comes out brighter,
/// where metering each image would have shown both alike.
#[test]
fn study_images_share_one_exposure() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::write(d.join("tiny.toml"), SCENE).unwrap();
    let out = brume(
        &[
            "study",
            "tiny.toml",
            "--set",
            "film.exposure=auto",
            "--vary",
            "lights.0.irradiance=250,1000",
            "--time",
            "0.2",
            "--runs",
            "1",
            "--reference-time",
            "0.5",
            "-o",
            "exp",
            "-q",
        ],
        d,
    );
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let mean = |name: &str| {
        let img = image::open(d.join("exp").join(name)).unwrap().to_rgb8();
        let n = img.pixels().len() as f64;
        img.pixels().map(|p| p.0[1] as f64).sum::<f64>() / n
    };
    let (dim, bright) = (mean("irradiance-250.png"), mean("irradiance-1000.png"));
    assert!(
        bright > dim + 30.0,
        "dim {dim}, bright {bright}: metered apart"
    );
}

fn brume(args: &[&str], cwd: &Path) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_brume"))
        .current_dir(cwd)
        .args(args)
        .output()
        .expect("brume runs")
}

/// study.csv as (header, rows of fields).
fn read_csv(path: &Path) -> (Vec<String>, Vec<Vec<String>>) {
    let text = std::fs::read_to_string(path).expect("study.csv");
    let mut lines = text.lines();
    let header = lines
        .next()
        .expect("header")
        .split(',')
        .map(String::from)
        .collect();
    let rows = lines
        .map(|l| l.split(',').map(String::from).collect())
        .collect();
    (header, rows)
}

fn column(header: &[String], row: &[String], name: &str) -> Option<f64> {
    let i = header.iter().position(|h| h == name).expect(name);
    row[i].parse().ok()
}

/// Every PNG plot decodes to an image with more than a few colours (axes, text and series).
fn check_pngs(dir: &Path, names: &[&str]) {
    for n in names {
        let p = dir.join(n);
        let img = image::open(&p)
            .unwrap_or_else(|e| panic!("{}: {e}", p.display()))
            .to_rgb8();
        assert!(img.width() >= 300 && img.height() >= 300, "{n}");
        let mut colours: Vec<[u8; 3]> = img.pixels().map(|p| p.0).collect();
        colours.sort();
        colours.dedup();
        assert!(colours.len() > 20, "{n}: only {} colours", colours.len());
        assert!(
            dir.join(n).with_extension("svg").exists(),
            "{n}: no SVG beside it"
        );
    }
}

/// The CSV's efficiency columns are 1 / (MSE x t) of its own MSE and time columns.
fn check_efficiencies(header: &[String], rows: &[Vec<String>]) {
    assert!(!rows.is_empty());
    for r in rows {
        let mse = column(header, r, "mse").expect("mse");
        for (t, eff) in [("seconds", "efficiency"), ("cpu_seconds", "cpu_efficiency")] {
            let t = column(header, r, t).expect("time");
            let e = column(header, r, eff).expect("efficiency");
            let want = 1.0 / (mse * t);
            assert!(
                (e - want).abs() <= 1e-12 * want,
                "{eff}: {e} vs 1/(mse t) = {want}"
            );
        }
    }
}

#[test]
fn study_against_exr_references_through_the_cli() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::write(d.join("tiny.toml"), SCENE).unwrap();
    let out = brume(
        &[
            "render",
            "tiny.toml",
            "--passes",
            "12",
            "--seed",
            "99",
            "-o",
            "ref.exr",
            "-q",
        ],
        d,
    );
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );

    // brume's own EXR: RGB with chromaticities and the medium / surface layers.
    let out = brume(
        &[
            "study",
            "tiny.toml",
            "--vary",
            "integrator.q=1,0.3,auto",
            "--time",
            "0.3",
            "--runs",
            "2",
            "--reference",
            "ref.exr",
            "--fit-scale",
            "-o",
            "own",
            "-q",
        ],
        d,
    );
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(stdout.contains("most efficient (image): q="), "{stdout}");
    assert!(stdout.contains("most efficient (medium): q="), "{stdout}");
    let own = d.join("own");
    check_pngs(
        &own,
        &[
            "error-vs-time.png",
            "efficiency.png",
            "efficiency-vs-q.png",
            "error-vs-time-medium.png",
            "efficiency-surface.png",
            "error-vs-time-scaled.png",
        ],
    );
    let (header, rows) = read_csv(&own.join("study.csv"));
    assert_eq!(header.join(","), CSV_HEADER);
    check_efficiencies(&header, &rows);
    for r in &rows {
        assert!(
            column(&header, r, "medium_mse").is_some(),
            "brume's EXR has layers"
        );
        // Same scene, independent seeds: the fitted scale is near 1.
        let k = column(&header, r, "k").expect("k");
        assert!((0.7..1.4).contains(&k), "k = {k}");
        let (mse, scaled) = (column(&header, r, "mse"), column(&header, r, "mse_scaled"));
        assert!(scaled.expect("scaled") <= mse.expect("mse") * (1.0 + 1e-9));
    }
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(own.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["clock"], "wall");
    assert_eq!(summary["reference_has_layers"], true);
    // `auto` is either refused by the scene (reported, skipped) or, once it exists, rendered.
    let refused = summary["invalid"]
        .as_array()
        .unwrap()
        .iter()
        .any(|i| i[0] == "q=auto");
    let rendered = summary["variants"]
        .as_array()
        .unwrap()
        .iter()
        .any(|v| v["label"] == "q=auto");
    assert!(refused != rendered, "{summary}");
    if refused {
        assert!(String::from_utf8_lossy(&out.stderr).contains("variant q=auto skipped"));
    }

    foreign_reference(d);
}

/// An RGB-only EXR without chromaticities, half as bright as brume's: refused until its space
/// is stated; then compared in RGB with the scale fitted (k close to 2), no layers, and a
/// CPU-time budget.
fn foreign_reference(d: &Path) {
    use exr::prelude::*;
    let img = read_first_rgba_layer_from_file(
        d.join("ref.exr"),
        |size, _| (size, vec![[0f32; 3]; size.0 * size.1]),
        |(size, px), pos, (r, g, b, _a): (f32, f32, f32, f32)| {
            px[pos.1 * size.0 + pos.0] = [r * 0.5, g * 0.5, b * 0.5];
        },
    )
    .unwrap();
    let (size, px) = img.layer_data.channel_data.pixels;
    write_rgb_file(d.join("other.exr"), size.0, size.1, |x, y| {
        let p = px[y * size.0 + x];
        (p[0], p[1], p[2])
    })
    .unwrap();

    let args = |extra: &[&'static str]| {
        let mut a = vec![
            "study",
            "tiny.toml",
            "--vary",
            "integrator.direct=nee,photons",
            "--cpu-time",
            "0.3",
            "--runs",
            "2",
            "--threads",
            "1",
            "--reference",
            "other.exr",
            "--fit-scale",
            "-o",
            "foreign",
            "-q",
        ];
        a.extend_from_slice(extra);
        a
    };
    let out = brume(&args(&[]), d);
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("other.exr") && err.contains("--reference-space"),
        "{err}"
    );

    let out = brume(&args(&["--reference-space", "srgb"]), d);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(stdout.contains("no medium / surface layers"), "{stdout}");
    let f = d.join("foreign");
    check_pngs(
        &f,
        &[
            "error-vs-time.png",
            "efficiency.png",
            "error-vs-time-scaled.png",
        ],
    );
    assert!(!f.join("error-vs-time-medium.png").exists());
    assert!(!f.join("efficiency-vs-q.png").exists(), "q was not varied");
    let (header, rows) = read_csv(&f.join("study.csv"));
    check_efficiencies(&header, &rows);
    for r in &rows {
        assert!(column(&header, r, "medium_mse").is_none());
        let k = column(&header, r, "k").expect("k");
        assert!((1.4..2.8).contains(&k), "k = {k}, want about 2");
    }
    // The CPU budget: each run stops at the first pass that reaches 0.3 CPU seconds; with one
    // worker thread the process cannot use much more CPU than wall time.
    for run in ["0", "1"] {
        for variant in ["0", "1"] {
            let cps: Vec<&Vec<String>> = rows
                .iter()
                .filter(|r| r[0] == variant && r[2] == run)
                .collect();
            let cpu = |r: &Vec<String>| column(&header, r, "cpu_seconds").expect("cpu");
            let last = cps.last().expect("checkpoints");
            assert!(cpu(last) >= 0.3, "{last:?}");
            if cps.len() > 1 {
                assert!(cpu(cps[cps.len() - 2]) < 0.3);
            }
            let wall = column(&header, last, "seconds").expect("wall");
            assert!(
                cpu(last) <= 1.3 * wall + 0.05,
                "cpu {} wall {wall}",
                cpu(last)
            );
        }
    }
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(f.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["clock"], "cpu");
    assert_eq!(summary["reference_has_layers"], false);
    let bests: Vec<&str> = summary["best_per_layer"]
        .as_array()
        .unwrap()
        .iter()
        .map(|b| b["measure"].as_str().unwrap())
        .collect();
    assert_eq!(bests, ["image", "image_scaled"]);
}
