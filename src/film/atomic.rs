//! Atomic replacement of output files, and the temporary files it leaves when killed.
//!
//! Every file brume writes (film files and images) is first written to a hidden temporary name
//! in the target's folder, `.NAME.PID.tmp.EXT`, synced, then renamed over the target: a reader
//! never sees a half-written file and an existing output is never left damaged. A process killed
//! with SIGKILL (or a power cut) cannot remove its temporary file, which is as large as the
//! output; [`remove_stale`] deletes those of one target whose writing process is gone.

use std::fs::File;
use std::io;
use std::path::{Path, PathBuf};

/// The temporary name `path` is written under by this process. The extension stays last
/// because some writers infer the format from it.
pub fn temp_path(path: &Path) -> PathBuf {
    temp_path_of(path, std::process::id())
}

fn temp_path_of(path: &Path, pid: u32) -> PathBuf {
    let name = file_name(path);
    match path.extension() {
        Some(ext) => path.with_file_name(format!(".{name}.{pid}.tmp.{}", ext.to_string_lossy())),
        None => path.with_file_name(format!(".{name}.{pid}.tmp")),
    }
}

fn file_name(path: &Path) -> String {
    path.file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default()
}

/// Writes `path` through `write(temporary path)`, then syncs and renames it into place. On any
/// error the temporary file is removed and `path` is untouched.
pub fn replace(path: &Path, write: impl FnOnce(&Path) -> io::Result<()>) -> io::Result<()> {
    if path.is_dir() {
        return Err(io::Error::other("is a folder"));
    }
    let tmp = temp_path(path);
    let result = write(&tmp)
        .and_then(|()| File::open(&tmp)?.sync_all())
        .and_then(|()| std::fs::rename(&tmp, path));
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    result?;
    sync_folder(path);
    Ok(())
}

/// Makes the rename durable; a folder that cannot be opened or synced (some file systems) only
/// loses that guarantee, never the file.
fn sync_folder(path: &Path) {
    let dir = path
        .parent()
        .filter(|d| !d.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    if let Ok(d) = File::open(dir) {
        let _ = d.sync_all();
    }
}

/// Checks, before a long render, that `path` can be written the way [`replace`] will write it:
/// creates and removes a temporary file beside it, and refuses a folder.
pub fn probe(path: &Path) -> io::Result<()> {
    if path.is_dir() {
        return Err(io::Error::other("is a folder, not a file"));
    }
    let tmp = temp_path(path);
    File::create(&tmp)?;
    std::fs::remove_file(&tmp)
}

/// Removes the temporary files of `path` left by brume processes that no longer run (killed
/// before they could rename or remove them) and returns their names. Files of a running
/// process, of this process, and anything not named like brume's temporary files are kept.
pub fn remove_stale(path: &Path) -> Vec<PathBuf> {
    let dir = match path.parent().filter(|d| !d.as_os_str().is_empty()) {
        Some(d) => d.to_path_buf(),
        None => PathBuf::from("."),
    };
    let prefix = format!(".{}.", file_name(path));
    let Ok(entries) = std::fs::read_dir(&dir) else {
        return Vec::new();
    };
    let mut removed = Vec::new();
    for entry in entries.flatten() {
        let name = entry.file_name().to_string_lossy().into_owned();
        let Some(pid) = name.strip_prefix(&prefix).and_then(temp_pid) else {
            continue;
        };
        let is_file = entry.file_type().is_ok_and(|t| t.is_file());
        if is_file && pid != std::process::id() && !process_alive(pid) {
            let p = dir.join(&name);
            if std::fs::remove_file(&p).is_ok() {
                removed.push(p);
            }
        }
    }
    removed
}

/// The PID in `PID.tmp` or `PID.tmp.EXT` (the part of a temporary name after `.NAME.`).
fn temp_pid(rest: &str) -> Option<u32> {
    let (pid, tail) = rest.split_once(".tmp")?;
    let tail_ok = tail.is_empty() || (tail.starts_with('.') && !tail[1..].contains('.'));
    let digits = !pid.is_empty() && pid.bytes().all(|b| b.is_ascii_digit());
    if tail_ok && digits {
        pid.parse().ok()
    } else {
        None
    }
}

#[cfg(unix)]
fn process_alive(pid: u32) -> bool {
    use nix::errno::Errno;
    use nix::sys::signal::kill;
    use nix::unistd::Pid;
    let Ok(raw) = i32::try_from(pid) else {
        return false;
    };
    // Signal 0 checks existence only. EPERM means it exists but belongs to another user.
    !matches!(kill(Pid::from_raw(raw), None), Err(Errno::ESRCH))
}

/// Without a portable liveness check, every writer is assumed alive: nothing is removed.
#[cfg(not(unix))]
fn process_alive(_pid: u32) -> bool {
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A PID that is not running: above Linux's largest possible PID (2^22).
    const DEAD: u32 = 4_194_305;

    #[test]
    fn temp_names_parse_back_to_their_pid() {
        let p = Path::new("/x/out.exr");
        let t = temp_path_of(p, 123);
        assert_eq!(t, Path::new("/x/.out.exr.123.tmp.exr"));
        let rest = file_name(&t).strip_prefix(".out.exr.").map(str::to_string);
        assert_eq!(rest.as_deref().and_then(temp_pid), Some(123));
        assert_eq!(temp_pid("77.tmp"), Some(77));
        for bad in ["x.tmp", "77.tmpx", "77.tmp.a.b", ".tmp", "77"] {
            assert_eq!(temp_pid(bad), None, "{bad}");
        }
    }

    #[test]
    fn stale_files_of_dead_writers_are_removed_and_nothing_else() {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("a.brume");
        let dead = temp_path_of(&out, DEAD);
        let legacy = dir.path().join(format!(".a.brume.{DEAD}.tmp"));
        let mine = temp_path(&out);
        let alive = temp_path_of(&out, 1);
        let other = temp_path_of(&dir.path().join("b.brume"), DEAD);
        let user = dir.path().join(".a.brume.notes");
        for p in [&dead, &legacy, &mine, &alive, &other, &user] {
            std::fs::write(p, b"x").unwrap();
        }
        let mut removed = remove_stale(&out);
        removed.sort();
        let mut want = vec![dead.clone(), legacy.clone()];
        want.sort();
        assert_eq!(removed, want);
        for kept in [&mine, &alive, &other, &user] {
            assert!(kept.exists(), "{} removed", kept.display());
        }
    }

    #[test]
    fn replace_leaves_the_target_intact_on_error() {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("a.png");
        std::fs::write(&out, b"old").unwrap();
        let err = replace(&out, |tmp| {
            std::fs::write(tmp, b"half")?;
            Err(io::Error::other("disk full"))
        });
        assert!(err.is_err());
        assert_eq!(std::fs::read(&out).unwrap(), b"old");
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
        replace(&out, |tmp| std::fs::write(tmp, b"new")).unwrap();
        assert_eq!(std::fs::read(&out).unwrap(), b"new");
        assert!(probe(dir.path()).is_err(), "a folder is not an output");
        assert!(probe(&dir.path().join("missing/a.png")).is_err());
        assert!(probe(&out).is_ok());
    }
}
