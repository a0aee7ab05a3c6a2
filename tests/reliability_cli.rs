//! Interrupt, checkpoint/resume, pass-range slices and merge, thread counts: every path to an
//! image of passes 0..N of a seed must give the same bytes; every request that would give
//! another image, or lose work, is refused before rendering. Drives the built `brume` binary.

#[path = "reliability_cli/auto_budgets.rs"]
mod auto_budgets;
#[path = "reliability_cli/interrupts.rs"]
mod interrupts;
#[path = "reliability_cli/legacy_films.rs"]
mod legacy_films;
#[path = "reliability_cli/pipes.rs"]
mod pipes;

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
    let child = signalled(env!("CARGO_BIN_EXE_brume"))
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

/// `brume render fog-cube SMALL... extra...` (not asserting anything).
fn try_render(dir: &Path, extra: &[&str]) -> Output {
    let s = scene(dir);
    let mut args = vec!["render", s.to_str().unwrap(), "-q"];
    args.extend_from_slice(SMALL);
    args.extend_from_slice(extra);
    brume(dir, &args)
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// Refused before rendering: rc != 0, the message says `words`, and no file appeared.
fn assert_refused(dir: &Path, extra: &[&str], words: &[&str]) {
    let before = listing(dir);
    let t0 = Instant::now();
    let out = try_render(dir, extra);
    let err = stderr(&out);
    assert!(!out.status.success(), "{extra:?} accepted: {err}");
    for w in words {
        assert!(err.contains(w), "{extra:?}: {err:?} lacks {w:?}");
    }
    assert_eq!(listing(dir), before, "{extra:?} wrote files");
    // Refused before any pass: well under the time of the 100000 passes asked for.
    assert!(
        t0.elapsed() < Duration::from_secs(20),
        "{extra:?} was not refused at once"
    );
}

fn listing(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .filter_map(|e| e.ok())
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

#[test]
fn bad_requests_are_refused_before_rendering() {
    let t = tempfile::tempdir().unwrap();
    let d = t.path();
    scene(d);
    std::fs::create_dir(d.join("folder.exr")).unwrap();
    std::fs::write(d.join("junk.brume"), b"not a film").unwrap();
    let cases: &[(&[&str], &[&str])] = &[
        (
            &["--passes", "100000", "-o", "folder.exr"],
            &["folder.exr", "folder"],
        ),
        (
            &["--passes", "100000", "-o", "missing/a.exr"],
            &["missing", "does not exist"],
        ),
        (
            &[
                "--passes",
                "100000",
                "--checkpoint",
                "x.brume",
                "-o",
                "x.brume",
            ],
            &["same file"],
        ),
        (
            &["--passes", "100000", "-o", "a.exr", "-o", "./a.exr"],
            &["same file"],
        ),
        (
            &["--passes", "100000", "--checkpoint", "c.exr", "-o", "a.png"],
            &["--checkpoint c.exr", "film file"],
        ),
        (
            &["--pass-range", "0..100000", "-o", "a.exr"],
            &["--pass-range", ".brume"],
        ),
        (
            &["--passes", "100000", "--threads", "100000", "-o", "a.exr"],
            &["--threads 100000", "at most"],
        ),
        (
            &[
                "--pass-range",
                "9007199254740990..9007199254740993",
                "-o",
                "p.brume",
            ],
            &["pass indices end at"],
        ),
        (
            &[
                "--passes",
                "100000",
                "--resume",
                "junk.brume",
                "-o",
                "a.exr",
            ],
            &["junk.brume", "not a brume film file"],
        ),
    ];
    for (extra, words) in cases {
        assert_refused(d, extra, words);
    }
}

#[test]
fn resumes_that_disagree_with_the_checkpoint_are_refused_with_the_command_that_continues_it() {
    let t = tempfile::tempdir().unwrap();
    let d = t.path();
    render(d, &["--pass-range", "2..4", "-o", "part.brume"]);
    render(d, &["--pass-range", "0..3", "-o", "full.brume"]);
    // --passes on a part would silently render 2..(2 + N): refused, naming --pass-range.
    let out = try_render(
        d,
        &["--resume", "part.brume", "--passes", "5", "-o", "x.brume"],
    );
    let err = stderr(&out);
    assert!(!out.status.success(), "{err}");
    assert!(err.contains("part.brume holds passes 2..4"), "{err}");
    let hint = between(&err, "continue it with `", "`");
    assert!(
        hint.contains("--pass-range 2..5") && hint.contains("--set"),
        "{hint}"
    );
    // Following the hint renders exactly passes 2..5, as a straight slice does.
    let out = Command::new("sh")
        .current_dir(d)
        .args(["-c", &hint])
        .output()
        .unwrap();
    assert!(out.status.success(), "{hint}: {}", stderr(&out));
    render(d, &["--pass-range", "2..5", "-o", "straight.brume"]);
    assert_same(d, "x.brume", "straight.brume");
    // Without --passes the hint names a real end (it printed `2..B`, which is refused): as
    // many passes again as the part holds, 2..6, and running it renders exactly those.
    let out = try_render(d, &["--resume", "part.brume", "-o", "z.brume"]);
    let err = stderr(&out);
    assert!(!out.status.success(), "{err}");
    let hint = between(&err, "continue it with `", "`");
    assert!(hint.contains("--pass-range 2..6"), "{hint}");
    let out = Command::new("sh")
        .current_dir(d)
        .args(["-c", &hint])
        .output()
        .unwrap();
    assert!(out.status.success(), "{hint}: {}", stderr(&out));
    render(d, &["--pass-range", "2..6", "-o", "straight6.brume"]);
    assert_same(d, "z.brume", "straight6.brume");
    // A range that ends before what the checkpoint holds would write more than asked.
    let out = try_render(
        d,
        &[
            "--resume",
            "full.brume",
            "--pass-range",
            "0..2",
            "-o",
            "y.brume",
        ],
    );
    let err = stderr(&out);
    assert!(
        !out.status.success() && err.contains("full.brume holds passes 0..3"),
        "{err}"
    );
    assert!(err.contains("--pass-range 0..3"), "{err}");
    let out = try_render(
        d,
        &["--resume", "full.brume", "--passes", "2", "-o", "y.brume"],
    );
    let err = stderr(&out);
    assert!(!out.status.success() && err.contains("at least 3"), "{err}");
    assert!(!d.join("y.brume").exists());
}

fn between(text: &str, start: &str, end: &str) -> String {
    let from = text
        .find(start)
        .unwrap_or_else(|| panic!("no {start:?} in {text}"))
        + start.len();
    let len = text[from..]
        .find(end)
        .unwrap_or_else(|| panic!("no end in {text}"));
    text[from..from + len].to_string()
}

/// Rewrites the sampling record of a film file, as another machine would have written it.
fn rewrite_sampling(path: &Path, f: impl FnOnce(&mut brume::film::Sampling)) {
    let mut file = brume::film::checkpoint::read(path).unwrap();
    f(&mut file.id.sampling);
    brume::film::checkpoint::write(path, &file.film, &file.id).unwrap();
}

#[test]
fn merge_compares_the_gather_budget_and_not_the_machine() {
    let t = tempfile::tempdir().unwrap();
    let d = t.path();
    render(d, &["--passes", "3", "-o", "s.exr"]);
    render(d, &["--pass-range", "0..1", "-o", "p0.brume"]);
    render(d, &["--pass-range", "1..3", "-o", "p1.brume"]);
    // Rendered with the default budget on a machine with another amount of memory: the
    // budget it used is recorded, and it is the same, so the parts merge bit for bit.
    rewrite_sampling(&d.join("p1.brume"), |s| {
        s.machine_memory = s.machine_memory / 2 + 1
    });
    let out = brume(d, &["merge", "p0.brume", "p1.brume", "-o", "m.exr", "-q"]);
    assert!(out.status.success(), "{}", stderr(&out));
    assert_same(d, "s.exr", "m.exr");
    // A part whose budget followed its machine's memory (another tiling) is refused.
    rewrite_sampling(&d.join("p1.brume"), |s| s.gather_budget /= 2);
    let out = brume(d, &["merge", "p0.brume", "p1.brume", "-o", "m2.exr"]);
    let err = stderr(&out);
    assert!(
        !out.status.success() && err.contains("gather memory budget"),
        "{err}"
    );
    assert!(
        err.contains("integrator.max_gather_bytes") && err.contains("p1.brume"),
        "{err}"
    );
    // Parts rendered with different budgets are refused, and so is resuming across them.
    render(
        d,
        &[
            "--pass-range",
            "1..3",
            "--set",
            "integrator.max_gather_bytes=60000",
            "-o",
            "q1.brume",
        ],
    );
    let out = brume(d, &["merge", "p0.brume", "q1.brume", "-o", "m3.exr"]);
    let err = stderr(&out);
    assert!(
        !out.status.success() && err.contains("gather memory budget 60000 bytes"),
        "{err}"
    );
    let out = try_render(
        d,
        &[
            "--resume",
            "p0.brume",
            "--pass-range",
            "0..3",
            "-o",
            "r.brume",
            "--set",
            "integrator.max_gather_bytes=60000",
        ],
    );
    assert!(
        !out.status.success() && stderr(&out).contains("gather memory budget"),
        "{}",
        stderr(&out)
    );
    for f in ["m2.exr", "m3.exr", "r.brume"] {
        assert!(!d.join(f).exists(), "{f} written");
    }
}

#[test]
fn leftover_temporary_files_of_killed_runs_are_removed() {
    let t = tempfile::tempdir().unwrap();
    let d = t.path();
    // PIDs above Linux's maximum (2^22) are never running; PID 1 always is.
    let dead = [
        "a.exr.4194305.tmp.exr",
        "c.brume.4194306.tmp",
        "c.brume.4194307.tmp.brume",
    ];
    for name in dead.iter().chain(&["c.brume.1.tmp.brume"]) {
        std::fs::write(d.join(format!(".{name}")), vec![0u8; 1000]).unwrap();
    }
    let out = try_render(
        d,
        &["--passes", "1", "-o", "a.exr", "--checkpoint", "c.brume"],
    );
    assert!(out.status.success(), "{}", stderr(&out));
    let err = stderr(&out);
    for name in dead {
        assert!(!d.join(format!(".{name}")).exists(), "{name} kept");
        assert!(err.contains(name), "{err} does not name {name}");
    }
    assert!(
        d.join(".c.brume.1.tmp.brume").exists(),
        "a running writer's file was removed"
    );
}

/// Slow passes (a few hundred milliseconds), so that a test can act between them.
const SLOW: &[&str] = &["--set", "integrator.forward_rays=400000"];

/// `program` with SIGINT, SIGTERM and SIGHUP at their defaults, for a test that sends one of
/// them: brume keeps a signal it was started with ignored (`cli::render::interrupt`), and a
/// test suite run as a script's background job (`cmd &`) or under nohup passes SIGINT or
/// SIGHUP ignored to every child.
fn signalled(program: &str) -> Command {
    use std::os::unix::process::CommandExt;
    let mut cmd = Command::new(program);
    // SAFETY: between fork and exec the child only calls signal(2), which is
    // async-signal-safe, with SIG_DFL (no handler function).
    unsafe {
        cmd.pre_exec(|| {
            use nix::sys::signal::{SigHandler, Signal, signal};
            for s in [Signal::SIGINT, Signal::SIGTERM, Signal::SIGHUP] {
                signal(s, SigHandler::SigDfl).map_err(std::io::Error::from)?;
            }
            Ok(())
        });
    }
    cmd
}

fn spawn_render(dir: &Path, extra: &[&str]) -> std::process::Child {
    let s = scene(dir);
    let mut args = vec!["render".to_string(), s.to_str().unwrap().to_string()];
    args.extend(SMALL.iter().chain(SLOW).chain(extra).map(|a| a.to_string()));
    signalled(env!("CARGO_BIN_EXE_brume"))
        .current_dir(dir)
        .args(&args)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap()
}

fn wait_for(path: &Path) {
    let t0 = Instant::now();
    while !path.exists() {
        assert!(
            t0.elapsed() < Duration::from_secs(120),
            "{} never appeared",
            path.display()
        );
        std::thread::sleep(Duration::from_millis(5));
    }
}

#[test]
fn sigterm_saves_the_passes_and_the_printed_command_continues_the_render() {
    let t = tempfile::tempdir().unwrap();
    let d = t.path();
    let extra = [
        "--passes",
        "6",
        "--checkpoint",
        "c.brume",
        "--checkpoint-every",
        "0.00001",
        "-o",
        "i.exr",
    ];
    let child = spawn_render(d, &extra);
    wait_for(&d.join("c.brume"));
    let kill = Command::new("kill")
        .args(["-TERM", &child.id().to_string()])
        .status()
        .unwrap();
    assert!(kill.success());
    let out = child.wait_with_output().unwrap();
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(130), "{err}");
    // The hint is the original command (its --set options included) resuming the checkpoint.
    let hint = between(&err, "continue with `", "`");
    assert!(
        hint.contains("--set") && hint.contains("--resume c.brume"),
        "{hint}"
    );
    let out = Command::new("sh")
        .current_dir(d)
        .args(["-c", &hint])
        .output()
        .unwrap();
    assert!(out.status.success(), "{hint}: {}", stderr(&out));
    let mut straight: Vec<&str> = SLOW.to_vec();
    straight.extend(["--passes", "6", "-o", "s.exr"]);
    render(d, &straight);
    assert_same(d, "i.exr", "s.exr");
}

#[test]
fn a_failed_write_after_rendering_saves_the_film_and_says_where() {
    let t = tempfile::tempdir().unwrap();
    let d = t.path();
    std::fs::create_dir(d.join("gone")).unwrap();
    let extra = [
        "--passes",
        "4",
        "-o",
        "gone/out.exr",
        "--checkpoint",
        "gone/c.brume",
        "--checkpoint-every",
        "0.00001",
    ];
    let child = spawn_render(d, &extra);
    // Once the first pass is saved the outputs were checked: take their folder away.
    wait_for(&d.join("gone/c.brume"));
    while d.join("gone").exists() {
        let _ = std::fs::remove_dir_all(d.join("gone"));
    }
    let out = child.wait_with_output().unwrap();
    let err = stderr(&out);
    assert!(!out.status.success(), "{err}");
    assert!(err.contains("gone/out.exr"), "{err}");
    let saved = between(&err, "is saved in ", " ");
    assert!(err.contains("passes 0..4"), "{err}");
    // The saved film gives the image asked for, exactly.
    let out = brume(d, &["merge", &saved, "-o", "m.exr", "-q"]);
    assert!(out.status.success(), "{}", stderr(&out));
    let mut straight: Vec<&str> = SLOW.to_vec();
    straight.extend(["--passes", "4", "-o", "s.exr"]);
    render(d, &straight);
    assert_same(d, "m.exr", "s.exr");
}
