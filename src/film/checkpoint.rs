//! The film file: a film's exact state on disk, used both as a checkpoint (`--checkpoint`,
//! `--resume`) and as the part file of a distributed render (`--pass-range`, `brume merge`).
//!
//! Layout (little-endian): magic `BRUMEFLM`, format version (u32), seed, scene hash, first
//! pass, passes, dropped (u64 each), width, height, bins (u32), lambda min and max (f64), the
//! spectral grid's equal bins and line count (u32 each) and its lines (f64 each), the length
//! of a UTF-8 JSON text (u32) and the text (the render's identity: scene description and
//! sampling settings, see [`FilmId`]), the numbers of light layers and sensors (u32 each), the
//! length of a JSON text (u32) and the text (the film's extras: its sensors and light layer
//! names, and the automatic settings' choice when there is one); then the sums and sums of squares (i128 each: pixels, light layers, sensors' values
//! per bin, sensors' squared photometric values), and an FNV-1a 64 checksum of everything
//! before it, so a truncated or damaged file is refused. A film with the difference layers of
//! `film::blend` is written as version 4: a u32 1 after the extras' JSON, and the layers'
//! sums after the sensors' (`BlendSums::all`); every other film as version 3, byte for byte as
//! before. Version 2 files (no lines, no extras) are still read.
//!
//! Reading checks the size the header announces against the file's size before reading the
//! data, so a damaged header cannot make brume allocate without bound, and a file can be
//! inspected ([`read_header`]) without loading its sums.

use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::Path;

use crate::spectrum::{MAX_BINS, SpectralGrid};

use super::file_io::OLDEST;
pub use super::file_io::{FilmFileError, VERSION};
use super::file_io::{Hashing, Source, damaged, open};
use super::identity::{self, Fnv};
use super::stored::{self, StoredIdentity};
use super::{BlendSums, Film, FilmExtras, FilmId, LAYERS, atomic};

const MAGIC: &[u8; 8] = b"BRUMEFLM";
/// The version of films without difference layers.
const PLAIN: u32 = 3;
/// Most light layers or sensors accepted on reading.
const MAX_EXTRAS: u32 = 1 << 16;
/// Films larger than this many values (pixels x bins) are refused on reading: 2^32 values are
/// 206 GB of sums, beyond any machine brume runs on.
pub const MAX_VALUES: u64 = 1 << 32;
/// Longest identity text accepted (a scene description is kilobytes).
const MAX_IDENTITY: u32 = 1 << 26;
/// Bytes before the identity text.
const FIXED_HEADER: u64 = 8 + 4 + 5 * 8 + 3 * 4 + 2 * 8 + 4;

/// A film with what identifies the render it belongs to.
#[derive(Clone, Debug, PartialEq)]
pub struct FilmFile {
    pub film: Film,
    pub id: FilmId,
}

/// A film file's header: everything but the sums.
#[derive(Clone, Debug, PartialEq)]
pub struct FilmHeader {
    pub id: FilmId,
    pub width: usize,
    pub height: usize,
    pub grid: SpectralGrid,
    pub first: u64,
    pub passes: u64,
    pub dropped: u64,
    /// Size of the whole file in bytes (what reading it allocates, about).
    pub file_bytes: u64,
}

impl FilmHeader {
    /// The pass index after the last one in the file.
    pub fn end(&self) -> u64 {
        self.first + self.passes
    }
}

/// Writes `film` to `path` atomically (see [`atomic::replace`]).
pub fn write(path: &Path, film: &Film, id: &FilmId) -> Result<(), FilmFileError> {
    let io = |e: serde_json::Error| FilmFileError::Io {
        path: path.to_path_buf(),
        source: e.into(),
    };
    let identity = serde_json::to_vec(&StoredIdentity {
        description: id.description.clone(),
        sampling: id.sampling.clone(),
    })
    .map_err(io)?;
    let extras = stored::extras_json(film).map_err(io)?;
    atomic::replace(path, |tmp| {
        let mut w = Hashing {
            inner: BufWriter::with_capacity(1 << 20, File::create(tmp)?),
            hash: Fnv::default(),
        };
        encode(&mut w, film, id, &identity, &extras)?;
        let sum = w.hash.0;
        w.inner.write_all(&sum.to_le_bytes())?;
        w.inner.flush()?;
        drop(w);
        // The identity read back before the file replaces anything: one that does not survive
        // its JSON text (a float one ulp off) would be refused by resume and merge.
        match read_header(tmp) {
            Ok(h) if h.id == *id => Ok(()),
            Ok(_) => Err(std::io::Error::other(
                "the film's identity does not read back",
            )),
            Err(e) => Err(std::io::Error::other(e)),
        }
    })
    .map_err(|source| FilmFileError::Io {
        path: path.to_path_buf(),
        source,
    })
}

