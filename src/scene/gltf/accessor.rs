//! Reading accessors with every size checked against the buffer view before anything is
//! allocated: a forged `count` (a "huge index count") is refused, never allocated or read
//! out of bounds.

use gltf::accessor::{DataType, Dimensions};

use super::file::{Fault, GltfFile};

/// The components of each element of `acc` as f32 (normalised integers mapped to [0, 1] or
/// [-1, 1] as glTF says), `dims` per element; `allowed` lists the component types accepted.
pub fn read_floats(
    f: &GltfFile,
    acc: &gltf::Accessor,
    dims: Dimensions,
    allowed: &[DataType],
    at: &str,
) -> Result<Vec<f32>, Fault> {
    check_kind(acc, dims, allowed, at)?;
    let bytes = element_bytes(f, acc, at)?;
    let t = acc.data_type();
    let norm = acc.normalized();
    let mut out = Vec::with_capacity(acc.count() * acc.dimensions().multiplicity());
    for e in bytes {
        for c in e.chunks_exact(t.size()) {
            out.push(component(t, c, norm));
        }
    }
    Ok(out)
}

/// An index accessor's values (unsigned 8, 16 or 32 bit scalars).
pub fn read_indices(f: &GltfFile, acc: &gltf::Accessor, at: &str) -> Result<Vec<u32>, Fault> {
    let allowed = [DataType::U8, DataType::U16, DataType::U32];
    check_kind(acc, Dimensions::Scalar, &allowed, at)?;
    let t = acc.data_type();
    // Sizes are checked before anything is allocated.
    let elements = element_bytes(f, acc, at)?;
    let mut out = Vec::with_capacity(acc.count());
    for e in elements {
        out.push(match t {
            DataType::U8 => e[0] as u32,
            DataType::U16 => u16::from_le_bytes([e[0], e[1]]) as u32,
            _ => u32::from_le_bytes([e[0], e[1], e[2], e[3]]),
        });
    }
    Ok(out)
}

fn check_kind(
    acc: &gltf::Accessor,
    dims: Dimensions,
    allowed: &[DataType],
    at: &str,
) -> Result<(), Fault> {
    if acc.dimensions() != dims || !allowed.contains(&acc.data_type()) {
        return Err(Fault::at(
            at,
            format!(
                "accessors[{}] holds {:?} of {:?}, expected {dims:?} of one of {allowed:?}",
                acc.index(),
                acc.dimensions(),
                acc.data_type()
            ),
        ));
    }
    if acc.sparse().is_some() {
        return Err(Fault::at(
            at,
            format!(
                "accessors[{}] is sparse, which brume does not read",
                acc.index()
            ),
        ));
    }
    Ok(())
}

/// The bytes of each element, after checking that `count` elements at the view's stride fit
/// inside the view.
fn element_bytes<'a>(
    f: &'a GltfFile,
    acc: &gltf::Accessor,
    at: &str,
) -> Result<impl Iterator<Item = &'a [u8]> + use<'a>, Fault> {
    let here = format!("{at}: accessors[{}]", acc.index());
    let Some(view) = acc.view() else {
        return Err(Fault::at(
            here,
            "has no bufferView (all zeros): nothing to read",
        ));
    };
    let size = acc.size();
    let stride = view.stride().unwrap_or(size);
    if stride < size {
        return Err(Fault::at(
            here,
            format!("byteStride {stride} is smaller than its elements ({size} bytes)"),
        ));
    }
    let count = acc.count();
    // u128: a forged count cannot overflow the check.
    let end = if count == 0 {
        0
    } else {
        acc.offset() as u128 + stride as u128 * (count as u128 - 1) + size as u128
    };
    if end > view.length() as u128 {
        return Err(Fault::at(
            here,
            format!(
                "{count} elements of {size} bytes (stride {stride}) from byte {} need {end} \
                 bytes; bufferViews[{}] has {}",
                acc.offset(),
                view.index(),
                view.length()
            ),
        ));
    }
    // `open` checked that the view lies inside its buffer.
    let start = view.offset() + acc.offset();
    let data = &f.buffers[view.buffer().index()][start..start + end as usize];
    Ok((0..count).map(move |i| &data[i * stride..i * stride + size]))
}

fn component(t: DataType, c: &[u8], normalized: bool) -> f32 {
    match t {
        DataType::F32 => f32::from_le_bytes([c[0], c[1], c[2], c[3]]),
        DataType::U8 => scale(c[0] as f32, 255.0, normalized),
        DataType::I8 => snorm(c[0] as i8 as f32, 127.0, normalized),
        DataType::U16 => scale(u16::from_le_bytes([c[0], c[1]]) as f32, 65535.0, normalized),
        DataType::I16 => snorm(i16::from_le_bytes([c[0], c[1]]) as f32, 32767.0, normalized),
        DataType::U32 => u32::from_le_bytes([c[0], c[1], c[2], c[3]]) as f32,
    }
}

fn scale(v: f32, max: f32, normalized: bool) -> f32 {
    if normalized { v / max } else { v }
}

/// Signed normalised integers: the most negative value also maps to -1.
fn snorm(v: f32, max: f32, normalized: bool) -> f32 {
    if normalized { (v / max).max(-1.0) } else { v }
}
