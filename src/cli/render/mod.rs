//! `brume render`: everything that can be checked is checked before the scene is built (pass
//! plan, resume agreement, outputs writable, memory), and nothing rendered is lost afterwards:
//! when an output cannot be written the film is saved somewhere and the message says where.

mod interrupt;
mod plan;
mod targets;

use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

use super::RenderArgs;
use super::command_line::CommandLine;
use super::film_files::{self, is_film_path};
use super::outputs;
use super::progress::Progress;
use brume::film::{Film, FilmFile, FilmId, checkpoint, output};
use brume::integrator::auto::Choice;
use brume::integrator::{Budget, OverBudget, Renderer};
use brume::scene::LoadedScene;

pub fn run(args: &RenderArgs) -> anyhow::Result<ExitCode> {
    let interrupt = interrupt::install(args.quiet);
    let cmd = CommandLine::current();
    check_numbers(args)?;
    let loaded = brume::scene::load(&args.scene.scene, &args.scene.sets)?;
    let resumed = args.resume.as_deref().map(read_film).transpose()?;
    let seed = match (&resumed, args.seed) {
        (Some(r), Some(s)) if r.id.seed != s => anyhow::bail!(
            "--seed {s} differs from the seed {} of the checkpoint being resumed",
            r.id.seed
        ),
        (Some(r), _) => r.id.seed,
        (None, s) => s.unwrap_or(loaded.desc.integrator.seed),
    };
    let id = film_files::film_id(&loaded, seed)?;
    let resume_path = args.resume.as_deref().unwrap_or(Path::new(""));
    if let Some(r) = &resumed {
        let name = resume_path.display().to_string();
        // The checkpoint's passes are kept as they are: they must be this render's.
        let passes = r.film.first..r.film.first + r.film.passes;
        film_files::check_same_render((&r.id, &name), (&id, "the render asked for"), passes)?;
    }
    let resumed_ref = resumed.as_ref().map(|r| (resume_path, r));
    let plan = plan::plan(args, loaded.desc.integrator.passes, resumed_ref, &cmd)?;
    let (outputs, derived) = targets::outputs(args, &loaded, plan.range)?;
    check_memory(&loaded, args.force)?;
    let pool = super::thread_pool(args.threads)?;

    let start = Instant::now();
    let (film, stopped, auto, over_budget) =
        pool.install(|| render(args, &loaded, &id, &plan, resumed, &interrupt))?;
    let interrupted = stopped && over_budget.is_none();
    // Standard output may be a pipe its reader has closed: what is printed before the files
    // are saved must not stop the saving, so its first error waits until they are.
    let mut printed = Ok(());
    if let (Some(choice), true) = (&auto, args.verbose) {
        for line in &choice.report {
            printed = printed.and_then(|()| outln!("auto: {line}"));
        }
    }
    if let (Some(b), true) = (film.blend(), args.verbose) {
        let line = brume::scene::identity::blend_report(&b);
        printed = printed.and_then(|()| outln!("blend: {line}"));
    }
    // An interrupt from now on lets the files being written finish; a second aborts.
    interrupt.writing_starts();
    let saved = save(args, (&outputs, &derived), &film, &id)?;
    let interrupted = interrupted || interrupt.interrupted();
    report(args, &film, &id, interrupted, start, &saved, &cmd);
    if film.passes > 0 && plan.range.is_none() {
        printed = printed.and(film_files::report_extras(&film, args.quiet));
    }
    // The passes before it are saved above; the render cannot go on within the budget.
    if let Some(e) = over_budget {
        anyhow::bail!(e);
    }
    if interrupted {
        return Ok(ExitCode::from(interrupt::INTERRUPTED));
    }
    printed?;
    Ok(ExitCode::SUCCESS)
}

/// Command-line numbers the parser cannot bound.
fn check_numbers(args: &RenderArgs) -> anyhow::Result<()> {
    if let Some(t) = args.time {
        anyhow::ensure!(
            t.is_finite() && t > 0.0,
            "--time must be a positive number of seconds"
        );
    }
    anyhow::ensure!(args.passes != Some(0), "--passes must be at least 1");
    if let Some(m) = args.checkpoint_every {
        anyhow::ensure!(
            m.is_finite() && m > 0.0,
            "--checkpoint-every must be a positive number of minutes"
        );
    }
    Ok(())
}

