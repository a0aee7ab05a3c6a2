//! Opening a glTF file: the JSON (or GLB container) through the `gltf` crate, which checks
//! every index into the file's arrays, then its buffers, each checked against the byte ranges
//! the buffer views claim, so that no later read can go out of bounds.

use std::path::{Path, PathBuf};

/// Largest glTF file or buffer read: 4 GiB (a 100-million-triangle mesh); beyond this a file
/// named by mistake would fill the memory.
pub const MAX_FILE_BYTES: u64 = 4 << 30;

/// A parsed glTF file with its buffers loaded and its buffer views checked.
pub struct GltfFile {
    pub doc: gltf::Document,
    pub buffers: Vec<Vec<u8>>,
    /// The folder its relative URIs resolve from.
    pub dir: PathBuf,
}

/// Why a glTF file cannot be used: the glTF path of the offending object (`meshes[3]
/// .primitives[0]`, empty for the whole file) and the reason.
#[derive(Debug)]
pub struct Fault {
    pub path: String,
    pub message: String,
}

impl Fault {
    pub fn at(path: impl Into<String>, message: impl Into<String>) -> Fault {
        Fault {
            path: path.into(),
            message: message.into(),
        }
    }
}

/// Reads `path`, its buffers and checks its buffer views.
pub fn open(path: &Path) -> Result<GltfFile, Fault> {
    let bytes = read_bounded(path).map_err(|m| Fault::at("", m))?;
    let gltf = gltf::Gltf::from_slice(&bytes).map_err(|e| Fault::at("", e.to_string()))?;
    let dir = path
        .parent()
        .map(Path::to_path_buf)
        .unwrap_or_else(|| PathBuf::from("."));
    let mut blob = gltf.blob;
    let doc = gltf.document;
    let mut buffers = Vec::new();
    for b in doc.buffers() {
        let at = format!("buffers[{}]", b.index());
        let data = match b.source() {
            gltf::buffer::Source::Bin => blob.take().ok_or_else(|| {
                Fault::at(&at, "refers to the GLB's binary chunk, which is absent")
            })?,
            gltf::buffer::Source::Uri(uri) if uri.starts_with("data:") => {
                let source = gltf::buffer::Source::Uri(uri);
                gltf::buffer::Data::from_source(source, Some(&dir))
                    .map_err(|e| Fault::at(&at, format!("data URI: {e}")))?
                    .0
            }
            gltf::buffer::Source::Uri(uri) => {
                let file = dir.join(percent_decoded(uri).map_err(|m| Fault::at(&at, m))?);
                read_bounded(&file).map_err(|m| Fault::at(&at, m))?
            }
        };
        if data.len() < b.length() {
            return Err(Fault::at(
                &at,
                format!(
                    "holds {} bytes, fewer than its byteLength {}",
                    data.len(),
                    b.length()
                ),
            ));
        }
        buffers.push(data);
    }
    for v in doc.views() {
        let len = buffers[v.buffer().index()].len();
        let end = v.offset().checked_add(v.length());
        if end.is_none_or(|e| e > len) {
            return Err(Fault::at(
                format!("bufferViews[{}]", v.index()),
                format!(
                    "bytes {}..{} lie beyond the {len} bytes of buffers[{}]",
                    v.offset(),
                    v.offset() as u128 + v.length() as u128,
                    v.buffer().index()
                ),
            ));
        }
    }
    Ok(GltfFile { doc, buffers, dir })
}

/// The bytes of a file, refused if it is missing, a folder or larger than [`MAX_FILE_BYTES`].
pub fn read_bounded(path: &Path) -> Result<Vec<u8>, String> {
    use std::io::Read;
    let shown = path.display();
    let meta = std::fs::metadata(path).map_err(|e| format!("{shown}: {e}"))?;
    if !meta.is_file() {
        return Err(format!("{shown}: not a file"));
    }
    if meta.len() > MAX_FILE_BYTES {
        return Err(format!(
            "{shown}: {} bytes, more than the {MAX_FILE_BYTES} read",
            meta.len()
        ));
    }
    let mut bytes = Vec::with_capacity(meta.len() as usize);
    std::fs::File::open(path)
        .and_then(|f| f.take(MAX_FILE_BYTES).read_to_end(&mut bytes))
        .map_err(|e| format!("{shown}: {e}"))?;
    Ok(bytes)
}

/// A relative URI's path with its `%XX` escapes decoded (glTF URIs are RFC 3986).
pub fn percent_decoded(uri: &str) -> Result<String, String> {
    let b = uri.as_bytes();
    let mut out = Vec::with_capacity(b.len());
    let mut i = 0;
    while i < b.len() {
        if b[i] == b'%' {
            let hex = b
                .get(i + 1..i + 3)
                .and_then(|h| std::str::from_utf8(h).ok())
                .and_then(|h| u8::from_str_radix(h, 16).ok())
                .ok_or_else(|| format!("URI `{uri}`: a `%` not followed by two hex digits"))?;
            out.push(hex);
            i += 3;
        } else {
            out.push(b[i]);
            i += 1;
        }
    }
    String::from_utf8(out).map_err(|_| format!("URI `{uri}` does not decode to UTF-8"))
}
