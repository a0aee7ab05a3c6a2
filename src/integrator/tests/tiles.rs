//! Tiles of a camera pass under a gather budget (issue 31): every tile's gather stays within
//! the budget at its peak, tiles end between rows whatever the thread count, and a row that
//! alone exceeds the budget stops the pass instead of growing without bound.

use std::path::Path;
use std::sync::atomic::AtomicBool;

use crate::integrator::Integrator;
use crate::integrator::camera_pass::{CameraJob, Halt, camera_pass};
use crate::integrator::gather::peak_bytes_for;
use crate::scene::{build, build_integrator, load};
use crate::world::Scene;

fn fog_cube(q: &str) -> (Scene, Integrator) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/fog-cube.toml");
    let sets = [
        format!("integrator.q={q}"),
        "camera.width=16".into(),
        "camera.height=16".into(),
        "film.bins=4".into(),
    ];
    let loaded = load(&path, &sets).unwrap();
    let scene = build(&loaded).unwrap();
    let integrator = build_integrator(&loaded, &scene).unwrap();
    (scene, integrator)
}

fn job(integrator: &Integrator, first_row: u32, budget_bytes: usize) -> CameraJob {
    CameraJob {
        seed: 5,
        pass: 0,
        radii: integrator.radii(0),
        first_row,
        budget_bytes,
        light_layers: false,
        stride: 1,
        nest_paths: None,
    }
}

/// (first row, rows, volumes, peak bytes) of each tile of pass 0 under `budget`, on `threads`.
fn tiles(s: &(Scene, Integrator), budget: usize, threads: usize) -> Vec<(u32, u32, usize, usize)> {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    let never = AtomicBool::new(false);
    let mut row = 0;
    let mut out = Vec::new();
    pool.install(|| {
        while row < s.0.camera.resolution().1 {
            let (tile, next) = camera_pass(&s.0, &s.1, &job(&s.1, row, budget), &never).unwrap();
            out.push((row, next - row, tile.volumes.len(), peak_bytes_for(&tile)));
            row = next;
        }
    });
    out
}

#[test]
fn tiles_stay_within_the_budget_and_do_not_depend_on_threads() {
    let s = fog_cube("0.05");
    let whole = tiles(&s, usize::MAX, 2);
    assert_eq!(whole.len(), 1);
    let (_, _, volumes, full) = whole[0];
    assert!(volumes > 5_000, "{volumes} volumes");
    let budget = full / 5;
    let one = tiles(&s, budget, 1);
    let two = tiles(&s, budget, 2);
    assert_eq!(one, two);
    assert!((5..=8).contains(&one.len()), "{one:?}");
    for &(_, rows, _, peak) in &one {
        assert!(rows >= 1 && peak <= budget, "{one:?}, budget {budget}");
    }
    // The tiles hold exactly the pass's records.
    assert_eq!(one.iter().map(|t| t.2).sum::<usize>(), volumes);
}

#[test]
fn a_row_over_the_budget_stops_the_pass() {
    let s = fog_cube("0.05");
    let never = AtomicBool::new(false);
    let Err(Halt::OverBudget(e)) = camera_pass(&s.0, &s.1, &job(&s.1, 3, 10_000), &never) else {
        panic!("a row of 16 x 2 camera paths of ~20 volumes each (~180 kB) exceeds 10 kB");
    };
    assert_eq!((e.row, e.budget), (3, 10_000));
    assert!(e.bytes > 10_000);
    let m = e.to_string();
    assert!(
        m.contains("9.8 KiB") && m.contains("max_gather_bytes"),
        "{m}"
    );
}
