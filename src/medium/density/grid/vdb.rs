//! OpenVDB density grids (Blender, Houdini, EmberGen) through the `vdb-rs` crate: one float
//! grid, densified over the bounding box of its active voxels.
//!
//! OpenVDB index coordinates are voxel centres, so the index box `[i0, i1]` becomes
//! `i1 - i0 + 1` samples per axis filling `[i0 - 0.5, i1 + 0.5]` mapped to world space, which
//! is GridData's convention. vdb-rs 0.6 drops the root node's background value and root tiles,
//! and panics on transforms it does not know, so [`root_header`] reads those few root fields
//! itself, at the offset that vdb-rs's own parse of the grid's metadata gives, before vdb-rs
//! reads the tree.

use std::fs::File;
use std::io::{self, BufReader, Read, Seek, SeekFrom};
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::Path;

use glam::Vec3;
use vdb_rs::{Grid, GridDescriptor, Map, Metadata, MetadataValue, ParseError, VdbReader};

use super::data::{GridData, GridFileError};

/// OpenVDB's magic number, `0x56444220` ("VDB " little-endian) as an int64.
const MAGIC: [u8; 8] = [0x20, 0x42, 0x44, 0x56, 0, 0, 0, 0];
/// File format versions read: 222 (node mask compression) to 224 (multi-pass I/O, current).
const VERSIONS: std::ops::RangeInclusive<u32> = 222..=224;
/// Index coordinates arrive from vdb-rs's iterator as f32, exact below this magnitude.
const MAX_COORD: i64 = 1 << 24;
/// An inclusive box of index coordinates, `(lo, hi)`.
type IndexBox = ([i64; 3], [i64; 3]);

/// Reads grid `grid` of the OpenVDB file `path` as dense samples, refusing more than `budget`
/// bytes of them.
pub fn read(path: &Path, grid: &str, budget: u64) -> Result<GridData, GridFileError> {
    let mut reader = open(path)?;
    let gd = descriptor(path, &reader, grid)?;
    let background = root_header(path, &gd)?;
    let vdb = guarded(path, || reader.read_grid::<f32>(grid))?;
    let (lo, hi) = scan(path, grid, &vdb, background)?;
    let res = [0, 1, 2].map(|a| (hi[a] - lo[a] + 1) as u128);
    let bytes = 4 * res.iter().product::<u128>();
    if bytes > u128::from(budget) {
        let (file, bytes) = (path.into(), u64::try_from(bytes).unwrap_or(u64::MAX));
        return Err(GridFileError::TooLarge {
            file,
            bytes,
            budget,
        });
    }
    let (scale, offset) = match &vdb.transform {
        Map::UniformScaleMap { scale_values, .. } => (scale_values, None),
        Map::ScaleTranslateMap {
            scale_values,
            translation,
            ..
        } => (scale_values, Some(translation)),
    };
    let (scale, offset) = (scale.to_array(), offset.map_or([0.0; 3], |t| t.to_array()));
    if scale.iter().any(|s| !s.is_finite() || *s == 0.0) {
        let message = format!("grid {grid:?} has the voxel size {scale:?}");
        return Err(format_err(path, message));
    }
    let res = res.map(|r| r as usize);
    let values = densify(&vdb, (lo, hi), res, scale, background);
    let ends = [0, 1, 2].map(|a| {
        let world = |i: f64| (i * scale[a] + offset[a]) as f32;
        let (p, q) = (world(lo[a] as f64 - 0.5), world(hi[a] as f64 + 0.5));
        (p.min(q), p.max(q))
    });
    let bounds = Some((Vec3::from(ends.map(|e| e.0)), Vec3::from(ends.map(|e| e.1))));
    Ok(GridData {
        res,
        values,
        bounds,
    })
}

fn format_err(path: &Path, message: String) -> GridFileError {
    GridFileError::Format {
        file: path.into(),
        message,
    }
}

