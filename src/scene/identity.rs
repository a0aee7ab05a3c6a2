//! What a render of a loaded scene is and what its outputs hold: the film identity (`FilmId`)
//! and the output settings recorded in it. The command line and the Python package both call
//! these, so a film or image written by either is the same bytes.

use std::path::Path;

use crate::film::output::OutputOptions;
use crate::film::{FilmId, IdentityError, Sampling};
use crate::integrator::auto::Choice;

use super::desc::FilmDesc;
use super::loaded::LoadedScene;

/// Extension of film files (checkpoints and parts).
pub const FILM_EXT: &str = "brume";

/// Whether `p` names a film file (`.brume`, any case) rather than an image.
pub fn is_film_path(p: &Path) -> bool {
    p.extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case(FILM_EXT))
}

/// The identity of rendering `scene` with `seed` on this machine: the description, and the
/// gather budget the renderer will resolve `integrator.max_gather_bytes` to (the same call).
pub fn film_id(scene: &LoadedScene, seed: u64) -> Result<FilmId, IdentityError> {
    let budget = scene.desc.integrator.gather_budget() as u64;
    let sampling = Sampling {
        gather_budget: budget,
        machine_memory: machine_memory().unwrap_or(0),
        version: env!("CARGO_PKG_VERSION").to_string(),
    };
    FilmId::new(&scene.desc, seed, sampling)
}

/// Total memory of this machine in bytes, when the system says (Linux).
pub fn machine_memory() -> Option<u64> {
    let info = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = info.lines().find(|l| l.starts_with("MemTotal:"))?;
    let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib * 1024)
}

/// A film file whose recorded `[film]` table cannot be read back.
#[derive(Debug, thiserror::Error)]
#[error("the film file's output settings are unreadable: {0}")]
pub struct FilmSettingsError(#[from] serde_json::Error);

/// The `[film]` table recorded in a film's identity.
pub fn film_desc(id: &FilmId) -> Result<FilmDesc, FilmSettingsError> {
    let film = id.section("film").cloned().unwrap_or_default();
    Ok(serde_json::from_value(film)?)
}

/// The output settings of a film's images: the scene's `[film]` table, and the automatic
/// settings' choice as the EXR attribute `brumeAutoSettings` when the render made one.
pub fn output_options(
    id: &FilmId,
    auto: Option<&Choice>,
) -> Result<OutputOptions, FilmSettingsError> {
    let mut opts = film_desc(id)?.output_options();
    if let Some(c) = auto {
        opts.attributes
            .push(("brumeAutoSettings".into(), c.report.join("; ")));
    }
    Ok(opts)
}

/// Why `memory_check` refuses a render.
#[derive(Debug, thiserror::Error)]
pub enum MemoryCheckError {
    /// The scene's spectral grid is invalid (the film's bins cannot be counted).
    #[error(transparent)]
    Scene(#[from] super::SceneError),
    /// The memory estimate exceeds the machine's memory (the sizes, formatted).
    #[error(
        "the render needs about {needs} (film {film}, gather {gather} per tile) but the machine \
         has {has}; lower camera.width/height or film.bins"
    )]
    Over {
        needs: String,
        film: String,
        gather: String,
        has: String,
    },
}

/// Refuses a render of `scene` whose memory estimate (`MemoryEstimate`, the figures
/// `brume info` prints) exceeds this machine's memory; Ok where the system does not say how
/// much it has. The command line and the Python package both check it before rendering.
pub fn memory_check(scene: &LoadedScene) -> Result<(), MemoryCheckError> {
    let Some(ram) = machine_memory() else {
        return Ok(());
    };
    let desc = &scene.desc;
    // Every bin the film holds, a narrow one per spectral line included.
    let bins = scene.grid()?.n;
    let est = crate::integrator::MemoryEstimate::new(
        &desc.integrator,
        (desc.camera.width, desc.camera.height),
        bins,
        !desc.media.is_empty(),
    );
    let ram = ram as f64;
    if est.total() > ram {
        let f = crate::integrator::format_bytes;
        return Err(MemoryCheckError::Over {
            needs: f(est.total()),
            film: f(est.film_bytes),
            gather: f(est.gather_held()),
            has: f(ram),
        });
    }
    Ok(())
}
