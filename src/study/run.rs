//! The study loop: every variant, every run, passes until the time budget is spent, errors
//! measured after each pass. Only pass rendering counts as time; measuring does not.

use std::path::PathBuf;
use std::time::Instant;

use super::StudyError;
use super::metrics::{LayerErrors, layer_errors, mean_error, mean_noise};
use super::reference::{Reference, layer};
use super::variants::Variant;
use crate::integrator::Renderer;
use crate::scene::{build, build_integrator, load};

#[derive(Clone, Debug)]
pub struct StudyConfig {
    pub scene: PathBuf,
    /// `--set` overrides applied to every variant (and the reference), before the variant's own.
    pub sets: Vec<String>,
    pub variants: Vec<Variant>,
    /// Seconds of rendering per run.
    pub seconds: f64,
    pub runs: u32,
    /// Base seed; run k of every variant uses seed + 1 + k (so variants share seeds).
    pub seed: u64,
}

/// Variants that could not be loaded or built: (index, message).
pub type InvalidVariants = Vec<(usize, String)>;

/// Errors after one pass of one run.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize)]
pub struct Checkpoint {
    pub passes: u64,
    /// Seconds spent rendering passes so far.
    pub seconds: f64,
    pub total: LayerErrors,
    pub medium: LayerErrors,
    pub surface: LayerErrors,
    /// Mean per-pixel standard error estimated from the run's own passes.
    pub noise: f64,
    /// Mean signed error (image minus reference) over all values: a bias that persists
    /// across runs shows here, where the MSE cannot tell it from noise.
    pub mean_error: f64,
}

/// One CSV row: a variant's run at a checkpoint.
#[derive(Clone, Debug, PartialEq)]
pub struct Row {
    pub variant: usize,
    pub run: u32,
    pub checkpoint: Checkpoint,
}

/// Progress of a study, for the caller's bar.
#[derive(Clone, Debug)]
pub enum Event<'a> {
    /// A pass finished: the variant, run, and seconds into this run.
    Pass {
        variant: &'a Variant,
        run: u32,
        seconds: f64,
    },
    /// A run finished; its final image (for side-by-side pictures at equal time).
    RunDone {
        variant: &'a Variant,
        run: u32,
        image: &'a crate::film::SpectralImage,
    },
    /// A variant could not be loaded or built: it is skipped.
    Invalid {
        variant: &'a Variant,
        message: String,
    },
}

/// Renders `sets` for `seconds` (at least one pass) with `seed`, calling `each` after every pass
/// with the renderer and the rendering time so far.
pub fn render_for(
    scene_file: &std::path::Path,
    sets: &[String],
    seconds: f64,
    seed: u64,
    mut each: impl FnMut(&Renderer, f64),
) -> Result<(), StudyError> {
    let loaded = load(scene_file, sets)?;
    let scene = build(&loaded)?;
    let integrator = build_integrator(&loaded, &scene)?;
    let mut r = Renderer::new(&scene, integrator, seed);
    let mut spent = 0.0;
    loop {
        let t0 = Instant::now();
        r.render_pass();
        spent += t0.elapsed().as_secs_f64();
        each(&r, spent);
        if spent >= seconds {
            return Ok(());
        }
    }
}

/// Runs the study against `reference`; variants that fail to load or build are reported through
/// `progress` and listed in the second result.
pub fn run_study(
    cfg: &StudyConfig,
    reference: &Reference,
    mut progress: impl FnMut(Event),
) -> Result<(Vec<Row>, InvalidVariants), StudyError> {
    let mut rows = Vec::new();
    let mut invalid = Vec::new();
    for (vi, variant) in cfg.variants.iter().enumerate() {
        let mut sets = cfg.sets.clone();
        sets.extend(variant.sets.iter().cloned());
        // Validate up front so a bad combination is reported once, not per run.
        let checked =
            load(&cfg.scene, &sets).and_then(|l| build(&l).map(|s| s.camera.resolution()));
        let (w, h) = match checked {
            Ok(r) => r,
            Err(e) => {
                let message = e.to_string();
                progress(Event::Invalid {
                    variant,
                    message: message.clone(),
                });
                invalid.push((vi, message));
                continue;
            }
        };
        let want = format!("{} x {}", w, h);
        if w as usize != reference.width || h as usize != reference.height {
            return Err(StudyError::Mismatch {
                got: reference.shape(),
                want,
            });
        }
        for run in 0..cfg.runs {
            let mut failed = None;
            render_for(
                &cfg.scene,
                &sets,
                cfg.seconds,
                cfg.seed.wrapping_add(1 + run as u64),
                |r, seconds| {
                    if failed.is_some() {
                        return;
                    }
                    match measure(r, seconds, reference) {
                        Ok(c) => rows.push(Row {
                            variant: vi,
                            run,
                            checkpoint: c,
                        }),
                        Err(e) => failed = Some(e),
                    }
                    progress(Event::Pass {
                        variant,
                        run,
                        seconds,
                    });
                    if seconds >= cfg.seconds {
                        progress(Event::RunDone {
                            variant,
                            run,
                            image: &r.image(),
                        });
                    }
                },
            )?;
            if let Some(e) = failed {
                return Err(e);
            }
        }
    }
    if invalid.len() == cfg.variants.len() {
        let msgs: Vec<String> = invalid.iter().map(|(_, m)| m.clone()).collect();
        return Err(StudyError::NoVariant(msgs.join("; ")));
    }
    Ok((rows, invalid))
}

fn measure(r: &Renderer, seconds: f64, reference: &Reference) -> Result<Checkpoint, StudyError> {
    let img = r.image();
    if img.data.len() != reference.total.len() {
        return Err(StudyError::Mismatch {
            got: reference.shape(),
            want: format!("{} x {} x {} bins", img.width, img.height, img.grid.n),
        });
    }
    let zeros;
    let (m, s) = match (layer(&img, "medium"), layer(&img, "surface")) {
        (Some(m), Some(s)) => (m, s),
        _ => {
            zeros = vec![0.0; img.data.len()];
            (zeros.as_slice(), zeros.as_slice())
        }
    };
    Ok(Checkpoint {
        passes: r.film().passes,
        seconds,
        total: layer_errors(&img.data, &reference.total),
        medium: layer_errors(m, &reference.medium),
        surface: layer_errors(s, &reference.surface),
        noise: mean_noise(&img),
        mean_error: mean_error(&img.data, &reference.total),
    })
}

/// Renders the reference: `sets` for `seconds` with a seed no study run uses.
pub fn render_reference(
    scene_file: &std::path::Path,
    sets: &[String],
    seconds: f64,
    seed: u64,
    mut progress: impl FnMut(f64),
) -> Result<Reference, StudyError> {
    let mut out = None;
    render_for(
        scene_file,
        sets,
        seconds,
        seed ^ 0x005E_ED0F_BEEF,
        |r, t| {
            progress(t);
            if t >= seconds {
                out = Some(Reference::from_image(&r.image(), r.film().passes, t));
            }
        },
    )?;
    out.ok_or_else(|| StudyError::NoVariant("reference rendered no pass".into()))
}
