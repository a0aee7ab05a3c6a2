//! Issue 27's bad input for density grids, through the CLI: each refused before rendering,
//! naming the scene file, the line and the key (and the grid file where it is at fault), with
//! nothing written.

use std::path::Path;
use std::process::Command;

use brume::medium::density::grid::{GridData, vol};
use glam::Vec3;

/// A small fog box whose density is `density`, written into `dir` as `s.toml`.
fn write_scene(dir: &Path, density: &str) -> std::path::PathBuf {
    let text = format!(
        r#"[film]
bins = 4
[camera]
type = "orthographic"
width = 8
height = 8
position = [0, 0, 3]
look_at = [0, 0, 0]
[integrator]
forward_rays = 1000
passes = 1
[media.smoke]
sigma_s = 1.0
{density}
[[shapes]]
type = "box"
size = [1, 1, 1]
interior = "smoke"
[[lights]]
type = "directional"
direction = [0, -1, 0]
irradiance = 1.0
"#
    );
    let p = dir.join("s.toml");
    std::fs::write(&p, text).unwrap();
    p
}

/// A one-channel `.vol` of `values` (x fastest) over the box [-0.5, 0.5]³.
fn write_vol(path: &Path, res: [usize; 3], values: &[f32]) {
    let data = GridData {
        res,
        values: values.to_vec(),
        bounds: Some((Vec3::splat(-0.5), Vec3::splat(0.5))),
    };
    std::fs::write(path, vol::encode(&data)).unwrap();
}

/// Runs `brume render` on the scene with `density` and returns its stderr, asserting it
/// failed and wrote nothing.
fn refused(dir: &Path, density: &str) -> String {
    let scene = write_scene(dir, density);
    let out = Command::new(env!("CARGO_BIN_EXE_brume"))
        .args(["render", scene.to_str().unwrap(), "-o", "x.exr", "--quiet"])
        .current_dir(dir)
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(!err.contains("panicked"), "{err}");
    let left: Vec<_> = std::fs::read_dir(dir)
        .unwrap()
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| !n.ends_with(".toml") && !n.ends_with(".vol"))
        .collect();
    assert!(left.is_empty(), "{left:?}");
    // The scene file, the density's line (line 14) and the key.
    assert!(err.contains("s.toml:14"), "{err}");
    err
}

#[test]
fn bad_grids_are_refused_before_rendering_at_their_key() {
    let t = tempfile::tempdir().unwrap();
    let d = t.path();
    let grid =
        |file: &str, more: &str| format!(r#"density = {{ type = "grid", file = "{file}"{more} }}"#);
    let e = refused(d, &grid("missing.vol", ""));
    assert!(
        e.contains("media.smoke.density.file") && e.contains("missing.vol"),
        "{e}"
    );

    std::fs::write(d.join("junk.vol"), b"not a volume").unwrap();
    let e = refused(d, &grid("junk.vol", ""));
    assert!(
        e.contains("media.smoke.density.file") && e.contains("'VOL'"),
        "{e}"
    );

    write_vol(&d.join("neg.vol"), [2, 2, 1], &[0.5, 1.0, -0.25, 0.0]);
    let e = refused(d, &grid("neg.vol", ""));
    assert!(
        e.contains("neg.vol") && e.contains("sample (0, 1, 0) is -0.25"),
        "{e}"
    );

    write_vol(&d.join("nan.vol"), [2, 2, 1], &[0.5, f32::NAN, 1.0, 0.0]);
    let e = refused(d, &grid("nan.vol", ""));
    assert!(e.contains("sample (1, 0, 0) is NaN"), "{e}");

    write_vol(&d.join("zero.vol"), [2, 2, 1], &[0.0; 4]);
    let e = refused(d, &grid("zero.vol", ""));
    assert!(e.contains("every sample is 0"), "{e}");

    write_vol(&d.join("big.vol"), [4, 4, 4], &[1.0; 64]);
    let e = refused(d, &grid("big.vol", ", max_bytes = 100"));
    assert!(
        e.contains("media.smoke.density.max_bytes") && e.contains("256 bytes"),
        "{e}"
    );

    let e = refused(d, &grid("big.vol", r#", grid = "temperature""#));
    assert!(e.contains("media.smoke.density.grid"), "{e}");

    let e = refused(d, &grid("big.txt", ""));
    assert!(e.contains("a .vol or .vdb file"), "{e}");
}

/// An OpenVDB grid loads (`brume info` describes it), and a grid name that is not in the file
/// is refused at `grid`, listing the names the file has.
#[test]
fn vdb_grids_load_and_a_wrong_grid_name_is_refused() {
    let t = tempfile::tempdir().unwrap();
    let d = t.path();
    let data = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data");
    let density = |file: &str, grid: &str| {
        let path = data.join(file);
        format!(
            r#"density = {{ type = "grid", file = "{}", grid = "{grid}" }}"#,
            path.display()
        )
    };
    let scene = write_scene(d, &density("vdb_density.vdb", "density"));
    let out = Command::new(env!("CARGO_BIN_EXE_brume"))
        .args(["info", scene.to_str().unwrap()])
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(text.contains("density grid 5 x 4 x 3 from"), "{text}");
    let e = refused(d, &density("vdb_grids.vdb", "smoke"));
    assert!(
        e.contains("media.smoke.density.grid") && e.contains("no grid named \"smoke\""),
        "{e}"
    );
}

/// A noise density is sampled over its box's shapes (`brume info` names its lattice); bad keys,
/// a lattice over `max_bytes` and a noise with no box to fill are refused at their keys.
#[test]
fn noise_fields_load_and_bad_ones_are_refused() {
    let t = tempfile::tempdir().unwrap();
    let d = t.path();
    let noise =
        r#"density = { type = "noise", scale = 0.5, octaves = 3, contrast = 0.8, seed = 7 }"#;
    let scene = write_scene(d, noise);
    let out = Command::new(env!("CARGO_BIN_EXE_brume"))
        .args(["info", scene.to_str().unwrap()])
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    // 4 samples per finest wavelength (0.125 m) over the 1 m box: 32 per axis.
    assert!(
        text.contains("density grid 32 x 32 x 32 from noise (scale 0.5 m"),
        "{text}"
    );
    let e = refused(
        d,
        r#"density = { type = "noise", scale = 0.5, octaves = 0 }"#,
    );
    assert!(e.contains("media.smoke.density.octaves"), "{e}");
    let e = refused(
        d,
        r#"density = { type = "noise", scale = 0.5, voxel = 0.01, max_bytes = 100000 }"#,
    );
    assert!(
        e.contains("media.smoke.density.voxel") && e.contains("larger `voxel`"),
        "{e}"
    );
    let e = refused(
        d,
        r#"density = { type = "noise", scale = 0.5, times = { type = "layer", top = 0.0, transition = -1.0 } }"#,
    );
    assert!(e.contains("media.smoke.density.times.transition"), "{e}");
}
