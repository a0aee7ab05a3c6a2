//! The film file: a film's exact state on disk, used both as a checkpoint (`--checkpoint`,
//! `--resume`) and as the part file of a distributed render (`--pass-range`, `brume merge`).
//!
//! Layout (little-endian): magic `BRUMEFLM`, format version (u32), seed, scene hash, first
//! pass, passes, dropped (u64 each), width, height, bins (u32), lambda min and max (f64), the
//! length of a UTF-8 metadata text (u32) and the text, the sums and sums of squares (i128 each),
//! and an FNV-1a 64 checksum of everything before it, so a truncated or damaged file is refused.

use std::io::{BufWriter, Read, Write};
use std::path::{Path, PathBuf};

use crate::spectrum::SpectralGrid;

use super::{Film, LAYERS};

const MAGIC: &[u8; 8] = b"BRUMEFLM";
pub const VERSION: u32 = 1;
/// Films larger than this many values are refused on reading (a damaged header must not make
/// brume allocate without bound).
const MAX_VALUES: u64 = 1 << 34;

/// A film with what identifies the render it belongs to.
#[derive(Clone, Debug, PartialEq)]
pub struct FilmFile {
    pub film: Film,
    pub id: FilmId,
}

/// What identifies the render a film belongs to.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct FilmId {
    pub seed: u64,
    /// Hash of the scene description (see `scene::identity_hash`): parts and checkpoints of
    /// another scene are refused.
    pub scene_hash: u64,
    /// Free text for the caller (brume stores the scene's output settings as JSON).
    pub meta: String,
}

