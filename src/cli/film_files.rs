//! What `render` and `merge` share about film files: their extension, the identity of a render
//! as the command line resolves it, writing a film's outputs, and comparing identities.

use std::path::{Path, PathBuf};

use anyhow::Context;

use brume::film::output::{self, OutputOptions};
use brume::film::{Film, FilmId, Sampling, checkpoint};
use brume::scene::LoadedScene;
use brume::scene::desc::FilmDesc;

/// Extension of film files (checkpoints and parts).
pub const FILM_EXT: &str = "brume";

pub fn is_film_path(p: &Path) -> bool {
    p.extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case(FILM_EXT))
}

/// The identity of rendering `scene` with `seed` on this machine: the description, and the
/// gather budget the renderer will resolve `integrator.max_gather_bytes` to (the same call).
pub fn film_id(scene: &LoadedScene, seed: u64) -> anyhow::Result<FilmId> {
    let budget = scene.desc.integrator.gather_budget() as u64;
    let sampling = Sampling {
        gather_budget: budget,
        machine_memory: machine_memory().unwrap_or(0),
        version: env!("CARGO_PKG_VERSION").to_string(),
    };
    Ok(FilmId::new(&scene.desc, seed, sampling)?)
}

/// Total memory of this machine in bytes, when the system says (Linux).
pub fn machine_memory() -> Option<u64> {
    let info = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = info.lines().find(|l| l.starts_with("MemTotal:"))?;
    let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib * 1024)
}

/// The output settings recorded in a film's identity (the scene's `[film]` table).
pub fn output_options(id: &FilmId) -> anyhow::Result<OutputOptions> {
    let film = id.section("film").cloned().unwrap_or_default();
    let film: FilmDesc =
        serde_json::from_value(film).context("the film file's output settings are unreadable")?;
    Ok(film.output_options())
}

/// Writes every output of `film` (images by extension, film files) and returns the failures:
/// one unwritable output does not cost the others.
pub fn write_outputs(
    outputs: &[PathBuf],
    film: &Film,
    id: &FilmId,
    opts: &OutputOptions,
) -> Vec<anyhow::Error> {
    let mut image = None;
    let mut failed = Vec::new();
    for path in outputs {
        let result = if is_film_path(path) {
            checkpoint::write(path, film, id).map_err(anyhow::Error::from)
        } else {
            let img = image.get_or_insert_with(|| film.image());
            output::write(path, img, opts).map_err(anyhow::Error::from)
        };
        if let Err(e) = result {
            failed.push(e);
        }
    }
    failed
}

/// Refuses a film of another render than `reference`, naming the files and what differs.
pub fn check_same_render(
    ours: &FilmId,
    ours_name: &str,
    reference: &FilmId,
    reference_name: &str,
) -> anyhow::Result<()> {
    ours.check(reference).map_err(|m| {
        anyhow::anyhow!(
            "{ours_name} is not of the same render as {reference_name}: {}",
            m.describe(ours_name, reference_name)
        )
    })
}

pub fn list(paths: &[PathBuf]) -> String {
    paths
        .iter()
        .map(|p| p.display().to_string())
        .collect::<Vec<_>>()
        .join(", ")
}
