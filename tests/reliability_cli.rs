//! Interrupt, checkpoint/resume, pass-range slices and merge, thread counts: every path to an
//! image of passes 0..N of a seed must give the same bytes. Drives the built `brume` binary.

use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

const SMALL: &[&str] = &[
    "--set",
    "camera.width=24",
    "--set",
    "camera.height=16",
    "--set",
    "film.bins=8",
    "--set",
    "integrator.forward_rays=3000",
];

/// The demo scene without its texture (whose loading dominates a tiny render's time), written
/// into the test's folder.
fn scene(dir: &Path) -> PathBuf {
    let demo = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/fog-cube.toml");
    let text: String = std::fs::read_to_string(demo)
        .unwrap()
        .lines()
        .filter(|l| !l.starts_with("texture"))
        .map(|l| format!("{l}\n"))
        .collect();
    let path = dir.join("fog.toml");
    std::fs::write(&path, text).unwrap();
    path
}

fn brume(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_brume"))
        .current_dir(dir)
        .args(args)
        .output()
        .expect("brume runs")
}

/// `brume render fog-cube SMALL... extra...`, asserting success.
fn render(dir: &Path, extra: &[&str]) {
    let s = scene(dir);
    let mut args = vec!["render", s.to_str().unwrap(), "-q"];
    args.extend_from_slice(SMALL);
    args.extend_from_slice(extra);
    let out = brume(dir, &args);
    assert!(
        out.status.success(),
        "brume {args:?} failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
}

fn bytes(dir: &Path, name: &str) -> Vec<u8> {
    std::fs::read(dir.join(name)).unwrap_or_else(|e| panic!("{name}: {e}"))
}

fn assert_same(dir: &Path, a: &str, b: &str) {
    assert!(bytes(dir, a) == bytes(dir, b), "{a} and {b} differ");
}

#[test]
fn resumed_merged_and_threaded_renders_are_bit_identical() {
    let t = tempfile::tempdir().unwrap();
    let d = t.path();
    render(
        d,
        &[
            "--passes",
            "5",
            "--threads",
            "2",
            "-o",
            "s.exr",
            "-o",
            "s.png",
            "-o",
            "s.brume",
        ],
    );
    for threads in ["1", "8"] {
        let exr = format!("t{threads}.exr");
        render(d, &["--passes", "5", "--threads", threads, "-o", &exr]);
        assert_same(d, "s.exr", &exr);
    }
    // Checkpoint after 2 passes, resume to 5.
    render(
        d,
        &["--passes", "2", "--checkpoint", "c.brume", "-o", "c.exr"],
    );
    render(
        d,
        &[
            "--passes", "5", "--resume", "c.brume", "-o", "r.exr", "-o", "r.png", "-o", "r.brume",
        ],
    );
    assert_same(d, "s.exr", "r.exr");
    assert_same(d, "s.png", "r.png");
    assert_same(d, "s.brume", "r.brume");
    // Three slices with different thread counts, merged out of order.
    render(
        d,
        &["--pass-range", "0..1", "--threads", "1", "-o", "p0.brume"],
    );
    render(
        d,
        &["--pass-range", "1..3", "--threads", "8", "-o", "p1.brume"],
    );
    render(d, &["--pass-range", "3..5", "-o", "p2.brume"]);
    let out = brume(
        d,
        &[
            "merge", "p2.brume", "p0.brume", "p1.brume", "-o", "m.exr", "-o", "m.png", "-q",
        ],
    );
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert_same(d, "s.exr", "m.exr");
    assert_same(d, "s.png", "m.png");
    // A gap is refused.
    let out = brume(d, &["merge", "p0.brume", "p2.brume", "-o", "g.exr"]);
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("not adjacent"));
}

#[test]
fn another_scene_or_seed_is_refused() {
    let t = tempfile::tempdir().unwrap();
    let d = t.path();
    render(
        d,
        &["--passes", "1", "--checkpoint", "c.brume", "-o", "c.exr"],
    );
    let s = scene(d);
    let mut args = vec!["render", s.to_str().unwrap(), "-q"];
    args.extend_from_slice(SMALL);
    args.extend_from_slice(&[
        "--set",
        "media.fog.g=0.3",
        "--resume",
        "c.brume",
        "-o",
        "x.exr",
    ]);
    let out = brume(d, &args);
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("another scene"));
    let mut args = vec!["render", s.to_str().unwrap(), "-q"];
    args.extend_from_slice(SMALL);
    args.extend_from_slice(&["--seed", "9", "--resume", "c.brume", "-o", "x.exr"]);
    let out = brume(d, &args);
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("seed"));
    render(
        d,
        &["--seed", "9", "--pass-range", "1..2", "-o", "p1.brume"],
    );
    let out = brume(d, &["merge", "c.brume", "p1.brume", "-o", "m.exr"]);
    assert!(!out.status.success());
    assert!(!d.join("m.exr").exists());
}

#[test]
fn sigint_keeps_completed_passes_and_they_resume_exactly() {
    let t = tempfile::tempdir().unwrap();
    let d = t.path();
    let s = scene(d);
    let mut args = vec!["render", s.to_str().unwrap()];
    args.extend_from_slice(SMALL);
    args.extend_from_slice(&[
        "--passes",
        "100000",
        "--checkpoint",
        "c.brume",
        "--checkpoint-every",
        "0.0001",
        "-o",
        "i.exr",
        "-o",
        "i.png",
    ]);
    let child = Command::new(env!("CARGO_BIN_EXE_brume"))
        .current_dir(d)
        .args(&args)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    // Wait for the first periodic checkpoint: at least one pass is done.
    let t0 = Instant::now();
    while !d.join("c.brume").exists() {
        assert!(t0.elapsed() < Duration::from_secs(60), "no pass finished");
        std::thread::sleep(Duration::from_millis(20));
    }
    let kill = Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .unwrap();
    assert!(kill.success());
    let out = child.wait_with_output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    assert_eq!(out.status.code(), Some(130), "{err}");
    let kept: u32 = err
        .split("kept ")
        .nth(1)
        .and_then(|r| r.split_whitespace().next())
        .and_then(|n| n.parse().ok())
        .unwrap_or_else(|| panic!("no pass count in: {err}"));
    assert!((1..100000).contains(&kept), "{err}");
    // The outputs are whole images of exactly the kept passes.
    let n = kept.to_string();
    render(d, &["--passes", &n, "-o", "s.exr", "-o", "s.png"]);
    assert_same(d, "i.exr", "s.exr");
    assert_same(d, "i.png", "s.png");
    assert!(image_is_valid_png(&d.join("i.png")));
    // The checkpoint saved on interrupt resumes to the same image as a straight run.
    let more = (kept + 1).to_string();
    render(
        d,
        &["--passes", &more, "--resume", "c.brume", "-o", "r.exr"],
    );
    render(d, &["--passes", &more, "-o", "s2.exr"]);
    assert_same(d, "r.exr", "s2.exr");
    // No temporary files are left behind.
    let leftovers: Vec<_> = std::fs::read_dir(d)
        .unwrap()
        .filter_map(|e| e.ok())
        .filter(|e| e.file_name().to_string_lossy().contains(".tmp"))
        .collect();
    assert!(leftovers.is_empty(), "{leftovers:?}");
}

fn image_is_valid_png(p: &Path) -> bool {
    std::fs::File::open(p)
        .ok()
        .and_then(|f| {
            png::Decoder::new(std::io::BufReader::new(f))
                .read_info()
                .ok()
        })
        .is_some()
}
