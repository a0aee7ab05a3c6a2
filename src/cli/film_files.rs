//! What `render` and `merge` share about film files: their extension, the identity of a render
//! as the command line resolves it, writing a film's outputs, and comparing identities.

use std::path::PathBuf;

use brume::film::output::{self, OutputOptions};
use brume::film::{Film, FilmId, SpectralImage, checkpoint};
use brume::scene::desc::FilmDesc;

// Moved to the library (the Python package writes the same files): re-exported for the
// subcommands.
pub use brume::scene::identity::{
    FILM_EXT, film_desc, film_id, is_film_path, machine_memory, output_options,
};

/// Files written beside the image outputs: a false-colour map `NAME-luminance.png` per image
/// name (with `film.false_colour`), and the sensors' `NAME.sensors.csv` and `.json` beside the
/// first image (when the scene has sensors). Film files (parts, checkpoints) get none.
pub fn derived(outputs: &[PathBuf], film: &FilmDesc, sensors: bool) -> Derived {
    let images: Vec<&PathBuf> = outputs.iter().filter(|p| !is_film_path(p)).collect();
    // Every image gets its map, also when an output is named like one (`-o b.png -o
    // b-luminance.png`): the outputs check then refuses the pair instead of one silently
    // replacing the other.
    let mut false_colour: Vec<(PathBuf, PathBuf)> = Vec::new();
    if film.false_colour {
        for p in &images {
            let stem = p.file_stem().map(|s| s.to_string_lossy().into_owned());
            let map = p.with_file_name(format!("{}-luminance.png", stem.unwrap_or_default()));
            if !false_colour.iter().any(|(m, _)| *m == map) {
                false_colour.push((map, (*p).clone()));
            }
        }
    }
    let sensors = match (sensors, images.first()) {
        (true, Some(first)) => Some(output::sensors::paths(first)),
        _ => None,
    };
    Derived {
        false_colour,
        sensors,
        range: film.false_colour_range,
    }
}

/// What [`derived`] decided.
pub struct Derived {
    /// Each false-colour map with the image it belongs to.
    false_colour: Vec<(PathBuf, PathBuf)>,
    pub sensors: Option<[PathBuf; 2]>,
    range: Option<[f32; 2]>,
}

impl Derived {
    /// Every path with what it is, for messages.
    pub fn named(&self) -> Vec<(PathBuf, String)> {
        let mut all: Vec<(PathBuf, String)> = self
            .false_colour
            .iter()
            .map(|(map, image)| {
                let what = format!(
                    "{} (the false-colour map of {}, film.false_colour)",
                    map.display(),
                    image.display()
                );
                (map.clone(), what)
            })
            .collect();
        for p in self.sensors.iter().flatten() {
            all.push((p.clone(), format!("{} (the sensor readings)", p.display())));
        }
        all
    }

    /// Writes the derived files of `film` (its image made once, in `image`): the paths
    /// written and the failures.
    pub fn write(
        &self,
        film: &Film,
        image: &mut Option<SpectralImage>,
    ) -> (Vec<PathBuf>, Vec<anyhow::Error>) {
        let (mut written, mut failed) = (Vec::new(), Vec::new());
        for (path, _) in &self.false_colour {
            let img = image.get_or_insert_with(|| film.image());
            match output::false_colour::write(path, img, self.range) {
                Ok(()) => written.push(path.clone()),
                Err(e) => failed.push(e.into()),
            }
        }
        if let Some(paths) = &self.sensors {
            match output::sensors::write(paths, &film.sensor_readings()) {
                Ok(()) => written.extend(paths.iter().cloned()),
                Err(e) => failed.push(e.into()),
            }
        }
        (written, failed)
    }
}

/// Writes every output of `film` (images by extension, film files, then the derived files)
/// and returns the failures: one unwritable output does not cost the others.
pub fn write_outputs(
    outputs: &[PathBuf],
    derived: &Derived,
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
    failed.extend(derived.write(film, &mut image).1);
    failed
}

/// What a finished film tells beside its images: the sensors' table (stdout), and a warning
/// when light layers miss part of the image.
/// A failed write of the table (a closed pipe) is returned after the warnings.
pub fn report_extras(film: &Film, quiet: bool) -> std::io::Result<()> {
    let readings = film.sensor_readings();
    let mut printed = Ok(());
    if !readings.is_empty() && !quiet {
        printed = out!("{}", output::sensors::table(&readings));
    }
    for r in readings
        .iter()
        .filter(|r| r.spectrum.iter().all(|v| *v == 0.0))
    {
        eprintln!(
            "brume: warning: sensor {} ({}) read exactly 0 in every pass: no light reached it",
            r.name,
            r.kind.name()
        );
    }
    if let Some(f) = film.unattributed()
        && f.abs() > 1e-4
    {
        eprintln!(
            "brume: warning: the light layers hold {:.2} % of the image's light, not all of it: \
             some light was added without the index of the light it came from",
            100.0 * (1.0 - f)
        );
    }
    printed
}

/// Refuses a film of another render than `reference`, naming the files and what differs;
/// `passes` are the passes the films share or hand on (`scene::identity::same_render`).
pub fn check_same_render(
    (ours, ours_name): (&FilmId, &str),
    (reference, reference_name): (&FilmId, &str),
    passes: std::ops::Range<u64>,
) -> anyhow::Result<()> {
    brume::scene::identity::same_render(ours, reference, passes).map_err(|m| {
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
