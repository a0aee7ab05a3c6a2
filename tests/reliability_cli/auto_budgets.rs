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
