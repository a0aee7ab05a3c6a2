//! The study loop: every variant, every run, passes until the time budget is spent, errors
//! measured after each pass. Only pass rendering counts as time; measuring does not.

use std::path::{Path, PathBuf};

use super::StudyError;
use super::clock::{Budget, Elapsed, PassEnd, run_budgeted};
use super::measure::{Checkpoint, Projection, measure};
use super::reference::Reference;
use super::variants::Variant;
use crate::integrator::Renderer;
use crate::scene::{build, build_integrator, load};

#[derive(Clone, Debug)]
pub struct StudyConfig {
    pub scene: PathBuf,
    /// `--set` overrides applied to every variant (and the reference), before the variant's own.
    pub sets: Vec<String>,
    pub variants: Vec<Variant>,
    /// How long each run renders.
    pub budget: Budget,
    pub runs: u32,
    /// Base seed; run k of every variant uses seed + 1 + k (so variants share seeds).
    pub seed: u64,
    /// Also fit the reference's scale to every checkpoint (`--fit-scale`).
    pub fit_scale: bool,
}

/// Variants that could not be loaded or built: (index, message).
pub type InvalidVariants = Vec<(usize, String)>;

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
    /// A pass finished: the variant, run, time into this run and fraction of its budget spent.
    Pass {
        variant: &'a Variant,
        run: u32,
        elapsed: Elapsed,
        fraction: f64,
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

/// Renders `sets` until `budget` is spent (at least one pass) with `seed`, calling `each` after
/// every pass with the renderer, the rendering time so far and whether it is the run's last
/// call. The pass in flight when the budget runs out is abandoned (see
/// [`run_budgeted`](super::clock::run_budgeted)): the last call then sees the film of the whole
/// passes with the whole time spent.
pub fn render_for(
    scene_file: &Path,
    sets: &[String],
    budget: Budget,
    seed: u64,
    mut each: impl FnMut(&Renderer, Elapsed, bool),
) -> Result<(), StudyError> {
    let loaded = load(scene_file, sets)?;
    let scene = build(&loaded)?;
    let integrator = build_integrator(&loaded, &scene)?;
    let r = std::cell::RefCell::new(Renderer::new(&scene, integrator, seed));
    let (_, end) = run_budgeted(
        budget,
        |stop| r.borrow_mut().render_pass_until(stop),
        |elapsed, last| each(&r.borrow(), elapsed, last),
    );
    match end {
        PassEnd::Done | PassEnd::Stopped => Ok(()),
        PassEnd::Failed => Err(StudyError::NoVariant(format!(
            "{}: a pass could not be rendered (its automatic settings could not be applied)",
            scene_file.display()
        ))),
    }
}

/// The sets of variant `v`: the common ones, then its own.
fn variant_sets(cfg: &StudyConfig, v: &Variant) -> Vec<String> {
    let mut sets = cfg.sets.clone();
    sets.extend(v.sets.iter().cloned());
    sets
}

/// Loads and builds `sets` as a run would; the message says why the scene refuses them.
fn check(
    scene_file: &Path,
    sets: &[String],
) -> Result<(crate::scene::LoadedScene, crate::scene::Scene), String> {
    let loaded = load(scene_file, sets).map_err(|e| e.to_string())?;
    let scene = build(&loaded).map_err(|e| e.to_string())?;
    build_integrator(&loaded, &scene).map_err(|e| e.to_string())?;
    Ok((loaded, scene))
}

/// Every variant the scene refuses (index, message), found by loading and building each as a
/// run would, before anything renders: a typo in a `--vary` value is reported at once, not
/// after the reference. Fails when no variant is valid.
pub fn check_variants(cfg: &StudyConfig) -> Result<InvalidVariants, StudyError> {
    let invalid: InvalidVariants = cfg
        .variants
        .iter()
        .enumerate()
        .filter_map(|(i, v)| {
            check(&cfg.scene, &variant_sets(cfg, v))
                .err()
                .map(|m| (i, m))
        })
        .collect();
    if invalid.len() == cfg.variants.len() {
        let msgs: Vec<String> = invalid.iter().map(|(_, m)| m.clone()).collect();
        return Err(StudyError::NoVariant(msgs.join("; ")));
    }
    Ok(invalid)
}

/// Loads and builds a variant as a run would (so that any value the scene refuses, such as an
/// unknown `integrator.q`, is caught once, before rendering) and prepares the comparison of its
/// images with the reference. The outer error is a variant the scene refuses; the inner one a
/// variant that cannot be compared with the reference at all.
fn prepare(
    scene_file: &Path,
    sets: &[String],
    reference: &Reference,
) -> Result<Result<Projection, StudyError>, String> {
    let (loaded, scene) = check(scene_file, sets)?;
    let (w, h) = scene.camera.resolution();
    if w as usize != reference.width || h as usize != reference.height {
        return Ok(Err(StudyError::Mismatch {
            got: reference.shape(),
            want: format!("{w} x {h}"),
        }));
    }
    let opts = loaded.desc.film.output_options();
    Ok(Projection::new(&reference.values, &scene.grid, &opts))
}

/// Runs the study against `reference`; variants that fail to load or build are reported through
/// `progress` and listed in the second result.
pub fn run_study(
    cfg: &StudyConfig,
    reference: &Reference,
    mut progress: impl FnMut(Event),
) -> Result<(Vec<Row>, InvalidVariants), StudyError> {
    cfg.budget.check()?;
    let mut rows = Vec::new();
    let mut invalid = Vec::new();
    for (vi, variant) in cfg.variants.iter().enumerate() {
        let sets = variant_sets(cfg, variant);
        let projection = match prepare(&cfg.scene, &sets, reference) {
            Ok(p) => p?,
            Err(message) => {
                progress(Event::Invalid {
                    variant,
                    message: message.clone(),
                });
                invalid.push((vi, message));
                continue;
            }
        };
        for run in 0..cfg.runs {
            let mut failed = None;
            let seed = cfg.seed.wrapping_add(1 + run as u64);
            render_for(&cfg.scene, &sets, cfg.budget, seed, |r, elapsed, last| {
                if failed.is_some() {
                    return;
                }
                let img = r.image();
                match measure(
                    &img,
                    r.film().passes,
                    elapsed,
                    reference,
                    &projection,
                    cfg.fit_scale,
                ) {
                    Ok(checkpoint) => rows.push(Row {
                        variant: vi,
                        run,
                        checkpoint,
                    }),
                    Err(e) => failed = Some(e),
                }
                progress(Event::Pass {
                    variant,
                    run,
                    elapsed,
                    fraction: cfg.budget.fraction(elapsed),
                });
                if last {
                    progress(Event::RunDone {
                        variant,
                        run,
                        image: &img,
                    });
                }
            })?;
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

/// Renders the reference: `sets` for `seconds` of wall-clock time with a seed no study run uses.
pub fn render_reference(
    scene_file: &Path,
    sets: &[String],
    seconds: f64,
    seed: u64,
    mut progress: impl FnMut(f64),
) -> Result<Reference, StudyError> {
    let budget = Budget::wall(seconds);
    budget.check()?;
    let mut out = None;
    render_for(
        scene_file,
        sets,
        budget,
        seed ^ 0x005E_ED0F_BEEF,
        |r, t, last| {
            progress(t.wall);
            if last {
                out = Some(Reference::from_image(&r.image(), r.film().passes, t.wall));
            }
        },
    )?;
    out.ok_or_else(|| StudyError::NoVariant("reference rendered no pass".into()))
}
