//! The film file's reading and writing machinery (`checkpoint`): its errors, and a reader and
//! a writer that hash what passes through them (the file ends with an FNV-1a 64 checksum).

use std::fs::File;
use std::io::{BufReader, Read, Write};
use std::path::{Path, PathBuf};

use super::identity::Fnv;

/// Version 2 added the identity JSON (description and sampling settings), version 3 the
/// spectral lines of the grid and the extras (sensors, light layers), version 4 the
/// difference layers of `film::blend` (only films that have them are written as version 4).
pub const VERSION: u32 = 4;
/// The oldest version read.
pub const OLDEST: u32 = 2;

#[derive(Debug, thiserror::Error)]
pub enum FilmFileError {
    #[error("{path}: {source}")]
    Io {
        path: PathBuf,
        source: std::io::Error,
    },
    #[error("{path}: not a brume film file")]
    Magic { path: PathBuf },
    #[error("{path}: film file version {found}, this brume reads versions {OLDEST} to {VERSION}")]
    Version { path: PathBuf, found: u32 },
    #[error("{path}: damaged or truncated film file ({what})")]
    Damaged { path: PathBuf, what: &'static str },
}

/// Writer that hashes what passes through it.
pub(super) struct Hashing<W> {
    pub inner: W,
    pub hash: Fnv,
}

impl<W: Write> Write for Hashing<W> {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        let n = self.inner.write(buf)?;
        self.hash.update(&buf[..n]);
        Ok(n)
    }
    fn flush(&mut self) -> std::io::Result<()> {
        self.inner.flush()
    }
}

/// Reader that hashes what it reads, with the file's errors mapped to [`FilmFileError`].
pub(super) struct Source<'a> {
    pub inner: BufReader<File>,
    pub hash: Fnv,
    pub path: &'a Path,
}

impl Source<'_> {
    pub fn bytes<const N: usize>(&mut self) -> Result<[u8; N], FilmFileError> {
        let mut b = [0u8; N];
        self.fill(&mut b)?;
        Ok(b)
    }
    pub fn fill(&mut self, b: &mut [u8]) -> Result<(), FilmFileError> {
        self.inner.read_exact(b).map_err(|e| self.fail(e))?;
        self.hash.update(b);
        Ok(())
    }
    pub fn u64(&mut self) -> Result<u64, FilmFileError> {
        self.bytes().map(u64::from_le_bytes)
    }
    pub fn u32(&mut self) -> Result<u32, FilmFileError> {
        self.bytes().map(u32::from_le_bytes)
    }
    pub fn fail(&self, e: std::io::Error) -> FilmFileError {
        if e.kind() == std::io::ErrorKind::UnexpectedEof {
            damaged(self.path, "truncated")
        } else {
            FilmFileError::Io {
                path: self.path.to_path_buf(),
                source: e,
            }
        }
    }
}

pub(super) fn damaged(path: &Path, what: &'static str) -> FilmFileError {
    FilmFileError::Damaged {
        path: path.to_path_buf(),
        what,
    }
}

pub(super) fn open(path: &Path) -> Result<Source<'_>, FilmFileError> {
    let f = File::open(path).map_err(|source| FilmFileError::Io {
        path: path.to_path_buf(),
        source,
    })?;
    Ok(Source {
        inner: BufReader::with_capacity(1 << 20, f),
        hash: Fnv::default(),
        path,
    })
}
