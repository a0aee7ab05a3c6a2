//! A scene description as loaded, with where its keys came from (see [`Source`]).

use std::path::PathBuf;

use super::desc::SceneDesc;
use super::error::SceneWarning;
use super::import_report::GltfReport;
use super::source::Source;

/// A scene description read from a file, overrides applied and validated.
#[derive(Clone, Debug)]
pub struct LoadedScene {
    pub desc: SceneDesc,
    /// The scene file.
    pub file: PathBuf,
    /// Folder that relative paths in the scene resolve from.
    pub dir: PathBuf,
    /// The file's text, to find the line of a key.
    pub text: String,
    /// The `--set` overrides applied, in order: (the assignment as given, its dotted key).
    pub sets: Vec<(String, String)>,
    /// What each glTF shape brought (`desc` holds it already, expanded).
    pub imports: Vec<GltfReport>,
    /// What loading allowed but reports (features of the glTF files that brume ignores).
    pub warnings: Vec<SceneWarning>,
}

impl LoadedScene {
    /// A path given in the scene, resolved against the scene file's folder.
    pub fn resolve(&self, rel: &str) -> PathBuf {
        self.dir.join(rel)
    }

    /// Where the scene's keys are, for placing problems.
    pub fn source(&self) -> Source<'_> {
        Source {
            file: &self.file,
            dir: &self.dir,
            text: &self.text,
            sets: &self.sets,
        }
    }
}
