//! With automatic budgets (brume's defaults) a render's images carry the choice its pilots made
//! (the EXR attribute `brumeAutoSettings`), and every path to passes 0..N gives the same bytes:
//! a straight run, a resumed checkpoint and merged parts. Parts keep the choice in their film
//! files; a part written before they did (no choice in its extras) still merges.

use std::path::Path;

use brume::film::checkpoint;

use super::{assert_same, brume, bytes, render, stderr};

const AUTO: &[&str] = &[
    "--set",
    "integrator.forward_rays=\"auto\"",
    "--set",
    "integrator.camera_samples=\"auto\"",
];

fn render_auto(dir: &Path, extra: &[&str]) {
    let args: Vec<&str> = AUTO.iter().chain(extra).copied().collect();
    render(dir, &args);
}

fn merge(dir: &Path, args: &[&str]) {
    let args: Vec<&str> = ["merge"].iter().chain(args).copied().collect();
    let o = brume(dir, &args);
    assert!(o.status.success(), "{args:?}: {}", stderr(&o));
}

#[test]
fn automatic_budgets_give_the_same_bytes_by_every_path() {
    let t = tempfile::tempdir().unwrap();
    let d = t.path();
    render_auto(d, &["--passes", "3", "-o", "s.exr", "-o", "s.brume"]);
    let s = bytes(d, "s.exr");
    assert!(
        s.windows(17).any(|w| w == b"brumeAutoSettings"),
        "the straight run's EXR lacks the choice"
    );
    let film = checkpoint::read(&d.join("s.brume")).unwrap().film;
    assert!(
        film.auto_settings
            .iter()
            .any(|l| l.contains("camera_samples")),
        "{:?}",
        film.auto_settings
    );
    render_auto(d, &["--passes", "1", "-o", "c.brume"]);
    render_auto(d, &["--passes", "3", "--resume", "c.brume", "-o", "r.exr"]);
    assert_same(d, "s.exr", "r.exr");
    render_auto(d, &["--pass-range", "0..1", "-o", "p0.brume"]);
    render_auto(d, &["--pass-range", "1..3", "-o", "p1.brume"]);
    merge(d, &["p1.brume", "p0.brume", "-o", "m.exr", "-q"]);
    assert_same(d, "s.exr", "m.exr");
    // A first part from before films kept the choice: the other part's choice is used.
    let path = d.join("p0.brume");
    let mut old = checkpoint::read(&path).unwrap();
    old.film.auto_settings.clear();
    checkpoint::write(&path, &old.film, &old.id).unwrap();
    merge(d, &["p0.brume", "p1.brume", "-o", "o.exr", "-q"]);
    assert_same(d, "s.exr", "o.exr");
}

/// Rewrites the choice recorded in film file `name` as another brume's pilots might have made
/// it: one more camera path per pixel than this brume's.
fn as_another_brumes_choice(dir: &Path, name: &str) -> String {
    let path = dir.join(name);
    let mut f = checkpoint::read(&path).unwrap();
    let first = f.film.auto_settings.first().cloned().expect("a choice");
    let (head, paths) = first
        .rsplit_once("camera_samples = ")
        .expect("the choice names its camera paths");
    let other: u32 = paths.trim().parse::<u32>().expect("a number") + 1;
    f.film.auto_settings[0] = format!("{head}camera_samples = {other}");
    checkpoint::write(&path, &f.film, &f.id).unwrap();
    format!("camera_samples = {other}")
}

/// A film (or a part) whose passes another brume's pilots configured differently is refused,
/// naming both choices, and nothing is written: its passes and this brume's would make one
/// image of two configurations under one recorded choice.
#[test]
fn a_film_with_another_automatic_choice_is_refused() {
    let t = tempfile::tempdir().unwrap();
    let d = t.path();
    render_auto(d, &["--passes", "1", "-o", "c.brume"]);
    let theirs = as_another_brumes_choice(d, "c.brume");
    let s = super::scene(d);
    let mut args = vec!["render", s.to_str().unwrap(), "-q"];
    args.extend_from_slice(super::SMALL);
    args.extend_from_slice(AUTO);
    args.extend_from_slice(&["--passes", "3", "--resume", "c.brume", "-o", "r.exr"]);
    let o = brume(d, &args);
    let err = stderr(&o);
    assert!(!o.status.success(), "resumed: {err}");
    assert!(
        err.contains(&theirs) && err.contains("automatic settings"),
        "{err}"
    );
    assert!(!d.join("r.exr").exists(), "an image was written");
    // Merging: two parts of one render whose recorded choices differ.
    render_auto(d, &["--pass-range", "0..1", "-o", "p0.brume"]);
    render_auto(d, &["--pass-range", "1..2", "-o", "p1.brume"]);
    as_another_brumes_choice(d, "p1.brume");
    let o = brume(d, &["merge", "p0.brume", "p1.brume", "-o", "m.exr", "-q"]);
    let err = stderr(&o);
    assert!(!o.status.success(), "merged: {err}");
    assert!(
        err.contains(&theirs) && err.contains("automatic settings differ"),
        "{err}"
    );
    assert!(!d.join("m.exr").exists(), "a merged image was written");
}