fn encode(
    w: &mut impl Write,
    f: &Film,
    id: &FilmId,
    identity: &[u8],
    extras: &[u8],
) -> std::io::Result<()> {
    let u32_of = |v: usize| u32::try_from(v).map_err(|_| std::io::Error::other("film too large"));
    let lines = f.grid.lines();
    w.write_all(MAGIC)?;
    let version = if f.blend.is_some() { VERSION } else { PLAIN };
    w.write_all(&version.to_le_bytes())?;
    for v in [id.seed, id.scene_hash, f.first, f.passes, f.dropped] {
        w.write_all(&v.to_le_bytes())?;
    }
    for v in [f.width, f.height, f.grid.n] {
        w.write_all(&u32_of(v)?.to_le_bytes())?;
    }
    w.write_all(&f.grid.lambda_min.to_le_bytes())?;
    w.write_all(&f.grid.lambda_max.to_le_bytes())?;
    for v in [f.grid.uniform_bins(), lines.len()] {
        w.write_all(&u32_of(v)?.to_le_bytes())?;
    }
    for l in lines {
        w.write_all(&l.to_le_bytes())?;
    }
    let len = u32::try_from(identity.len()).map_err(|_| std::io::Error::other("identity"))?;
    w.write_all(&len.to_le_bytes())?;
    w.write_all(identity)?;
    for v in [
        f.extras.light_layers.len(),
        f.extras.sensors.len(),
        extras.len(),
    ] {
        w.write_all(&u32_of(v)?.to_le_bytes())?;
    }
    w.write_all(extras)?;
    if f.blend.is_some() {
        w.write_all(&1u32.to_le_bytes())?;
    }
    let sums = [&f.sum, &f.sum_sq, &f.light_sum, &f.sensor_sum, &f.sensor_sq];
    for v in sums.into_iter().flatten() {
        w.write_all(&v.to_le_bytes())?;
    }
    for v in f.blend.iter().flat_map(BlendSums::all) {
        w.write_all(&v.to_le_bytes())?;
    }
    Ok(())
}

/// Fixed fields read before the identity text; the text is parsed once the checksum is known
/// to be right, so a damaged file reports damage rather than a confusing parse error.
struct Raw {
    seed: u64,
    scene_hash: u64,
    first: u64,
    passes: u64,
    dropped: u64,
    width: usize,
    height: usize,
    grid: SpectralGrid,
    identity: Vec<u8>,
    /// Light layers and sensors, and the extras' JSON (empty for version 2).
    lights: usize,
    sensors: usize,
    extras: Vec<u8>,
    /// Whether the film has the difference layers of `film::blend` (version 4).
    blend: bool,
    values: usize,
    file_bytes: u64,
}

impl Raw {
    /// Number of i128 sums after the header.
    fn sums(&self) -> usize {
        let (px, n) = (self.width * self.height, self.grid.n);
        (LAYERS + 1) * self.values
            + self.lights * px * n
            + self.sensors * (n + 1)
            + self.blend_sums()
    }

    /// Number of the difference layers' sums (the last of the file's sums).
    fn blend_sums(&self) -> usize {
        if self.blend {
            BlendSums::len(self.values)
        } else {
            0
        }
    }
}

/// The magic and the format version, refused unless this brume reads it.
fn read_version(src: &mut Source) -> Result<u32, FilmFileError> {
    let path = src.path;
    let head: [u8; 12] = src.bytes().map_err(|_| FilmFileError::Magic {
        path: path.to_path_buf(),
    })?;
    if &head[..8] != MAGIC {
        return Err(FilmFileError::Magic {
            path: path.to_path_buf(),
        });
    }
    let found = u32::from_le_bytes([head[8], head[9], head[10], head[11]]);
    if !(OLDEST..=VERSION).contains(&found) {
        let path = path.to_path_buf();
        return Err(FilmFileError::Version { path, found });
    }
    Ok(found)
}