/// Reads a film file to resume, refusing one larger than the machine's memory before loading.
fn read_film(path: &Path) -> anyhow::Result<FilmFile> {
    let header = checkpoint::read_header(path)?;
    if let Some(ram) = film_files::machine_memory() {
        anyhow::ensure!(
            header.file_bytes <= ram,
            "{}: the film file holds {} bytes, more than this machine's memory ({ram} bytes)",
            path.display(),
            header.file_bytes
        );
    }
    Ok(checkpoint::read(path)?)
}

/// What `render` returns: the film (whole passes only), whether it stopped early, the
/// automatic settings' choice, and the row over the gather budget that stopped it, if one did.
type Rendered = (Film, bool, Option<Choice>, Option<OverBudget>);

/// Builds the scene and renders the plan; an interrupt stops it (one during the build exits
/// at once), and so does a row of camera paths over the gather budget.
fn render(
    args: &RenderArgs,
    loaded: &LoadedScene,
    id: &FilmId,
    plan: &plan::Plan,
    resumed: Option<FilmFile>,
    interrupt: &interrupt::Interrupt,
) -> anyhow::Result<Rendered> {
    let (scene, warnings) = brume::scene::build_with_warnings(loaded)?;
    for w in &warnings {
        eprintln!("brume: warning: {w}");
    }
    let integrator = brume::scene::build_integrator(loaded, &scene)?;
    let seed = id.seed;
    // The film keeps the scene's sensors and light layers from the start.
    let film = match resumed {
        Some(r) => {
            anyhow::ensure!(
                r.film.extras == scene.film_extras,
                "the film being resumed keeps other sensors or light layers than the scene"
            );
            r.film
        }
        None => {
            let (w, h) = scene.camera.resolution();
            let extras = scene.film_extras.clone();
            Film::with_extras(
                w as usize,
                h as usize,
                scene.grid.clone(),
                plan.first,
                extras,
            )
        }
    };
    let mut renderer =
        Renderer::resume(&scene, integrator, seed, film).map_err(anyhow::Error::msg)?;
    let total = match plan.budget {
        Budget::Passes(p) => p as u64,
        Budget::Time(t) => t.ceil() as u64,
    };
    if args.verbose && !args.quiet {
        renderer.on_large_build(|n| eprintln!("render: building the gather of {n} records"));
    }
    // Before the progress shows the render started: an interrupt now saves, not exits.
    interrupt.rendering_starts();
    let mut progress = Progress::new("render", total, args.quiet);
    let every = args.checkpoint_every.map(|m| m * 60.0);
    let mut last_save = 0.0;
    let interrupted = renderer.run_until(plan.budget, &interrupt.stop, |film, elapsed| {
        let shown = match plan.budget {
            Budget::Passes(_) => film.passes,
            Budget::Time(_) => (elapsed as u64).min(total),
        };
        progress.set(shown, &format!("{} passes", film.passes));
        let due = every.is_some_and(|every| elapsed - last_save >= every);
        if let (Some(path), true) = (&args.checkpoint, due) {
            last_save = elapsed;
            if let Err(e) = checkpoint::write(path, film, id) {
                eprintln!("brume: warning: checkpoint not saved: {e}");
            }
        }
    });
    progress.finish();
    if args.verbose {
        print_work(&renderer);
    }
    // Nothing was added to the film: no output may claim otherwise.
    if let Some(e) = renderer.choice_changed() {
        anyhow::bail!(
            "{}: {e}",
            args.resume
                .as_ref()
                .map_or_else(|| "the film".to_string(), |p| p.display().to_string())
        );
    }
    let auto = renderer.auto_choice().cloned();
    let over_budget = renderer.over_budget().cloned();
    Ok((renderer.into_film(), interrupted, auto, over_budget))
}

/// `--verbose`'s account of the work done and where the time went.
/// Mid-render: a failed write (a closed pipe) is ignored, the render goes on.
fn print_work(renderer: &Renderer) {
    let s = renderer.stats();
    let _ = outln!(
        "work: {} camera paths, {} volume records, {} forward rays, {} gather hits, {} \
         forward segments; seconds: camera {:.3}, build {:.3}, light {:.3}",
        s.camera_paths,
        s.volume_records,
        s.forward_rays,
        s.gather_hits,
        s.forward_segments,
        s.camera_seconds,
        s.build_seconds,
        s.light_seconds
    );
}

