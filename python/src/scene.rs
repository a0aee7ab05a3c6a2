//! `brume.Scene`: a loaded and validated scene description with its `set` overrides.

use std::path::{Path, PathBuf};

use pyo3::prelude::*;
use pyo3::types::PyDict;

use brume::scene::LoadedScene;

use crate::SceneError;
use crate::convert::{assignment, json_to_py};
use crate::render::{self, Request};
use crate::result::RenderResult;

/// A scene: the file (or text) it came from, the overrides applied, validated.
#[pyclass(frozen, module = "brume")]
pub struct Scene {
    pub loaded: LoadedScene,
    /// The overrides as `--set` takes them, in order.
    sets: Vec<String>,
}

pub fn scene_error(e: brume::scene::SceneError) -> PyErr {
    SceneError::new_err(e.to_string())
}

/// The `set` dict as `KEY=VALUE` assignments.
fn assignments(set: Option<&Bound<'_, PyDict>>) -> PyResult<Vec<String>> {
    let mut out = Vec::new();
    if let Some(d) = set {
        for (k, v) in d.iter() {
            out.push(assignment(&k, &v)?);
        }
    }
    Ok(out)
}

fn load(text: &str, file: &Path, sets: Vec<String>) -> PyResult<Scene> {
    let loaded = brume::scene::load_str(text, file, &sets).map_err(scene_error)?;
    Ok(Scene { loaded, sets })
}

/// Loads a scene file (`text` None) or TOML text (named `file` in messages, relative paths
/// from the working folder).
#[pyfunction]
#[pyo3(signature = (file, text=None, set=None))]
pub fn load_scene(
    file: PathBuf,
    text: Option<String>,
    set: Option<&Bound<'_, PyDict>>,
) -> PyResult<Scene> {
    let sets = assignments(set)?;
    match text {
        Some(t) => load(&t, &file, sets),
        None => {
            let loaded = brume::scene::load(&file, &sets).map_err(scene_error)?;
            Ok(Scene { loaded, sets })
        }
    }
}

#[pymethods]
impl Scene {
    /// What `brume info --json` prints: image size, spectral bins and their edges, each
    /// medium's coefficients per bin with its visibility, the starting radius and the memory
    /// estimate. Builds the scene (reads its textures, meshes and spectra).
    fn info<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let loaded = &self.loaded;
        let (value, _) = py
            .detach(|| brume::scene::info::info_json(loaded))
            .map_err(scene_error)?;
        json_to_py(py, &value.to_string())
    }

    /// The same scene with more overrides (applied after this scene's): for sweeps.
    fn with_set(&self, set: &Bound<'_, PyDict>) -> PyResult<Scene> {
        let mut sets = self.sets.clone();
        sets.extend(assignments(Some(set))?);
        load(&self.loaded.text, &self.loaded.file, sets)
    }

    /// Renders the scene and returns a `RenderResult` (numpy arrays, sensors, `save`).
    ///
    /// passes: passes to render (default: the scene's `integrator.passes`); time: seconds of
    /// wall-clock time instead (whole passes, at least one); pass_range: `(A, B)` renders
    /// passes A..B of the seed's sequence only, a part for `brume.merge`; seed: seed of all
    /// random streams (default: the scene's `integrator.seed`); the image is the same bits
    /// for a seed and pass count whatever `threads` (default or 0: every core). progress:
    /// True shows a bar (tqdm when installed, else a line per pass on stderr), False shows
    /// nothing, a callable is called as `progress(done, total, passes)` after each pass.
    ///
    /// The interpreter is released while rendering. Ctrl-C stops the pass in flight and
    /// raises KeyboardInterrupt (nothing is returned: no partial result). One render runs
    /// in a process at a time (RenderError otherwise). Bad arguments raise ValueError. A
    /// render whose memory estimate exceeds the machine's memory raises RenderError before
    /// it starts, unless `force=True` (the CLI's `--force`).
    #[pyo3(
        signature = (passes=None, time=None, seed=None, threads=None, pass_range=None, progress=None, force=false),
        text_signature = "(self, passes=None, time=None, seed=None, threads=None, pass_range=None, progress=True, force=False)"
    )]
    // The keyword arguments of the Python method, one parameter each.
    #[allow(clippy::too_many_arguments)]
    fn render(
        &self,
        py: Python<'_>,
        passes: Option<i64>,
        time: Option<f64>,
        seed: Option<i64>,
        threads: Option<i64>,
        pass_range: Option<(i64, i64)>,
        progress: Option<Bound<'_, PyAny>>,
        force: bool,
    ) -> PyResult<RenderResult> {
        let request = Request::new(&self.loaded, passes, time, seed, threads, pass_range)?;
        if !force {
            use brume::scene::identity::{MemoryCheckError, memory_check};
            memory_check(&self.loaded).map_err(|e| match e {
                MemoryCheckError::Scene(s) => scene_error(s),
                MemoryCheckError::Over { .. } => {
                    crate::RenderError::new_err(format!("{e}, or pass force=True"))
                }
            })?;
        }
        render::render(py, &self.loaded, &request, progress)
    }

    /// The `KEY=VALUE` overrides applied, as `brume render --set` takes them.
    #[getter]
    fn sets(&self) -> Vec<String> {
        self.sets.clone()
    }

    /// The scene file (or the name given to TOML text).
    #[getter]
    fn file(&self) -> PathBuf {
        self.loaded.file.clone()
    }

    /// The scene's TOML text, before overrides.
    #[getter]
    fn text(&self) -> String {
        self.loaded.text.clone()
    }

    fn __repr__(&self) -> String {
        let d = &self.loaded.desc;
        format!(
            "<brume.Scene {} ({} x {} pixels){}>",
            self.loaded.file.display(),
            d.camera.width,
            d.camera.height,
            if self.sets.is_empty() {
                String::new()
            } else {
                format!(" set {}", self.sets.join(", "))
            }
        )
    }
}