fn read_raw(src: &mut Source) -> Result<Raw, FilmFileError> {
    let path = src.path;
    let file_bytes = src
        .inner
        .get_ref()
        .metadata()
        .map_err(|e| src.fail(e))?
        .len();
    let found = read_version(src)?;
    let [seed, scene_hash, first, passes, dropped] = [(); 5].map(|()| src.u64());
    let [width, height, n] = [(); 3].map(|()| src.u32());
    let (lambda_min, lambda_max) = (src.u64()?, src.u64()?);
    let (width, height, n) = (width?, height?, n?);
    let (uniform, lines) = if found >= 3 {
        read_lines(src)?
    } else {
        (n, Vec::new())
    };
    let (lambda_min, lambda_max) = (f64::from_bits(lambda_min), f64::from_bits(lambda_max));
    let grid = grid(n, uniform, lambda_min, lambda_max, &lines)
        .ok_or_else(|| damaged(path, "bad spectral grid"))?;
    let identity_len = src.u32()?;
    if identity_len > MAX_IDENTITY {
        return Err(damaged(path, "absurd identity size"));
    }
    let (width, height, n) = (width as u64, height as u64, n as u64);
    let values = (width * height)
        .checked_mul(n)
        .filter(|v| *v <= MAX_VALUES)
        .ok_or_else(|| damaged(path, "absurd film size"))?;
    let line_bytes = if found >= 3 {
        8 + 8 * lines.len() as u64
    } else {
        0
    };
    if FIXED_HEADER + line_bytes + identity_len as u64 > file_bytes {
        return Err(damaged(path, "file size does not match the header"));
    }
    let mut identity = vec![0u8; identity_len as usize];
    src.fill(&mut identity)?;
    let at = FIXED_HEADER + line_bytes + identity_len as u64;
    let (lights, sensors, extras) = if found >= 3 {
        read_extras(src, values, at, file_bytes)?
    } else {
        (0, 0, Vec::new())
    };
    let blend = found >= 4 && read_blend(src)?;
    let extras_bytes = match found {
        4.. => 16 + extras.len() as u64,
        3 => 12 + extras.len() as u64,
        _ => 0,
    };
    let header = FIXED_HEADER + line_bytes + identity_len as u64 + extras_bytes;
    let raw = Raw {
        seed: seed?,
        scene_hash: scene_hash?,
        first: first?,
        passes: passes?,
        dropped: dropped?,
        width: width as usize,
        height: height as usize,
        grid,
        identity,
        lights,
        sensors,
        extras,
        blend,
        values: values as usize,
        file_bytes,
    };
    if header + raw.sums() as u64 * 16 + 8 != file_bytes {
        return Err(damaged(path, "file size does not match the header"));
    }
    Ok(raw)
}

/// A version 4 file's flag of the difference layers (1; a film without them is version 3).
fn read_blend(src: &mut Source) -> Result<bool, FilmFileError> {
    match src.u32()? {
        1 => Ok(true),
        _ => Err(damaged(src.path, "bad difference-layer flag")),
    }
}

/// A version 3 file's extras: the light layer and sensor counts and the extras' JSON, which
/// starts at byte `at` of a file of `file_bytes` bytes whose image has `values` values.
fn read_extras(
    src: &mut Source,
    values: u64,
    at: u64,
    file_bytes: u64,
) -> Result<(usize, usize, Vec<u8>), FilmFileError> {
    let path = src.path;
    let [lights, sensors, len] = [(); 3].map(|()| src.u32());
    let (lights, sensors, len) = (lights?, sensors?, len?);
    if lights > MAX_EXTRAS || sensors > MAX_EXTRAS || len > MAX_IDENTITY {
        return Err(damaged(path, "absurd extras"));
    }
    let layer_values = lights as u64 * values;
    if layer_values > MAX_VALUES {
        return Err(damaged(path, "absurd film size"));
    }
    if at + 12 + len as u64 > file_bytes {
        return Err(damaged(path, "file size does not match the header"));
    }
    let mut extras = vec![0u8; len as usize];
    src.fill(&mut extras)?;
    Ok((lights as usize, sensors as usize, extras))
}