/// What was written, and which film file holds the passes (to resume or merge from).
struct Saved {
    written: Vec<PathBuf>,
    film_file: Option<PathBuf>,
}

/// Writes the outputs and the checkpoint. A film without passes (interrupted before its first)
/// writes nothing: it would replace an earlier file with an empty one. When an output fails,
/// the film is saved somewhere safe and the error says where.
fn save(
    args: &RenderArgs,
    (outputs, derived): (&[PathBuf], &film_files::Derived),
    film: &Film,
    id: &FilmId,
) -> anyhow::Result<Saved> {
    let mut targets: Vec<PathBuf> = Vec::new();
    if film.passes > 0 {
        targets.extend(outputs.iter().chain(&args.checkpoint).cloned());
    }
    let opts = film_files::output_options(id, film)?;
    let is_film = |p: &PathBuf| is_film_path(p) || args.checkpoint.as_ref() == Some(p);
    let mut image = None;
    let mut failed = Vec::new();
    let mut written = Vec::new();
    for t in &targets {
        let result = if is_film(t) {
            checkpoint::write(t, film, id).map_err(anyhow::Error::from)
        } else {
            let img = image.get_or_insert_with(|| film.image());
            output::write(t, img, &opts).map_err(anyhow::Error::from)
        };
        match result {
            Ok(()) => written.push(t.clone()),
            Err(e) => failed.push(e),
        }
    }
    if film.passes > 0 {
        let (w, f) = derived.write(film, &mut image);
        written.extend(w);
        failed.extend(f);
    }
    let film_file = written.iter().find(|p| is_film(p)).cloned();
    if failed.is_empty() {
        return Ok(Saved { written, film_file });
    }
    let errors: Vec<String> = failed.iter().map(|e| format!("{e:#}")).collect();
    let safe = match film_file {
        Some(p) => Some(p),
        None => outputs::rescue(film, id, &outputs::rescue_candidates(&targets[0])),
    };
    let images: Vec<String> = targets
        .iter()
        .filter(|t| !written.contains(t) && !is_film(t))
        .map(|t| format!("-o {}", t.display()))
        .collect();
    Err(match safe {
        Some(p) => anyhow::anyhow!(
            "{}; the film of passes {}..{} is saved in {} (write the images with `brume merge \
             {} {}`)",
            errors.join("; "),
            film.first,
            film.end(),
            p.display(),
            p.display(),
            images.join(" ")
        ),
        None => anyhow::anyhow!(
            "{}; the film could not be saved anywhere either",
            errors.join("; ")
        ),
    })
}

fn report(
    args: &RenderArgs,
    film: &Film,
    id: &FilmId,
    interrupted: bool,
    start: Instant,
    saved: &Saved,
    cmd: &CommandLine,
) {
    let dropped = if film.dropped > 0 {
        format!(", {} non-finite samples dropped", film.dropped)
    } else {
        String::new()
    };
    let wrote = if saved.written.is_empty() {
        "nothing written".to_string()
    } else {
        format!("wrote {}", film_files::list(&saved.written))
    };
    if !interrupted {
        if !args.quiet {
            eprintln!(
                "brume: {} passes in {:.2} s{dropped}; {wrote}",
                film.passes,
                start.elapsed().as_secs_f64(),
            );
        }
        return;
    }
    eprintln!(
        "brume: interrupted: kept {} completed passes (passes {}..{} of seed {}){dropped}; {wrote}",
        film.passes,
        film.first,
        film.end(),
        id.seed
    );
    if let Some(f) = &saved.film_file {
        let again = cmd.replacing(&["--resume"], &[("--resume", f.display().to_string())]);
        eprintln!("brume: continue with `{}`", again.shell());
    }
}

/// Refuses a render whose memory estimate exceeds the machine's memory, unless forced
/// (`brume::scene::identity::memory_check`).
fn check_memory(loaded: &brume::scene::LoadedScene, force: bool) -> anyhow::Result<()> {
    if force {
        return Ok(());
    }
    use brume::scene::identity::{MemoryCheckError, memory_check};
    memory_check(loaded).map_err(|e| match e {
        MemoryCheckError::Over { .. } => anyhow::anyhow!("{e}, or pass --force"),
        MemoryCheckError::Scene(s) => s.into(),
    })
}
