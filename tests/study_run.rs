//! A tiny end-to-end study: two variants of a small fog scene for 0.5 s each against a
//! rendered reference; the CSV has the documented schema and one row per variant, run and pass.

use std::path::Path;

use brume::study::{
    CSV_HEADER, StudyConfig, expand, parse_vary, render_reference, run_study, summarise, write_csv,
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
        seconds: 0.5,
        runs: 2,
        seed: 3,
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
    }
    // Every run spends its budget: the last checkpoint is at or past 0.5 s, the one before
    // it (if any) short of it.
    for v in [0, 2] {
        for run in 0..2 {
            let cps: Vec<_> = rows
                .iter()
                .filter(|r| r.variant == v && r.run == run)
                .map(|r| r.checkpoint)
                .collect();
            assert!(!cps.is_empty());
            assert!(cps.last().unwrap().seconds >= 0.5);
            if cps.len() > 1 {
                assert!(cps[cps.len() - 2].seconds < 0.5);
            }
            for (i, c) in cps.iter().enumerate() {
                assert_eq!(c.passes, i as u64 + 1);
            }
        }
    }

    let csv = dir.path().join("study.csv");
    write_csv(&csv, &variants, &rows).unwrap();
    let text = std::fs::read_to_string(&csv).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines[0], CSV_HEADER);
    let cols = CSV_HEADER.split(',').count();
    assert_eq!(cols, 17);
    assert_eq!(lines.len(), rows.len() + 1);
    for l in &lines[1..] {
        assert_eq!(l.split(',').count(), cols, "row {l}");
        let fields: Vec<&str> = l.split(',').collect();
        for f in &fields[4..] {
            let v: f64 = f.parse().unwrap_or_else(|_| panic!("not a number: {f}"));
            assert!(v.is_finite() || f.contains("inf"));
        }
    }

    let s = summarise(
        &cfg,
        "test",
        (reference.passes, reference.seconds, 0.0),
        &rows,
        &invalid,
    );
    assert_eq!(s.variants.len(), 2);
    assert_eq!(s.invalid.len(), 2);
    for v in &s.variants {
        assert_eq!(v.runs, 2);
        assert!((v.efficiency - 1.0 / (v.mse * v.mean_seconds)).abs() <= 1e-9 * v.efficiency);
    }
    assert!(serde_json::to_string(&s).is_ok());
    brume::study::plot_error_vs_time(&dir.path().join("e.svg"), &variants, &rows).unwrap();
    brume::study::plot_efficiency(
        &dir.path().join("q.svg"),
        &variants,
        &s.variants,
        "integrator.q",
    )
    .unwrap();
    assert!(Path::new(&dir.path().join("q.svg")).exists());
}