/// Opens `path` as an OpenVDB file, checking the magic number and version before vdb-rs reads
/// the header (vdb-rs 0.6 checks neither and panics or allocates at random on other files).
fn open(path: &Path) -> Result<VdbReader<BufReader<File>>, GridFileError> {
    let read_err = |e: io::Error| GridFileError::Read {
        file: path.into(),
        message: e.to_string(),
    };
    let mut file = BufReader::new(File::open(path).map_err(read_err)?);
    let mut head = [0u8; 12];
    if let Err(e) = file.read_exact(&mut head) {
        return Err(parse_error(path, ParseError::IoError(e)));
    }
    if head[..8] != MAGIC {
        let message = "no OpenVDB magic number (not a .vdb file)";
        return Err(format_err(path, message.into()));
    }
    let version = u32::from_le_bytes([head[8], head[9], head[10], head[11]]);
    if !VERSIONS.contains(&version) {
        let message = format!("OpenVDB file format version {version} (reads {VERSIONS:?})");
        return Err(format_err(path, message));
    }
    file.rewind().map_err(read_err)?;
    guarded(path, || VdbReader::new(file))
}

/// The grid's descriptor, if the file has a float grid of that name at full precision.
fn descriptor<R: Read + Seek>(
    path: &Path,
    reader: &VdbReader<R>,
    grid: &str,
) -> Result<GridDescriptor, GridFileError> {
    let Some(gd) = reader.grid_descriptors.get(grid) else {
        let mut names = reader.available_grids();
        names.sort();
        let available = match names.is_empty() {
            true => "no grids".to_string(),
            false => format!("the grids {}", names.join(", ")),
        };
        let (file, name) = (path.into(), grid.into());
        return Err(GridFileError::NoSuchGrid {
            file,
            name,
            available,
        });
    };
    let float = ["Tree_float_5_4_3", "Tree_float_5_4_3_HalfFloat"].contains(&gd.grid_type.as_str());
    let message = if !float {
        format!("grid {grid:?} is a {}, not a float grid", gd.grid_type)
    } else if !gd.instance_parent.is_empty() {
        let parent = &gd.instance_parent;
        format!(
            "grid {grid:?} is an instance of grid {parent:?} (instanced grids are not supported)"
        )
    } else if gd.meta_data.is_half_float() {
        // vdb-rs expects a size before every node's values; OpenVDB writes none for a node
        // without active values when it saves half floats.
        format!(
            "grid {grid:?} is saved as half floats, which vdb-rs 0.6 misreads; save it at full \
             float precision"
        )
    } else {
        return Ok(gd.clone());
    };
    Err(format_err(path, message))
}

/// Runs a vdb-rs read, turning its errors and its panics (vdb-rs 0.6 panics on some malformed
/// files) into this reader's errors.
fn guarded<T>(path: &Path, f: impl FnOnce() -> Result<T, ParseError>) -> Result<T, GridFileError> {
    catch_unwind(AssertUnwindSafe(f))
        .unwrap_or_else(|panic| {
            let why = (panic.downcast_ref::<String>().map(String::as_str))
                .or_else(|| panic.downcast_ref::<&str>().copied())
                .unwrap_or("no message");
            let message = format!("vdb-rs cannot read it ({why})");
            Err(ParseError::InvalidGridName(message))
        })
        .map_err(|e| parse_error(path, e))
}

fn parse_error(path: &Path, e: ParseError) -> GridFileError {
    match e {
        ParseError::IoError(e) if e.kind() == io::ErrorKind::UnexpectedEof => {
            format_err(path, "the file ends early (truncated?)".into())
        }
        ParseError::IoError(e) => GridFileError::Read {
            file: path.into(),
            message: e.to_string(),
        },
        ParseError::InvalidGridName(message) => format_err(path, message),
        e => format_err(path, e.to_string()),
    }
}

