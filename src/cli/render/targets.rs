//! The files a render writes, decided and checked before anything is built.

use std::path::{Component, Path, PathBuf};

use brume::film::output;
use brume::scene::{LoadedScene, Origin};

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
        scene_outputs(scene)?
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
    let mut named = outputs::named(&paths);
    if let Some(c) = &args.checkpoint {
        named.push((c.clone(), format!("--checkpoint {}", c.display())));
    }
    named.extend(derived.named());
    outputs::check_distinct(&named)?;
    outputs::prepare(&named.into_iter().map(|(p, _)| p).collect::<Vec<_>>())?;
    Ok((paths, derived))
}

/// The scene's `film.outputs`, resolved against the scene file's folder. A scene file may
/// write only inside its folder: an absolute path or one that climbs out of it (`../x.exr`)
/// is refused at its key, unless it came from the command line (`--set`; `-o` replaces
/// `film.outputs` altogether).
fn scene_outputs(scene: &LoadedScene) -> anyhow::Result<Vec<PathBuf>> {
    let source = scene.source();
    let mut out = Vec::with_capacity(scene.desc.film.outputs.len());
    for (i, o) in scene.desc.film.outputs.iter().enumerate() {
        let key = format!("film.outputs.{i}");
        let from_file = matches!(source.origin(&key), Origin::File { .. });
        if from_file && !stays_inside(Path::new(o)) {
            return Err(source
                .invalid(
                    &key,
                    format!(
                        "{o:?} is outside the scene file's folder: a scene writes its outputs \
                         only there (relative paths without `..` above it); give this path \
                         on the command line (-o) instead"
                    ),
                )
                .into());
        }
        out.push(source.resolve(o));
    }
    Ok(out)
}

/// Whether a relative path stays inside the folder it is relative to (no root, drive prefix
/// or `..` that climbs above it).
fn stays_inside(p: &Path) -> bool {
    let mut depth = 0usize;
    for c in p.components() {
        match c {
            Component::Prefix(_) | Component::RootDir => return false,
            Component::CurDir => {}
            Component::ParentDir => match depth.checked_sub(1) {
                Some(d) => depth = d,
                None => return false,
            },
            Component::Normal(_) => depth += 1,
        }
    }
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_paths_below_the_folder_stay_inside() {
        for ok in ["a.exr", "out/a.exr", "./a.exr", "out/../a.exr"] {
            assert!(stays_inside(Path::new(ok)), "{ok}");
        }
        for bad in ["/tmp/a.exr", "../a.exr", "../../x.exr", "out/../../a.exr"] {
            assert!(!stays_inside(Path::new(bad)), "{bad}");
        }
    }
}
