//! The files a render writes, decided and checked before anything is built.

use std::path::PathBuf;

use brume::film::output;
use brume::scene::LoadedScene;

use super::super::RenderArgs;
use super::super::film_files::{self, Derived, FILM_EXT, is_film_path};
use super::super::outputs;

/// The outputs (`-o`, else a part file for `--pass-range`, else the scene's `film.outputs`,
/// else SCENE.exr and SCENE.png), checked: known formats, a film file for a pass range, no
/// file named twice, every file writable (leftover temporary files of killed runs removed);
/// with the files derived from them (false-colour maps, sensor tables).
pub fn outputs(
    args: &RenderArgs,
    scene: &LoadedScene,
    range: Option<(u64, u64)>,
) -> anyhow::Result<(Vec<PathBuf>, Derived)> {
    let stem = args
        .scene
        .scene
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "render".into());
    let paths: Vec<PathBuf> = if !args.outputs.is_empty() {
        args.outputs.clone()
    } else if let Some((a, b)) = range {
        vec![PathBuf::from(format!("{stem}.part-{a}-{b}.{FILM_EXT}"))]
    } else if !scene.desc.film.outputs.is_empty() {
        scene.desc.film.outputs.iter().map(PathBuf::from).collect()
    } else {
        vec![
            PathBuf::from(format!("{stem}.exr")),
            PathBuf::from(format!("{stem}.png")),
        ]
    };
    for p in &paths {
        if !is_film_path(p) {
            output::format_of(p)?;
        }
    }
    if let Some(c) = &args.checkpoint
        && output::format_of(c).is_ok()
    {
        anyhow::bail!(
            "--checkpoint {}: a checkpoint is a film file, not an image; name it NAME.{FILM_EXT}",
            c.display()
        );
    }
    if let Some((a, b)) = range {
        // The image of a slice is not the image of the render: only the film file can be
        // merged into it.
        anyhow::ensure!(
            paths.iter().any(|p| is_film_path(p)),
            "--pass-range {a}..{b} renders a part of an image: write it as a film file \
             (-o NAME.{FILM_EXT}) and combine the parts with `brume merge`"
        );
    }
    let sensors = !scene.desc.sensors.is_empty();
    let derived = film_files::derived(&paths, &scene.desc.film, sensors);
    let extra = derived.paths();
    let all: Vec<&PathBuf> = paths.iter().chain(&args.checkpoint).chain(&extra).collect();
    outputs::check_distinct(&all)?;
    outputs::prepare(&all.into_iter().cloned().collect::<Vec<_>>())?;
    Ok((paths, derived))
}