/// The root node's background value, after checking the grid's transform (vdb-rs 0.6 reads
/// only scale and scale-translate maps) and that no root tile is active (vdb-rs drops them).
/// The grid's stream is: compression flags (u32), metadata (as vdb-rs parsed it into `gd`),
/// transform (name, then 5 or 6 f64 triples), buffer count (u32, 1), background (f32, also
/// when saved as half), root tile count, child count, root tiles (coord, value, active byte).
fn root_header(path: &Path, gd: &GridDescriptor) -> Result<f32, GridFileError> {
    let read = |e: io::Error| parse_error(path, ParseError::IoError(e));
    let mut file = BufReader::new(File::open(path).map_err(read)?);
    let start = gd.grid_pos + 4 + metadata_bytes(&gd.meta_data);
    file.seek(SeekFrom::Start(start)).map_err(read)?;
    let mut name = vec![0u8; read_u32(&mut file).map_err(read)?.min(64) as usize];
    file.read_exact(&mut name).map_err(read)?;
    let name = String::from_utf8_lossy(&name);
    let grid = &gd.name;
    let triples = match name.as_ref() {
        "UniformScaleMap" => 5,
        "ScaleTranslateMap" | "UniformScaleTranslateMap" => 6,
        "AffineMap" | "UnitaryMap" => 0,
        _ => -1,
    };
    if triples <= 0 {
        let message = match triples {
            0 => format!(
                "grid {grid:?} has a rotated or sheared transform ({name}); rotated VDB \
                 transforms are not supported yet"
            ),
            _ => format!("grid {grid:?}: transform {name:?} is not supported"),
        };
        return Err(format_err(path, message));
    }
    file.seek(SeekFrom::Current(triples * 24)).map_err(read)?;
    let mut fields = [0u32; 4];
    for field in &mut fields {
        *field = read_u32(&mut file).map_err(read)?;
    }
    let [buffers, background, tiles, _children] = fields;
    let mut tile = [0u8; 17]; // origin, value, active
    for _ in 0..tiles {
        file.read_exact(&mut tile).map_err(read)?;
        if tile[16] != 0 || buffers != 1 {
            let message = format!("grid {grid:?} has active root tiles or {buffers} buffers");
            return Err(format_err(path, message));
        }
    }
    Ok(f32::from_bits(background))
}

fn read_u32(file: &mut impl Read) -> io::Result<u32> {
    let mut bytes = [0u8; 4];
    file.read_exact(&mut bytes)
        .map(|_| u32::from_le_bytes(bytes))
}

/// The bytes of a metadata block as OpenVDB writes it: a count, then per entry its name, its
/// type name and its value, each after a u32 length.
fn metadata_bytes(meta: &Metadata) -> u64 {
    let entry = |(name, value): (&String, &MetadataValue)| -> usize {
        let (type_len, len) = match value {
            MetadataValue::String(s) => (6, s.chars().count()),
            MetadataValue::Bool(_) => (4, 1),
            MetadataValue::I32(_) | MetadataValue::Float(_) => (5, 4),
            MetadataValue::I64(_) => (5, 8),
            MetadataValue::Vec3i(_) => (5, 12),
            MetadataValue::Unknown { name, data } => (name.chars().count(), data.len()),
        };
        12 + name.chars().count() + type_len + len
    };
    4 + meta.0.iter().map(entry).sum::<usize>() as u64
}

/// Active voxels and tiles: minimum index corner, value, edge length in voxels.
fn voxels(vdb: &Grid<f32>) -> impl Iterator<Item = ([i64; 3], f32, i64)> + '_ {
    let index = |c: f32| c as i64;
    vdb.iter()
        .map(move |(c, v, l)| ([index(c.x), index(c.y), index(c.z)], v, l.scale() as i64))
}

/// The index box of the active voxels, after checking their values (and the background's, if
/// the box has inactive voxels) and that coordinates are exact.
fn scan(path: &Path, grid: &str, vdb: &Grid<f32>, bg: f32) -> Result<IndexBox, GridFileError> {
    let bad = |v: f32| !v.is_finite() || v < 0.0;
    let (mut lo, mut hi, mut count) = ([i64::MAX; 3], [i64::MIN; 3], 0u128);
    let mut first_bad: Option<([i64; 3], f32)> = None;
    let order = |c: [i64; 3]| [c[2], c[1], c[0]];
    for (c, v, n) in voxels(vdb) {
        if c.iter().any(|x| x.abs() >= MAX_COORD) {
            let message = format!("grid {grid:?} has voxels beyond index {MAX_COORD}");
            return Err(format_err(path, message));
        }
        for a in 0..3 {
            (lo[a], hi[a]) = (lo[a].min(c[a]), hi[a].max(c[a] + n - 1));
        }
        count += (n * n * n) as u128;
        if bad(v) && first_bad.is_none_or(|(w, _)| order(c) < order(w)) {
            first_bad = Some((c, v));
        }
    }
    let message = if let Some((c, v)) = first_bad {
        format!("grid {grid:?}: voxel {c:?} has the value {v}; a density is finite and >= 0")
    } else if count == 0 {
        format!("grid {grid:?} has no active voxels")
    } else if bad(bg) && count < (0..3).map(|a| (hi[a] - lo[a] + 1) as u128).product() {
        format!("grid {grid:?}: the background (inactive voxels) is {bg}; a density is >= 0")
    } else {
        return Ok((lo, hi));
    };
    Err(GridFileError::Values {
        file: path.into(),
        message,
    })
}