/// A version 3 header's equal-bin count and lines (at most `MAX_BINS` of them, maybe none).
fn read_lines(src: &mut Source) -> Result<(u32, Vec<f64>), FilmFileError> {
    let (uniform, count) = (src.u32()?, src.u32()?);
    if count as usize > MAX_BINS {
        return Err(damaged(src.path, "bad spectral grid"));
    }
    let lines = (0..count)
        .map(|_| src.u64().map(f64::from_bits))
        .collect::<Result<_, _>>()?;
    Ok((uniform, lines))
}

/// The grid a header describes, if it is one brume makes and has `n` bins.
fn grid(n: u32, uniform: u32, min: f64, max: f64, lines: &[f64]) -> Option<SpectralGrid> {
    let uniform = uniform as usize;
    if !((1..=MAX_BINS).contains(&uniform) && min.is_finite() && max.is_finite() && max > min) {
        return None;
    }
    let grid = SpectralGrid::with_lines(uniform, min, max, lines).ok()?;
    (grid.n == n as usize).then_some(grid)
}

fn header(raw: Raw, path: &Path) -> Result<FilmHeader, FilmFileError> {
    let stored: StoredIdentity =
        serde_json::from_slice(&raw.identity).map_err(|_| damaged(path, "unreadable identity"))?;
    let id = FilmId::from_parts(raw.seed, stored.description, stored.sampling);
    if id.scene_hash != raw.scene_hash || identity::hash(&id.description) != raw.scene_hash {
        return Err(damaged(path, "scene hash does not match the description"));
    }
    Ok(FilmHeader {
        id,
        width: raw.width,
        height: raw.height,
        grid: raw.grid,
        first: raw.first,
        passes: raw.passes,
        dropped: raw.dropped,
        file_bytes: raw.file_bytes,
    })
}

/// Reads a film file's header without its sums (cheap whatever the film's size). The checksum
/// covers the whole file and is checked by [`read`] only.
pub fn read_header(path: &Path) -> Result<FilmHeader, FilmFileError> {
    let raw = read_raw(&mut open(path)?)?;
    header(raw, path)
}

/// Reads and checks a film file written by [`write`].
pub fn read(path: &Path) -> Result<FilmFile, FilmFileError> {
    let mut src = open(path)?;
    let raw = read_raw(&mut src)?;
    let values = raw.values;
    let total = raw.sums();
    let mut sums = Vec::with_capacity(total);
    let mut buf = vec![0u8; 1 << 16];
    while sums.len() < total {
        let left = (total - sums.len()) * 16;
        let chunk = &mut buf[..left.min(1 << 16)];
        src.fill(chunk)?;
        sums.extend(
            chunk
                .chunks_exact(16)
                .map(|c| i128::from_le_bytes(c.try_into().unwrap_or_default())),
        );
    }
    let computed = src.hash.0;
    let stored = src.u64()?;
    if computed != stored {
        return Err(damaged(path, "checksum mismatch"));
    }
    let (extras, auto_settings) = if raw.extras.is_empty() {
        (FilmExtras::default(), Vec::new())
    } else {
        stored::read_extras(&raw.extras).map_err(|_| damaged(path, "unreadable extras"))?
    };
    if (extras.light_layers.len(), extras.sensors.len()) != (raw.lights, raw.sensors) {
        return Err(damaged(path, "extras do not match their counts"));
    }
    let (lights, sensors, n) = (raw.lights, raw.sensors, raw.grid.n);
    let blend_sums = sums.split_off(total - raw.blend_sums());
    let blend = raw.blend;
    let h = header(raw, path)?;
    let blend = if blend {
        Some(
            BlendSums::from_all(blend_sums, values)
                .ok_or_else(|| damaged(path, "difference layers"))?,
        )
    } else {
        None
    };
    let total = sums.len();
    let sensor_sq = sums.split_off(total - sensors);
    let sensor_sum = sums.split_off(sums.len() - sensors * n);
    let light_sum = sums.split_off(sums.len() - lights * values);
    let sum_sq = sums.split_off(LAYERS * values);
    let film = Film {
        width: h.width,
        height: h.height,
        grid: h.grid,
        first: h.first,
        passes: h.passes,
        sum: sums,
        sum_sq,
        dropped: h.dropped,
        extras,
        light_sum,
        sensor_sum,
        sensor_sq,
        auto_settings,
        blend,
    };
    Ok(FilmFile { film, id: h.id })
}

#[cfg(test)]
#[path = "checkpoint_tests.rs"]
mod tests;
