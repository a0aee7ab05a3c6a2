//! What each glTF shape brought into a scene (`brume info` prints it).

use std::fmt;

/// What one glTF shape brought, for `brume info`.
#[derive(Clone, Debug, Default)]
pub struct GltfReport {
    /// `shapes.<i>`.
    pub key: String,
    pub file: String,
    pub meshes: usize,
    pub primitives: usize,
    pub triangles: usize,
    /// (glTF material, the scene material its primitives are made of).
    pub materials: Vec<(String, String)>,
    pub emitting: usize,
    /// Lights added to the scene, and lights in the file.
    pub lights: (usize, usize),
    /// The camera taken as the scene's, if any.
    pub camera: Option<String>,
    /// One line per feature brume ignored.
    pub ignored: Vec<String>,
}

impl fmt::Display for GltfReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(
            f,
            "  {}: {}: {} meshes ({} primitives), {} triangles, {} materials ({} emitting), \
             {} of {} lights imported, camera: {}",
            self.key,
            self.file,
            self.meshes,
            self.primitives,
            self.triangles,
            self.materials.len(),
            self.emitting,
            self.lights.0,
            self.lights.1,
            self.camera.as_deref().unwrap_or("none taken"),
        )?;
        for (g, m) in &self.materials {
            writeln!(f, "    material {g} -> {m}")?;
        }
        for line in &self.ignored {
            writeln!(f, "    ignored: {line}")?;
        }
        Ok(())
    }
}
