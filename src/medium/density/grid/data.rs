//! A density grid as a file holds it: dense samples and, where the file says, the box they
//! fill. The readers (`vol`, `vdb`) produce it; `GridField` (mod.rs) turns it into the field.
//!
//! Sample convention (Mitsuba 3's `gridvolume`, so that one `.vol` file means the same in both
//! renderers): sample `(i, j, k)` sits at the centre of cell `(i, j, k)` of the box divided into
//! `res` cells per axis, i.e. at local coordinate `(i + 0.5) / res` of the unit box. Between
//! sample centres the field is trilinear; in the half cell between the outermost centres and the
//! box's faces it is clamped (the nearest centre's value along that axis); outside the box it
//! is zero.

use std::path::PathBuf;

use glam::Vec3;

/// Dense samples, x fastest: `values[(k * res[1] + j) * res[0] + i]`.
#[derive(Clone, Debug, PartialEq)]
pub struct GridData {
    pub res: [usize; 3],
    pub values: Vec<f32>,
    /// The world box the samples fill, when the file places them (a `.vol` file's bounding
    /// box; an OpenVDB grid's active voxels through its transform), else None.
    pub bounds: Option<(Vec3, Vec3)>,
}

/// Why a grid file cannot be used. Every variant names the file.
#[derive(Debug, thiserror::Error)]
pub enum GridFileError {
    #[error("{}: cannot read: {message}", file.display())]
    Read { file: PathBuf, message: String },
    #[error("{}: not a grid file this reader understands: {message}", file.display())]
    Format { file: PathBuf, message: String },
    #[error("{}: no grid named {name:?}; the file has {available}", file.display())]
    NoSuchGrid {
        file: PathBuf,
        name: String,
        available: String,
    },
    #[error("{}: {message}", file.display())]
    Values { file: PathBuf, message: String },
    #[error(
        "{}: the grid needs {bytes} bytes as dense samples, over the budget of {budget} \
         bytes (the density's max_bytes)",
        file.display()
    )]
    TooLarge {
        file: PathBuf,
        bytes: u64,
        budget: u64,
    },
}
