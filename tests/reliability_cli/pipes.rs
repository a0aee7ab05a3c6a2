//! A reader that closes brume's standard output early (`brume info --json | head -1`): the
//! command neither panics nor loses work. Each child gets a pipe whose read end is closed before
//! it writes, so every write to standard output fails with a broken pipe, deterministically.

use std::path::Path;
use std::process::{Command, Stdio};

use super::{SMALL, scene};

/// Runs brume with its standard output a pipe closed before it writes; (success, stderr).
fn closed_stdout(dir: &Path, args: &[&str]) -> (bool, String) {
    let mut child = Command::new(env!("CARGO_BIN_EXE_brume"))
        .args(args)
        .current_dir(dir)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("spawn brume");
    drop(child.stdout.take());
    let out = child.wait_with_output().expect("brume runs");
    (
        out.status.success(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

#[test]
fn a_closed_standard_output_neither_panics_nor_loses_work() {
    let tmp = tempfile::tempdir().expect("tempdir");
    let dir = tmp.path();
    let s = scene(dir);
    let s = s.to_str().expect("utf-8 path");
    for args in [vec!["info", "--json", s], vec!["info", s]] {
        let (ok, err) = closed_stdout(dir, &args);
        assert!(!err.contains("panicked"), "{args:?}: {err}");
        assert!(ok, "{args:?}: {err}");
    }
    // A render whose --verbose report and sensor table go nowhere still saves its image.
    let mut args = vec!["render", s, "--passes", "2", "--verbose", "-o", "x.exr"];
    args.extend(SMALL);
    let (ok, err) = closed_stdout(dir, &args);
    assert!(!err.contains("panicked"), "render: {err}");
    assert!(ok, "render: {err}");
    assert!(dir.join("x.exr").is_file(), "render: no image; {err}");
}
