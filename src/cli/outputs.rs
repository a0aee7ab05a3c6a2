//! Output files: checked before any work (distinct, writable, leftovers of killed runs removed),
//! and a safe place for the film when writing them fails after the work is done.

use std::path::{Path, PathBuf};

use brume::film::{Film, FilmId, atomic, checkpoint};

use super::film_files::FILM_EXT;

/// Longest chain of symbolic links followed (Linux's own limit is 40).
const MAX_LINKS: usize = 40;

/// A path as the file system resolves it, so that two spellings of one file compare equal:
/// symbolic links are followed, also to a file that does not exist yet (a link to an output
/// of the same run), and a file that does not exist is resolved through its folder.
fn resolved(p: &Path) -> PathBuf {
    let mut p = p.to_path_buf();
    for _ in 0..MAX_LINKS {
        let Ok(target) = std::fs::read_link(&p) else {
            break;
        };
        p = match p.parent() {
            Some(dir) if target.is_relative() => dir.join(target),
            _ => target,
        };
    }
    if let Ok(c) = p.canonicalize() {
        return c;
    }
    let dir = p.parent().filter(|d| !d.as_os_str().is_empty());
    let dir = dir.unwrap_or(Path::new("."));
    match (dir.canonicalize(), p.file_name()) {
        (Ok(d), Some(name)) => d.join(name),
        _ => p,
    }
}

/// Whether `a` and `b` name one file: the same resolved path, or (existing files) the same
/// file on disk under two names (hard links).
fn same_file(a: &Path, b: &Path) -> bool {
    if resolved(a) == resolved(b) {
        return true;
    }
    #[cfg(unix)]
    {
        use std::os::unix::fs::MetadataExt;
        if let (Ok(x), Ok(y)) = (std::fs::metadata(a), std::fs::metadata(b)) {
            return x.dev() == y.dev() && x.ino() == y.ino();
        }
    }
    false
}

/// Refuses one file named twice (`-o a.exr -o a.exr`, `--checkpoint x -o x`, a link to
/// another output, an image named like another's false-colour map): the second write would
/// replace the first with something else. Each path comes with how the message names it.
pub fn check_distinct(paths: &[(PathBuf, String)]) -> anyhow::Result<()> {
    for (i, (a, a_name)) in paths.iter().enumerate() {
        for (b, b_name) in &paths[..i] {
            anyhow::ensure!(
                !same_file(a, b),
                "{b_name} and {a_name} are the same file: give each output its own name",
            );
        }
    }
    Ok(())
}

/// Paths named by themselves, for [`check_distinct`].
pub fn named(paths: &[PathBuf]) -> Vec<(PathBuf, String)> {
    paths
        .iter()
        .map(|p| (p.clone(), p.display().to_string()))
        .collect()
}

/// Before any work: removes temporary files of these outputs left by killed brume runs (saying
/// so), then checks that each output can be written (its folder exists and takes a new file;
/// it is not a folder).
pub fn prepare(paths: &[PathBuf]) -> anyhow::Result<()> {
    for p in paths {
        for stale in atomic::remove_stale(p) {
            eprintln!(
                "brume: removed {}, left by an interrupted run",
                stale.display()
            );
        }
    }
    for p in paths {
        if let Some(dir) = p.parent().filter(|d| !d.as_os_str().is_empty()) {
            anyhow::ensure!(
                dir.is_dir(),
                "{}: output folder does not exist",
                dir.display()
            );
        }
        atomic::probe(p).map_err(|e| anyhow::anyhow!("{}: cannot write here: {e}", p.display()))?;
    }
    Ok(())
}

/// Writes `film` to the first of `candidates` that takes it and returns that path: the film is
/// all a render leaves, so after an output failed it must land somewhere.
pub fn rescue(film: &Film, id: &FilmId, candidates: &[PathBuf]) -> Option<PathBuf> {
    candidates
        .iter()
        .find(|p| checkpoint::write(p, film, id).is_ok())
        .cloned()
}

/// Where a film goes when its outputs cannot be written: beside the first output, in the
/// working folder, in the system's temporary folder.
pub fn rescue_candidates(first_output: &Path) -> Vec<PathBuf> {
    let stem = first_output
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "render".into());
    let name = format!("{stem}.rescued-{}.{FILM_EXT}", std::process::id());
    vec![
        first_output.with_file_name(&name),
        PathBuf::from(&name),
        std::env::temp_dir().join(&name),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;
    use brume::film::Sampling;
    use brume::spectrum::SpectralGrid;

    #[test]
    fn the_same_file_named_twice_is_refused() {
        let dir = tempfile::tempdir().unwrap();
        let a = dir.path().join("x.brume");
        let b = dir.path().join("sub/../x.brume");
        std::fs::create_dir(dir.path().join("sub")).unwrap();
        assert!(check_distinct(&named(&[a.clone(), b])).is_err());
        let c = dir.path().join("y.brume");
        assert!(check_distinct(&named(&[a, c])).is_ok());
    }

    /// A symbolic link to another output is that output, also before either exists (a
    /// dangling link, relative or absolute, through a chain of links), and so is a hard link.
    #[cfg(unix)]
    #[test]
    fn links_to_another_output_are_the_same_file() {
        use std::os::unix::fs::symlink;
        let dir = tempfile::tempdir().unwrap();
        let d = dir.path();
        let a = d.join("a.exr");
        symlink("a.exr", d.join("rel.exr")).unwrap();
        symlink(&a, d.join("abs.exr")).unwrap();
        symlink("rel.exr", d.join("chain.exr")).unwrap();
        for link in ["rel.exr", "abs.exr", "chain.exr"] {
            let e = check_distinct(&named(&[a.clone(), d.join(link)])).unwrap_err();
            assert!(e.to_string().contains("same file"), "{link}: {e}");
        }
        std::fs::write(&a, b"x").unwrap();
        std::fs::hard_link(&a, d.join("hard.exr")).unwrap();
        assert!(check_distinct(&named(&[a.clone(), d.join("hard.exr")])).is_err());
        // A link to a file that is not an output is not refused.
        symlink("other.exr", d.join("elsewhere.exr")).unwrap();
        assert!(check_distinct(&named(&[a, d.join("elsewhere.exr")])).is_ok());
    }

    #[test]
    fn rescue_falls_back_to_the_next_place() {
        let dir = tempfile::tempdir().unwrap();
        let film = Film::new(1, 1, SpectralGrid::new(2, 400.0, 700.0));
        let sampling = Sampling {
            gather_budget: 1,
            machine_memory: 1,
            version: "t".into(),
        };
        let id = FilmId::new(&1, 0, sampling).unwrap();
        let gone = dir.path().join("gone/out.brume");
        let ok = dir.path().join("ok.brume");
        let saved = rescue(&film, &id, &[gone, ok.clone()]);
        assert_eq!(saved.as_ref(), Some(&ok));
        assert_eq!(checkpoint::read(&ok).unwrap().film, film);
    }
}