/// Dense samples, x fastest; an axis with a negative voxel size runs from index `hi` down, so
/// that sample 0 is at the box's low world end.
fn densify(
    vdb: &Grid<f32>,
    (lo, hi): IndexBox,
    res: [usize; 3],
    scale: [f64; 3],
    bg: f32,
) -> Vec<f32> {
    let mut values = vec![bg; res.iter().product()];
    let (start, step) = (
        scale.map(|s| s < 0.0),
        scale.map(|s| if s < 0.0 { -1 } else { 1 }),
    );
    let start = [0, 1, 2].map(|a| if start[a] { hi[a] } else { lo[a] });
    for (c, v, n) in voxels(vdb) {
        for m in 0..n * n * n {
            let c = [c[0] + m % n, c[1] + m / n % n, c[2] + m / (n * n)];
            let p = [0, 1, 2].map(|a| ((c[a] - start[a]) * step[a]) as usize);
            values[(p[2] * res[1] + p[1]) * res[0] + p[0]] = v;
        }
    }
    values
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::PathBuf;

    fn data(file: &str) -> PathBuf {
        Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("tests/data")
            .join(file)
    }

    fn boxed(lo: [f32; 3], hi: [f32; 3]) -> Option<(Vec3, Vec3)> {
        Some((Vec3::from(lo), Vec3::from(hi)))
    }

    /// The message of a Format or Values error.
    fn refusal(file: &str, grid: &str) -> String {
        match read(&data(file), grid, 1 << 20) {
            Err(
                GridFileError::Format { message: m, .. } | GridFileError::Values { message: m, .. },
            ) => m,
            other => panic!("{file} {grid}: {other:?}"),
        }
    }

    #[test]
    fn density_every_value_res_and_bounds() {
        let g = read(&data("vdb_density.vdb"), "density", 240).unwrap();
        assert_eq!(g.res, [5, 4, 3]);
        for (n, v) in g.values.iter().enumerate() {
            let (a, b, c) = (n % 5, n / 5 % 4, n / 20);
            let hole = (a, b, c) == (2, 1, 1); // index (5, -1, 6)
            let e = if hole {
                0.0
            } else {
                0.1 * (a + 2 * b + 3 * c) as f32 + 1.0
            };
            assert!((v - e).abs() < 1e-6, "sample {n}: {v} != {e}");
        }
        // Index box [2.5, 7.5] x [-2.5, 1.5] x [4.5, 7.5]; voxel size 0.5; translation
        // (1, -2, 0.25).
        assert_eq!(g.bounds, boxed([2.25, -3.25, 2.5], [4.75, -1.25, 4.0]));
        // The writer used OpenVDB's default compression, Blosc.
        let compression =
            open(&data("vdb_density.vdb")).unwrap().grid_descriptors["density"].compression;
        assert!(
            compression.contains(vdb_rs::Compression::BLOSC),
            "{compression:?}"
        );
    }

    #[test]
    fn zip_and_uncompressed_files_read_the_same() {
        let blosc = read(&data("vdb_density.vdb"), "density", 240).unwrap();
        for (file, zip) in [("vdb_zip.vdb", true), ("vdb_uncompressed.vdb", false)] {
            let compression = open(&data(file)).unwrap().grid_descriptors["density"].compression;
            assert_eq!(
                compression.contains(vdb_rs::Compression::ZIP),
                zip,
                "{file}"
            );
            assert!(!compression.contains(vdb_rs::Compression::BLOSC), "{file}");
            assert_eq!(read(&data(file), "density", 240).unwrap(), blosc, "{file}");
        }
    }

    #[test]
    fn tiles_background_and_non_uniform_scale() {
        let g = read(&data("vdb_grids.vdb"), "tiles", 1 << 20).unwrap();
        assert_eq!(g.res, [17, 8, 8]);
        for (n, v) in g.values.iter().enumerate() {
            let (i, jk) = (n % 17, n / 17);
            let e = [0.5, 2.0, 0.0][if i < 16 {
                0
            } else if jk == 0 {
                1
            } else {
                2
            }];
            assert_eq!(*v, e, "voxel ({i}, {}, {})", jk % 8, jk / 8);
        }
        assert_eq!(g.bounds, boxed([-1.0; 3], [33.0, 15.0, 15.0]));
        let g = read(&data("vdb_grids.vdb"), "temperature", 1 << 20).unwrap();
        assert_eq!((g.res, g.values), ([2, 2, 1], vec![1.5, 0.25, 0.25, 3.0]));
        // diag(0.5, 0.25, 2) + (1, 2, 3) applied to [-0.5, 1.5] x [-0.5, 1.5] x [-0.5, 0.5].
        assert_eq!(g.bounds, boxed([0.75, 1.875, 2.0], [1.75, 2.375, 4.0]));
    }

    #[test]
    fn transforms() {
        let m = refusal("vdb_transforms.vdb", "rotated");
        assert!(
            m.contains("rotated VDB transforms are not supported"),
            "{m}"
        );
        let m = refusal("vdb_transforms.vdb", "scale_only");
        assert!(m.contains("\"ScaleMap\" is not supported"), "{m}");
        // Voxel size -1 on x, translation (1, 0, 0): index 1 is at x = 0, index 0 at x = 1.
        let g = read(&data("vdb_transforms.vdb"), "mirrored", 1 << 20).unwrap();
        assert_eq!((g.res, g.values), ([2, 1, 1], vec![2.0, 1.0]));
        assert_eq!(g.bounds, boxed([-0.5; 3], [1.5, 0.5, 0.5]));
    }

    #[test]
    fn missing_grid_lists_the_names() {
        let e = read(&data("vdb_grids.vdb"), "density", 1 << 20).unwrap_err();
        let GridFileError::NoSuchGrid {
            name, available, ..
        } = e
        else {
            panic!("{e:?}")
        };
        assert_eq!(name, "density");
        assert_eq!(
            available,
            "the grids empty, half, temperature, tiles, tiles_instance, velocity"
        );
    }

    #[test]
    fn refused_content() {
        let cases = [
            (
                "vdb_grids.vdb",
                "velocity",
                "is a Tree_vec3s_5_4_3, not a float grid",
            ),
            ("vdb_grids.vdb", "empty", "no active voxels"),
            ("vdb_grids.vdb", "half", "saved as half floats"),
            (
                "vdb_grids.vdb",
                "tiles_instance",
                "an instance of grid \"tiles\"",
            ),
            (
                "vdb_bad.vdb",
                "negative",
                "voxel [1, 2, 3] has the value -0.5",
            ),
            ("vdb_bad.vdb", "nan", "voxel [0, 0, 1] has the value NaN"),
            ("vdb_bad.vdb", "inf", "voxel [2, 0, 0] has the value inf"),
        ];
        for (file, grid, expected) in cases {
            let m = refusal(file, grid);
            assert!(m.contains(expected), "{grid}: {m}");
        }
    }

    #[test]
    fn budget_is_checked_before_allocating() {
        let too_large = |file, budget| match read(&data(file), "density", budget) {
            Err(GridFileError::TooLarge { bytes, budget, .. }) => (bytes, budget),
            other => panic!("{other:?}"),
        };
        assert_eq!(too_large("vdb_density.vdb", 1), (240, 1));
        assert_eq!(too_large("vdb_density.vdb", 239), (240, 239));
        // 4 * 100001^3 bytes (4 PB): allocating before the check would abort the test.
        assert_eq!(
            too_large("vdb_far.vdb", 1 << 40),
            (4 * 100_001u64.pow(3), 1 << 40)
        );
    }

    #[test]
    fn unreadable_foreign_and_truncated_files() {
        let e = read(&data("no_such_file.vdb"), "density", 1 << 20);
        assert!(matches!(e, Err(GridFileError::Read { .. })), "{e:?}");
        assert!(refusal("quadrant.ies", "density").contains("not a .vdb file"));
        let dir = tempfile::tempdir().unwrap();
        let bytes = std::fs::read(data("vdb_density.vdb")).unwrap();
        for len in [10, 300, bytes.len() / 2, bytes.len() - 1] {
            let cut = dir.path().join(format!("cut{len}.vdb"));
            std::fs::write(&cut, &bytes[..len]).unwrap();
            let e = read(&cut, "density", 1 << 20).unwrap_err();
            let GridFileError::Format { message: m, .. } = e else {
                panic!("{len}: {e:?}")
            };
            assert!(m.contains("the file ends early (truncated?)"), "{len}: {m}");
        }
        // A panic inside vdb-rs (it has asserts and todo!s on odd files) becomes a refusal.
        let e = guarded::<()>(&data("x.vdb"), || panic!("boom")).unwrap_err();
        assert!(matches!(&e, GridFileError::Format { message, .. } if message.contains("boom")));
    }
}
