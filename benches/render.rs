//! End-to-end throughput on scenes/fog-cube.toml: camera paths/s, gather build time and forward
//! rays/s for q = 1, 0.3, 0.1, 0.03, truncated and eq. 2 cylinders, at 1 and 2 threads. Not a
//! criterion bench: a pass is hundreds of milliseconds, so each case renders a few whole passes and reports the engine's own
//! timers (`Renderer::stats`). Run: `cargo bench --bench render` (env BRUME_BENCH_PASSES=N,
//! default 3; BRUME_BENCH_THREADS="1 2"; BRUME_BENCH_CASES="q=1,cylinders" keeps the cases whose
//! name contains one of the words; BRUME_BENCH_SCENE=scenes/other.toml; BRUME_BENCH_SET="KEY=V ..."
//! adds overrides to every case).

use std::path::Path;
use std::time::Instant;

use brume::integrator::{Budget, Renderer};
use brume::scene::{build, build_integrator, load};

fn main() {
    // `cargo test --benches` runs bench targets without `--bench`: nothing to check here.
    if !std::env::args().any(|a| a == "--bench") {
        return;
    }
    let passes: u32 = std::env::var("BRUME_BENCH_PASSES")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(3);
    let threads: Vec<usize> = std::env::var("BRUME_BENCH_THREADS")
        .unwrap_or_else(|_| "1 2".into())
        .split_whitespace()
        .filter_map(|s| s.parse().ok())
        .collect();
    let scene_file =
        std::env::var("BRUME_BENCH_SCENE").unwrap_or_else(|_| "scenes/fog-cube.toml".into());
    let file = Path::new(env!("CARGO_MANIFEST_DIR")).join(scene_file);
    let wanted: Vec<String> = std::env::var("BRUME_BENCH_CASES")
        .map(|s| s.split(',').map(str::to_string).collect())
        .unwrap_or_default();
    let extra: Vec<String> = std::env::var("BRUME_BENCH_SET")
        .map(|s| s.split_whitespace().map(str::to_string).collect())
        .unwrap_or_default();
    let cases: [(&str, &[&str]); 6] = [
        ("q=1 spheres", &["integrator.q=1.0"]),
        ("q=0.3 spheres", &["integrator.q=0.3"]),
        ("q=0.1 spheres", &["integrator.q=0.1"]),
        ("q=0.03 spheres", &["integrator.q=0.03"]),
        (
            "truncated cylinders",
            &["integrator.volume=\"cylinder-truncated\""],
        ),
        ("cylinders", &["integrator.volume=\"cylinder\""]),
    ];
    println!(
        "| case | threads | passes | wall s | speed-up | camera paths/s | camera s | build s | light s | forward rays/s (light phase) | forward rays/s (wall) | volume records/pass | peak gather MB |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|---|---|---|");
    for (name, sets) in cases {
        if !wanted.is_empty() && !wanted.iter().any(|w| name.contains(w.as_str())) {
            continue;
        }
        let mut sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
        sets.extend(extra.iter().cloned());
        let loaded = load(&file, &sets).unwrap_or_else(|e| panic!("{e}"));
        let scene = build(&loaded).unwrap_or_else(|e| panic!("{e}"));
        let integrator = build_integrator(&loaded, &scene).unwrap_or_else(|e| panic!("{e}"));
        let mut first_wall = None;
        for &t in &threads {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(t)
                .build()
                .expect("thread pool");
            let (s, wall) = pool.install(|| {
                let mut r = Renderer::new(&scene, integrator.clone(), 1);
                let t0 = Instant::now();
                r.run(Budget::Passes(passes), |_, _| {});
                (r.stats, t0.elapsed().as_secs_f64())
            });
            let speedup = first_wall.get_or_insert(wall).to_owned() / wall;
            println!(
                "| {name} | {t} | {passes} | {wall:.2} | {speedup:.2} | {:.3e} | {:.2} | {:.2} | {:.2} | {:.3e} | {:.3e} | {:.3e} | {:.0} |",
                s.camera_paths as f64 / s.camera_seconds,
                s.camera_seconds,
                s.build_seconds,
                s.light_seconds,
                s.forward_rays as f64 / s.light_seconds,
                s.forward_rays as f64 / wall,
                s.volume_records as f64 / passes as f64,
                s.peak_gather_bytes as f64 / 1e6,
            );
        }
    }
}
