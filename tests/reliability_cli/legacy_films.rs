//! Film files written before the radius schedule's keys existed (`integrator.radius_schedule`,
//! `integrator.shrink_after`): such a film rendered every pass at its starting radius. Its
//! passes are today's default render's while today's radius has not started to shrink, so it
//! resumes and merges into it; past that point, or against a render that shrinks sooner, it is
//! refused, naming the key; and asking for the fixed schedule continues it at any length.

use std::path::Path;

use brume::film::{FilmId, checkpoint};

use super::{assert_same, brume, render, stderr, try_render};

/// Rewrites the film file `name` as a brume from before the schedule keys wrote it: the same
/// sums, its recorded description without `integrator.shrink_after`.
fn as_before_the_schedule(dir: &Path, name: &str) {
    let path = dir.join(name);
    let mut f = checkpoint::read(&path).expect("film file");
    let mut desc = f.id.description.clone();
    let removed = desc["integrator"]
        .as_object_mut()
        .and_then(|i| i.remove("shrink_after"));
    assert!(removed.is_some(), "{name} records no shrink_after");
    f.id = FilmId::from_parts(f.id.seed, desc, f.id.sampling.clone());
    checkpoint::write(&path, &f.film, &f.id).expect("rewritten");
}

/// Refused: rc != 0, the message names `key`, and `out` was not written.
fn assert_refused_naming(dir: &Path, extra: &[&str], key: &str, out: &str) {
    let o = try_render(dir, extra);
    let err = stderr(&o);
    assert!(!o.status.success(), "{extra:?} accepted");
    assert!(err.contains(key), "{extra:?}: {err}");
    assert!(!dir.join(out).exists(), "{extra:?} wrote {out}");
}

#[test]
fn films_from_before_the_radius_schedule_continue_while_their_radius_is_todays() {
    let t = tempfile::tempdir().unwrap();
    let d = t.path();
    render(d, &["--passes", "2", "-o", "old.brume"]);
    as_before_the_schedule(d, "old.brume");
    // Today's default keeps the starting radius for 256 passes: the old film's two passes
    // are this render's, and resuming gives a straight run's bytes.
    render(
        d,
        &["--passes", "4", "--resume", "old.brume", "-o", "r.exr"],
    );
    render(d, &["--passes", "4", "-o", "s.exr"]);
    assert_same(d, "r.exr", "s.exr");
    // A render whose radius shrinks from pass 1 would join passes of two radii.
    let shrinks = "integrator.shrink_after=1";
    assert_refused_naming(
        d,
        &[
            "--passes",
            "4",
            "--resume",
            "old.brume",
            "--set",
            shrinks,
            "-o",
            "x.exr",
        ],
        "integrator.shrink_after",
        "x.exr",
    );
    // The fixed schedule is the old render exactly.
    let fixed = "integrator.radius_schedule=\"fixed\"";
    render(
        d,
        &[
            "--passes",
            "4",
            "--resume",
            "old.brume",
            "--set",
            fixed,
            "-o",
            "f.exr",
        ],
    );
    render(d, &["--passes", "4", "--set", fixed, "-o", "g.exr"]);
    assert_same(d, "f.exr", "g.exr");
    // Merged with a part of today's render, in either order: the straight run's bytes.
    render(d, &["--pass-range", "2..4", "-o", "new.brume"]);
    for (a, b, out) in [
        ("old.brume", "new.brume", "m1.exr"),
        ("new.brume", "old.brume", "m2.exr"),
    ] {
        let o = brume(d, &["merge", a, b, "-o", out]);
        assert!(o.status.success(), "merge {a} {b}: {}", stderr(&o));
        assert_same(d, out, "s.exr");
    }
    // A part whose radius shrinks from pass 3 does not merge with the old film: their union
    // reaches pass 3, rendered at another radius under each description.
    render(
        d,
        &[
            "--pass-range",
            "2..4",
            "--set",
            "integrator.shrink_after=3",
            "-o",
            "late.brume",
        ],
    );
    let o = brume(d, &["merge", "old.brume", "late.brume", "-o", "m3.exr"]);
    let err = stderr(&o);
    assert!(!o.status.success(), "merged across the onset");
    assert!(err.contains("integrator.shrink_after"), "{err}");
    assert!(!d.join("m3.exr").exists());
}
