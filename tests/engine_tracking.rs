//! Null-collision transport against the exact one on a whole scene (method note 10,
//! docs/media.md "Delta tracking"): scenes/smoke-plume.toml (a grid plume filling 5 % of its
//! box, a spot light, a directional fill, surfaces behind), made denser (multiplier 10) so that
//! multiple scattering and shadowing by the smoke matter, rendered small with
//! `tracking = "delta"` and `"delta-global"` and with the exact optical depth (itself checked
//! against Mitsuba 3 in docs/media.md). This exercises what the single-scattering test of
//! engine_density does not: equiangular NEE about a spot with the camera's transmittance by
//! ratio tracking, shadow rays through the smoke, multiple scattering of forward flights and
//! camera paths. Per region, the difference of the independent means (summed over bins) is
//! within 4 standard errors (8 independent renders each, fixed seeds).

mod common;

use std::path::Path;

use common::*;

const RUNS: u64 = 8;
const PASSES: u32 = 2;
const W: usize = 40;
const H: usize = 52;

fn setup(tracking: &str) -> Setup {
    let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/smoke-plume.toml");
    let sets: Vec<String> = [
        format!("camera.width={W}"),
        format!("camera.height={H}"),
        "integrator.forward_rays=20000".into(),
        "media.smoke.density.multiplier=10".into(),
        format!("media.smoke.tracking=\"{tracking}\""),
    ]
    .into();
    scene_file(&file, &sets)
}

/// Regions: the plume's middle, its top, the wall on either side, the floor.
/// A pixel rectangle `[x0, x1) x [y0, y1)`.
type Rect = (usize, usize, usize, usize);

const REGIONS: [(&str, Rect); 5] = [
    ("plume middle", (14, 26, 18, 34)),
    ("plume top", (12, 28, 2, 16)),
    ("wall left", (0, 12, 4, 40)),
    ("wall right", (28, 40, 4, 40)),
    ("floor", (0, 40, 44, 52)),
];

/// Per region, the mean over bins of each run's region mean: (mean, standard error).
fn estimates(s: &Setup, seed0: u64) -> Vec<(f64, f64)> {
    let mut runs: Vec<Vec<f64>> = vec![Vec::new(); REGIONS.len()];
    for r in 0..RUNS {
        let img = render(s, seed0 + r, PASSES);
        for (k, (_, (x0, x1, y0, y1))) in REGIONS.iter().enumerate() {
            let m = region_mean(&img, &img.data, *x0, *x1, *y0, *y1);
            runs[k].push(m.iter().sum::<f64>() / m.len() as f64);
        }
    }
    runs.iter()
        .map(|v| {
            let k = v.len() as f64;
            let m = v.iter().sum::<f64>() / k;
            let var = v.iter().map(|x| (x - m).powi(2)).sum::<f64>() / (k - 1.0);
            (m, (var / k).sqrt())
        })
        .collect()
}

#[test]
fn tracked_smoke_matches_the_exact_transport() {
    let exact = estimates(&setup("exact"), 100);
    for (tracking, seed0) in [("delta", 300), ("delta-global", 500)] {
        let tracked = estimates(&setup(tracking), seed0);
        for (k, (name, _)) in REGIONS.iter().enumerate() {
            let ((a, sa), (b, sb)) = (exact[k], tracked[k]);
            assert!(a > 0.0, "{name}: the region is black");
            let z = (b - a) / (sa * sa + sb * sb).sqrt();
            println!(
                "{tracking} {name}: exact {a:.5e} +- {sa:.2e}, tracked {b:.5e} +- {sb:.2e}, z = {z:.2}"
            );
            assert!(z.abs() <= 4.0, "{tracking} {name}: z = {z}");
        }
    }
}

/// A tracked medium keeps the renderer's guarantees: 1 and 2 threads, and passes rendered as
/// slices and merged, give the same bytes.
#[test]
fn tracked_renders_are_bit_identical_across_threads_and_merges() {
    let t = tempfile::tempdir().unwrap();
    let d = t.path();
    let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/smoke-plume.toml");
    let run = |extra: &[&str]| {
        let mut args = vec![
            "render".to_string(),
            file.to_string_lossy().into_owned(),
            "-q".into(),
        ];
        for s in [
            "camera.width=24",
            "camera.height=32",
            "integrator.forward_rays=3000",
            "media.smoke.tracking=\"delta\"",
        ] {
            args.push("--set".into());
            args.push(s.into());
        }
        args.extend(extra.iter().map(|s| s.to_string()));
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_brume"))
            .current_dir(d)
            .args(&args)
            .output()
            .expect("brume runs");
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
    };
    run(&["--passes", "3", "--threads", "1", "-o", "a.exr"]);
    run(&["--passes", "3", "--threads", "2", "-o", "b.exr"]);
    run(&["--pass-range", "0..1", "-o", "p0.brume"]);
    run(&["--pass-range", "1..3", "-o", "p1.brume"]);
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_brume"))
        .current_dir(d)
        .args(["merge", "p1.brume", "p0.brume", "-o", "m.exr", "-q"])
        .output()
        .expect("brume runs");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let read = |n: &str| std::fs::read(d.join(n)).unwrap_or_else(|e| panic!("{n}: {e}"));
    assert!(read("a.exr") == read("b.exr"), "1 and 2 threads differ");
    assert!(read("a.exr") == read("m.exr"), "the merged slices differ");
}
