//! Mitsuba's binary volume format (`.vol`, version 3, float32), as Mitsuba 0.6 and 3 read and
//! write it: the bytes `VOL`, the version byte 3, then little-endian int32 encoding (1 =
//! float32), int32 cell counts along x, y and z, int32 channel count, six float32 giving the
//! box (x, y, z minimum, then maximum), then the samples, x fastest, channels innermost. brume
//! reads one-channel grids (a density); several channels are refused, not averaged.

use std::path::Path;

use glam::Vec3;

use super::data::{GridData, GridFileError};

const HEADER: usize = 48;

/// Reads a one-channel float32 `.vol` file. Sizes are checked against the file's length and
/// `budget` (bytes of dense samples) before anything is allocated; values are not checked here
/// (`GridField::new` does, naming the sample).
pub fn read(path: &Path, budget: u64) -> Result<GridData, GridFileError> {
    let bytes = std::fs::read(path).map_err(|e| GridFileError::Read {
        file: path.to_path_buf(),
        message: e.to_string(),
    })?;
    let format = |message: String| GridFileError::Format {
        file: path.to_path_buf(),
        message,
    };
    if bytes.len() < HEADER || &bytes[..3] != b"VOL" {
        return Err(format(
            "a .vol file starts with 'VOL' and a 48-byte header".into(),
        ));
    }
    if bytes[3] != 3 {
        return Err(format(format!(
            "version {} (only version 3 is read)",
            bytes[3]
        )));
    }
    let int =
        |at: usize| i32::from_le_bytes([bytes[at], bytes[at + 1], bytes[at + 2], bytes[at + 3]]);
    let float =
        |at: usize| f32::from_le_bytes([bytes[at], bytes[at + 1], bytes[at + 2], bytes[at + 3]]);
    let encoding = int(4);
    if encoding != 1 {
        return Err(format(format!(
            "encoding {encoding} (only 1, float32, is read)"
        )));
    }
    let (nx, ny, nz, channels) = (int(8), int(12), int(16), int(20));
    if channels != 1 {
        return Err(format(format!(
            "{channels} channels: a density grid has one"
        )));
    }
    if nx < 1 || ny < 1 || nz < 1 {
        return Err(format(format!("cell counts {nx} x {ny} x {nz}")));
    }
    let res = [nx as usize, ny as usize, nz as usize];
    let count = res.iter().map(|&n| n as u64).product::<u64>();
    let need = count * 4;
    if need > budget {
        return Err(GridFileError::TooLarge {
            file: path.to_path_buf(),
            bytes: need,
            budget,
        });
    }
    if (bytes.len() - HEADER) as u64 != need {
        return Err(format(format!(
            "{nx} x {ny} x {nz} samples need {need} bytes after the header, the file has {}",
            bytes.len() - HEADER
        )));
    }
    let lo = Vec3::new(float(24), float(28), float(32));
    let hi = Vec3::new(float(36), float(40), float(44));
    let values = bytes[HEADER..]
        .chunks_exact(4)
        .map(|c| f32::from_le_bytes([c[0], c[1], c[2], c[3]]))
        .collect();
    // A box that is not a box (Mitsuba writes whatever its caller gave) places nothing.
    let placed = lo.is_finite() && hi.is_finite() && lo.cmplt(hi).all();
    Ok(GridData {
        res,
        values,
        bounds: placed.then_some((lo, hi)),
    })
}

/// The bytes of a one-channel `.vol` file of `data` (its bounds, or the unit box).
pub fn encode(data: &GridData) -> Vec<u8> {
    let (lo, hi) = data.bounds.unwrap_or((Vec3::ZERO, Vec3::ONE));
    let mut out = Vec::with_capacity(HEADER + 4 * data.values.len());
    out.extend_from_slice(b"VOL\x03");
    let ints = [
        1,
        data.res[0] as i32,
        data.res[1] as i32,
        data.res[2] as i32,
        1,
    ];
    ints.iter()
        .for_each(|i| out.extend_from_slice(&i.to_le_bytes()));
    let floats = lo.to_array().into_iter().chain(hi.to_array());
    floats.for_each(|f| out.extend_from_slice(&f.to_le_bytes()));
    data.values
        .iter()
        .for_each(|f| out.extend_from_slice(&f.to_le_bytes()));
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample() -> GridData {
        GridData {
            res: [3, 2, 4],
            values: (0..24).map(|i| i as f32 * 0.25 - 1.0).collect(),
            bounds: Some((Vec3::new(-1.0, 0.0, 2.0), Vec3::new(1.0, 0.5, 3.0))),
        }
    }

    #[test]
    fn a_written_file_reads_back_exactly() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("g.vol");
        std::fs::write(&p, encode(&sample())).unwrap();
        assert_eq!(read(&p, 1 << 20).unwrap(), sample());
    }

    #[test]
    fn damaged_or_foreign_files_are_refused_naming_the_file() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("g.vol");
        let good = encode(&sample());
        let cases: Vec<(Vec<u8>, &str)> = vec![
            (b"not a grid".to_vec(), "starts with 'VOL'"),
            (good[..good.len() - 4].to_vec(), "the file has 92"),
            ([&good[..3], &[2u8], &good[4..]].concat(), "version 2"),
            (
                [&good[..20], &3i32.to_le_bytes(), &good[24..]].concat(),
                "3 channels",
            ),
            (
                [&good[..8], &0i32.to_le_bytes(), &good[12..]].concat(),
                "cell counts 0",
            ),
        ];
        for (bytes, says) in cases {
            std::fs::write(&p, bytes).unwrap();
            let e = read(&p, 1 << 20).unwrap_err().to_string();
            assert!(e.contains("g.vol") && e.contains(says), "{e}");
        }
        let e = read(&dir.path().join("none.vol"), 1 << 20).unwrap_err();
        assert!(matches!(e, GridFileError::Read { .. }), "{e}");
    }

    #[test]
    fn the_budget_is_checked_before_the_samples_are_read() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("g.vol");
        // A header claiming 2^30 samples over 4 bytes of data: refused by size, not allocated.
        let mut bytes = encode(&sample())[..HEADER].to_vec();
        bytes[8..12].copy_from_slice(&1024i32.to_le_bytes());
        bytes[12..16].copy_from_slice(&1024i32.to_le_bytes());
        bytes[16..20].copy_from_slice(&1024i32.to_le_bytes());
        std::fs::write(&p, bytes).unwrap();
        let e = read(&p, 1 << 30).unwrap_err();
        assert!(
            matches!(e, GridFileError::TooLarge { bytes, .. } if bytes == 1 << 32),
            "{e}"
        );
    }
}