#[derive(Debug, thiserror::Error)]
pub enum FilmFileError {
    #[error("{path}: {source}")]
    Io {
        path: PathBuf,
        source: std::io::Error,
    },
    #[error("{path}: not a brume film file")]
    Magic { path: PathBuf },
    #[error("{path}: film file version {found}, this brume reads version {VERSION}")]
    Version { path: PathBuf, found: u32 },
    #[error("{path}: damaged or truncated film file ({what})")]
    Damaged { path: PathBuf, what: &'static str },
}

/// FNV-1a 64: a small, stable hash (the same on every machine and build).
#[derive(Clone, Copy, Debug)]
pub struct Fnv(pub u64);

impl Default for Fnv {
    fn default() -> Self {
        Fnv(0xcbf2_9ce4_8422_2325)
    }
}

impl Fnv {
    pub fn update(&mut self, bytes: &[u8]) {
        for b in bytes {
            self.0 ^= *b as u64;
            self.0 = self.0.wrapping_mul(0x0000_0100_0000_01b3);
        }
    }
}

/// Writer that hashes what passes through it.
struct Hashing<W> {
    inner: W,
    hash: Fnv,
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

/// Writes `film` to `path` atomically (temporary name in the same folder, synced, renamed).
pub fn write(path: &Path, film: &Film, id: &FilmId) -> Result<(), FilmFileError> {
    let io = |source| FilmFileError::Io {
        path: path.to_path_buf(),
        source,
    };
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let tmp = path.with_file_name(format!(".{name}.{}.tmp", std::process::id()));
    let result = (|| -> std::io::Result<()> {
        let f = std::fs::File::create(&tmp)?;
        let mut w = Hashing {
            inner: BufWriter::with_capacity(1 << 20, f),
            hash: Fnv::default(),
        };
        encode(&mut w, film, id)?;
        let sum = w.hash.0;
        w.inner.write_all(&sum.to_le_bytes())?;
        let f = w.inner.into_inner().map_err(|e| e.into_error())?;
        f.sync_all()
    })();
    if let Err(e) = result.and_then(|_| std::fs::rename(&tmp, path)) {
        let _ = std::fs::remove_file(&tmp);
        return Err(io(e));
    }
    Ok(())
}

fn encode(w: &mut impl Write, f: &Film, file: &FilmId) -> std::io::Result<()> {
    w.write_all(MAGIC)?;
    w.write_all(&VERSION.to_le_bytes())?;
    for v in [file.seed, file.scene_hash, f.first, f.passes, f.dropped] {
        w.write_all(&v.to_le_bytes())?;
    }
    for v in [f.width, f.height, f.grid.n] {
        w.write_all(&(v as u32).to_le_bytes())?;
    }
    w.write_all(&f.grid.lambda_min.to_le_bytes())?;
    w.write_all(&f.grid.lambda_max.to_le_bytes())?;
    w.write_all(&(file.meta.len() as u32).to_le_bytes())?;
    w.write_all(file.meta.as_bytes())?;
    for v in f.sum.iter().chain(&f.sum_sq) {
        w.write_all(&v.to_le_bytes())?;
    }
    Ok(())
}

/// Reads and checks a film file written by `write`.
pub fn read(path: &Path) -> Result<FilmFile, FilmFileError> {
    let io = |source| FilmFileError::Io {
        path: path.to_path_buf(),
        source,
    };
    let damaged = |what| FilmFileError::Damaged {
        path: path.to_path_buf(),
        what,
    };
    let mut bytes = Vec::new();
    std::fs::File::open(path)
        .and_then(|mut f| f.read_to_end(&mut bytes))
        .map_err(io)?;
    if bytes.len() < 12 || &bytes[..8] != MAGIC {
        return Err(FilmFileError::Magic {
            path: path.to_path_buf(),
        });
    }
    let version = u32::from_le_bytes(bytes[8..12].try_into().unwrap_or_default());
    if version != VERSION {
        return Err(FilmFileError::Version {
            path: path.to_path_buf(),
            found: version,
        });
    }
    if bytes.len() < 20 {
        return Err(damaged("too short"));
    }
    let (body, tail) = bytes.split_at(bytes.len() - 8);
    let mut h = Fnv::default();
    h.update(body);
    if h.0.to_le_bytes() != tail {
        return Err(damaged("checksum mismatch"));
    }
    let mut r = Reader { b: body, at: 12 };
    let short = || damaged("header too short");
    let seed = r.u64().ok_or_else(short)?;
    let scene_hash = r.u64().ok_or_else(short)?;
    let first = r.u64().ok_or_else(short)?;
    let passes = r.u64().ok_or_else(short)?;
    let dropped = r.u64().ok_or_else(short)?;
    let width = r.u32().ok_or_else(short)? as usize;
    let height = r.u32().ok_or_else(short)? as usize;
    let n = r.u32().ok_or_else(short)? as usize;
    let lambda_min = f64::from_bits(r.u64().ok_or_else(short)?);
    let lambda_max = f64::from_bits(r.u64().ok_or_else(short)?);
    let meta_len = r.u32().ok_or_else(short)? as usize;
    let meta = r.take(meta_len).ok_or_else(short)?;
    let meta = String::from_utf8(meta.to_vec()).map_err(|_| damaged("metadata is not UTF-8"))?;
    let px = (width as u64)
        .checked_mul(height as u64)
        .and_then(|v| v.checked_mul(n as u64))
        .filter(|v| *v <= MAX_VALUES)
        .ok_or_else(|| damaged("absurd film size"))? as usize;
    if r.b.len() - r.at != (LAYERS + 1) * px * 16 {
        return Err(damaged("data size does not match the header"));
    }
    let mut values = r.b[r.at..]
        .chunks_exact(16)
        .map(|c| i128::from_le_bytes(c.try_into().unwrap_or_default()));
    let sum: Vec<i128> = values.by_ref().take(LAYERS * px).collect();
    let sum_sq: Vec<i128> = values.collect();
    let film = Film {
        width,
        height,
        grid: SpectralGrid {
            n,
            lambda_min,
            lambda_max,
        },
        first,
        passes,
        sum,
        sum_sq,
        dropped,
    };
    Ok(FilmFile {
        film,
        id: FilmId {
            seed,
            scene_hash,
            meta,
        },
    })
}

struct Reader<'a> {
    b: &'a [u8],
    at: usize,
}

impl<'a> Reader<'a> {
    fn take(&mut self, n: usize) -> Option<&'a [u8]> {
        let s = self.b.get(self.at..self.at.checked_add(n)?)?;
        self.at += n;
        Some(s)
    }
    fn u64(&mut self) -> Option<u64> {
        Some(u64::from_le_bytes(self.take(8)?.try_into().ok()?))
    }
    fn u32(&mut self) -> Option<u32> {
        Some(u32::from_le_bytes(self.take(4)?.try_into().ok()?))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::film::PassBuffer;

    fn sample() -> FilmFile {
        let grid = SpectralGrid {
            n: 3,
            lambda_min: 380.0,
            lambda_max: 730.0,
        };
        let mut film = Film::starting_at(2, 2, grid, 7);
        let mut b = PassBuffer::new(4, 3);
        b.data
            .iter_mut()
            .enumerate()
            .for_each(|(i, v)| *v = i as f32 * 0.37 - 3.0);
        film.add_pass(&b);
        film.add_pass(&b);
        film.dropped = 5;
        FilmFile {
            film,
            id: FilmId {
                seed: 42,
                scene_hash: 0xdead_beef,
                meta: "{\"x\":1}".into(),
            },
        }
    }

    #[test]
    fn round_trip_is_exact() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("a.brume");
        let f = sample();
        write(&p, &f.film, &f.id).unwrap();
        assert_eq!(read(&p).unwrap(), f);
    }

    #[test]
    fn damaged_files_are_refused_not_panicked_on() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("a.brume");
        let f = sample();
        write(&p, &f.film, &f.id).unwrap();
        let good = std::fs::read(&p).unwrap();
        // Every truncation and a flipped byte at every position is an error, never a panic.
        for cut in 0..good.len() {
            std::fs::write(&p, &good[..cut]).unwrap();
            assert!(read(&p).is_err(), "truncated at {cut}");
        }
        for i in 0..good.len() {
            let mut bad = good.clone();
            bad[i] ^= 0x10;
            std::fs::write(&p, &bad).unwrap();
            assert!(read(&p).is_err(), "flipped byte {i}");
        }
    }
}
