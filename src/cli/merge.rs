//! `brume merge`: combines film part files (from `brume render --pass-range`) into the image a
//! single run of all their passes gives, bit for bit. Also the helpers both commands share to
//! identify a render (scene hash, stored output settings).

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use anyhow::Context;

use super::MergeArgs;
use brume::film::checkpoint::{self, Fnv};
use brume::film::output::{self, OutputOptions};
use brume::film::{Film, FilmId};
use brume::scene::desc::{FilmDesc, SceneDesc};

/// Extension of film files (checkpoints and parts).
pub const FILM_EXT: &str = "brume";

pub fn is_film_path(p: &Path) -> bool {
    p.extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case(FILM_EXT))
}

/// A stable hash of everything in the scene that changes the film: the description without
/// the pass count, seed and output file names (which may differ between slices of one render).
/// Files the scene refers to (textures, meshes, tables) are identified by path, not content.
pub fn scene_hash(desc: &SceneDesc) -> u64 {
    let mut d = desc.clone();
    d.integrator.passes = 0;
    d.integrator.seed = 0;
    d.film.outputs.clear();
    let text = serde_json::to_string(&d).unwrap_or_default();
    let mut h = Fnv::default();
    h.update(text.as_bytes());
    h.0
}

pub fn film_id(desc: &SceneDesc, seed: u64) -> FilmId {
    FilmId {
        seed,
        scene_hash: scene_hash(desc),
        meta: serde_json::to_string(&desc.film).unwrap_or_default(),
    }
}

fn output_options(meta: &str) -> anyhow::Result<OutputOptions> {
    let film: FilmDesc =
        serde_json::from_str(meta).context("the part's stored output settings are unreadable")?;
    Ok(film.output_options())
}

/// Writes images (by extension) and film files of `film`.
pub fn write_outputs(
    outputs: &[PathBuf],
    film: &Film,
    id: &FilmId,
    opts: &OutputOptions,
) -> anyhow::Result<()> {
    let mut image = None;
    for path in outputs {
        if is_film_path(path) {
            checkpoint::write(path, film, id)?;
        } else {
            let img = image.get_or_insert_with(|| film.image());
            output::write(path, img, opts)?;
        }
    }
    Ok(())
}

pub fn run(args: &MergeArgs) -> anyhow::Result<ExitCode> {
    anyhow::ensure!(!args.parts.is_empty(), "no part files given");
    for p in &args.outputs {
        if !is_film_path(p) {
            output::format_of(p)?;
        }
    }
    let mut parts = Vec::with_capacity(args.parts.len());
    for p in &args.parts {
        let f = checkpoint::read(p)?;
        parts.push((p.clone(), f));
    }
    // Integer sums make the order irrelevant to the result; sorting only makes gaps and
    // overlaps easy to report.
    parts.sort_by_key(|(_, f)| f.film.first);
    let (first_path, first) = &parts[0];
    let id = first.id.clone();
    let mut film = first.film.clone();
    for (path, part) in &parts[1..] {
        anyhow::ensure!(
            part.id.scene_hash == id.scene_hash,
            "{}: part of another scene than {}",
            path.display(),
            first_path.display()
        );
        anyhow::ensure!(
            part.id.seed == id.seed,
            "{}: seed {} differs from {}'s seed {}",
            path.display(),
            part.id.seed,
            first_path.display(),
            id.seed
        );
        film.merge(&part.film)
            .with_context(|| format!("{}: cannot merge", path.display()))?;
    }
    let opts = output_options(&id.meta)?;
    write_outputs(&args.outputs, &film, &id, &opts)?;
    if !args.quiet {
        eprintln!(
            "brume: merged {} parts: passes {}..{} of seed {}{}; wrote {}",
            parts.len(),
            film.first,
            film.end(),
            id.seed,
            if film.dropped > 0 {
                format!(", {} non-finite samples dropped", film.dropped)
            } else {
                String::new()
            },
            list(&args.outputs)
        );
    }
    if film.first != 0 {
        eprintln!(
            "brume: warning: the merged passes start at {}, not 0: parts are missing",
            film.first
        );
    }
    Ok(ExitCode::SUCCESS)
}

pub fn list(paths: &[PathBuf]) -> String {
    paths
        .iter()
        .map(|p| p.display().to_string())
        .collect::<Vec<_>>()
        .join(", ")
}
