use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::time::Instant;

use anyhow::Context;

use super::RenderArgs;
use super::merge::{self, FILM_EXT, is_film_path};
use super::progress::Progress;
use brume::film::{Film, FilmId, checkpoint, output};
use brume::integrator::{Budget, MemoryEstimate, Renderer};

/// Exit status of an interrupted render (the shell convention for SIGINT).
const INTERRUPTED: u8 = 130;

pub fn run(args: &RenderArgs) -> anyhow::Result<ExitCode> {
    let loaded = brume::scene::load(&args.scene.scene, &args.scene.sets)?;
    if let Some(t) = args.time {
        anyhow::ensure!(
            t.is_finite() && t > 0.0,
            "--time must be a positive number of seconds"
        );
    }
    if args.passes == Some(0) {
        anyhow::bail!("--passes must be at least 1");
    }
    if let Some(m) = args.checkpoint_every {
        anyhow::ensure!(
            m.is_finite() && m > 0.0,
            "--checkpoint-every must be a positive number of minutes"
        );
    }
    let range = args.pass_range.as_deref().map(parse_range).transpose()?;
    let resumed = match &args.resume {
        Some(p) => Some(checkpoint::read(p)?),
        None => None,
    };
    let seed = match (&resumed, args.seed) {
        (Some(r), Some(s)) if r.id.seed != s => anyhow::bail!(
            "--seed {s} differs from the seed {} of the checkpoint being resumed",
            r.id.seed
        ),
        (Some(r), _) => r.id.seed,
        (None, s) => s.unwrap_or(loaded.desc.integrator.seed),
    };
    let id = merge::film_id(&loaded.desc, seed);
    if let (Some(r), Some(p)) = (&resumed, &args.resume) {
        anyhow::ensure!(
            r.id.scene_hash == id.scene_hash,
            "{}: the checkpoint is of another scene (or the scene was edited since)",
            p.display()
        );
        if let Some((a, _)) = range {
            anyhow::ensure!(
                r.film.first == a,
                "{}: the checkpoint starts at pass {}, not at the range's {a}",
                p.display(),
                r.film.first
            );
        }
    }
    let outputs = output_paths(args, &loaded, range)?;
    check_memory(&loaded.desc, args.force)?;
    let budget = match (range, args.passes, args.time) {
        (Some((a, b)), _, _) => {
            Budget::Passes(u32::try_from(b - a).context("pass range too long")?)
        }
        (None, _, Some(t)) => Budget::Time(t),
        (None, Some(p), None) => Budget::Passes(p),
        (None, None, None) => Budget::Passes(loaded.desc.integrator.passes),
    };
    let threads = args.threads.unwrap_or(0);
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .context("cannot start worker threads")?;
    let stop = install_interrupt_handler(args.quiet);

    let start = Instant::now();
    let (film, interrupted) = pool.install(|| -> anyhow::Result<(Film, bool)> {
        let (scene, warnings) = brume::scene::build_with_warnings(&loaded)?;
        for w in &warnings {
            eprintln!("brume: warning: {w}");
        }
        let integrator = brume::scene::build_integrator(&loaded, &scene)?;
        let mut renderer = match (resumed, range) {
            (Some(r), _) => {
                Renderer::resume(&scene, integrator, seed, r.film).map_err(anyhow::Error::msg)?
            }
            (None, Some((a, _))) => Renderer::starting_at(&scene, integrator, seed, a),
            (None, None) => Renderer::new(&scene, integrator, seed),
        };
        let total = match budget {
            Budget::Passes(p) => p as u64,
            Budget::Time(t) => t.ceil() as u64,
        };
        let mut progress = Progress::new("render", total, args.quiet);
        let every = args.checkpoint_every.map(|m| m * 60.0);
        let mut last_save = 0.0;
        let interrupted = renderer.run_until(budget, &stop, |film, elapsed| {
            let shown = match budget {
                Budget::Passes(_) => film.passes,
                Budget::Time(_) => (elapsed as u64).min(total),
            };
            progress.set(shown, &format!("{} passes", film.passes));
            if let (Some(path), Some(every)) = (&args.checkpoint, every)
                && elapsed - last_save >= every
            {
                last_save = elapsed;
                if let Err(e) = checkpoint::write(path, film, &id) {
                    eprintln!("brume: warning: checkpoint not saved: {e}");
                }
            }
        });
        progress.finish();
        Ok((renderer.into_film(), interrupted))
    })?;

    let mut written = outputs.clone();
    if film.passes > 0 {
        let opts = loaded.desc.film.output_options();
        merge::write_outputs(&outputs, &film, &id, &opts)?;
    } else {
        written.clear();
    }
    if let Some(path) = &args.checkpoint {
        checkpoint::write(path, &film, &id)?;
        written.push(path.clone());
    }
    report(args, &film, &id, interrupted, start, &written);
    Ok(if interrupted {
        ExitCode::from(INTERRUPTED)
    } else {
        ExitCode::SUCCESS
    })
}

fn report(
    args: &RenderArgs,
    film: &Film,
    id: &FilmId,
    interrupted: bool,
    start: Instant,
    written: &[PathBuf],
) {
    let dropped = if film.dropped > 0 {
        format!(", {} non-finite samples dropped", film.dropped)
    } else {
        String::new()
    };
    let wrote = if written.is_empty() {
        "nothing written".to_string()
    } else {
        format!("wrote {}", merge::list(written))
    };
    if interrupted {
        eprintln!(
            "brume: interrupted: kept {} completed passes (passes {}..{} of seed {}){dropped}; {wrote}",
            film.passes,
            film.first,
            film.end(),
            id.seed
        );
        if let Some(c) = &args.checkpoint {
            eprintln!(
                "brume: continue with `brume render {} --resume {}`",
                args.scene.scene.display(),
                c.display()
            );
        }
    } else if !args.quiet {
        eprintln!(
            "brume: {} passes in {:.2} s{dropped}; {wrote}",
            film.passes,
            start.elapsed().as_secs_f64(),
        );
    }
}

/// First Ctrl-C (or SIGTERM): finish the pass in flight, then save and exit. Second: abort now.
fn install_interrupt_handler(quiet: bool) -> Arc<AtomicBool> {
    let stop = Arc::new(AtomicBool::new(false));
    let count = AtomicUsize::new(0);
    let flag = stop.clone();
    let result = ctrlc::set_handler(move || {
        if count.fetch_add(1, Ordering::SeqCst) == 0 {
            flag.store(true, Ordering::SeqCst);
            if !quiet {
                eprintln!(
                    "\nbrume: interrupt: finishing the pass in flight, then saving \
                     (interrupt again to abort without saving)"
                );
            }
        } else {
            eprintln!("\nbrume: aborted");
            std::process::exit(INTERRUPTED as i32);
        }
    });
    if let Err(e) = result {
        eprintln!("brume: warning: cannot catch interrupts ({e}); Ctrl-C will lose the render");
    }
    stop
}

/// `A..B`: passes A (inclusive) to B (exclusive) of the seed's sequence.
fn parse_range(s: &str) -> anyhow::Result<(u64, u64)> {
    let bad = || anyhow::anyhow!("--pass-range {s:?}: expected A..B with whole numbers A < B");
    let (a, b) = s.split_once("..").ok_or_else(bad)?;
    let a: u64 = a.trim().parse().map_err(|_| bad())?;
    let b: u64 = b.trim().parse().map_err(|_| bad())?;
    anyhow::ensure!(a < b, bad());
    Ok((a, b))
}

/// Refuses a render whose memory estimate exceeds the machine's memory, unless forced.
fn check_memory(desc: &brume::scene::desc::SceneDesc, force: bool) -> anyhow::Result<()> {
    let est = MemoryEstimate::new(
        &desc.integrator,
        desc.camera.width as u64 * desc.camera.height as u64,
        desc.film.bins,
        !desc.media.is_empty(),
    );
    let values = desc.camera.width as f64 * desc.camera.height as f64 * desc.film.bins as f64;
    // Film: three i128 sums; pass buffer: two f32 layers; final image: data, noise, layers.
    let film = values * (3.0 * 16.0 + 2.0 * 4.0 + 4.0 * 4.0);
    let gather = est.gather_bytes.min(desc.integrator.gather_budget() as f64);
    let need = film + gather;
    let ram = machine_memory();
    if need > ram && !force {
        anyhow::bail!(
            "the render needs about {:.1} GiB (film {:.1} GiB, gather {:.1} GiB) but the machine \
             has {:.1} GiB; lower camera.width/height or film.bins, or pass --force",
            need / GIB,
            film / GIB,
            gather / GIB,
            ram / GIB
        );
    }
    Ok(())
}

const GIB: f64 = (1u64 << 30) as f64;

/// The machine's memory in bytes (8 GiB when /proc/meminfo cannot be read).
fn machine_memory() -> f64 {
    std::fs::read_to_string("/proc/meminfo")
        .ok()
        .and_then(|m| {
            m.lines()
                .find(|l| l.starts_with("MemTotal:"))
                .and_then(|l| l.split_whitespace().nth(1)?.parse::<u64>().ok())
        })
        .map_or(8.0 * GIB, |kib| kib as f64 * 1024.0)
}

fn output_paths(
    args: &RenderArgs,
    scene: &brume::scene::LoadedScene,
    range: Option<(u64, u64)>,
) -> anyhow::Result<Vec<PathBuf>> {
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
    for p in paths.iter().chain(&args.checkpoint) {
        if !is_film_path(p) && args.checkpoint.as_deref().is_none_or(|c| c != p) {
            output::format_of(p)?;
        }
        check_folder(p)?;
    }
    Ok(paths)
}

fn check_folder(p: &Path) -> anyhow::Result<()> {
    if let Some(dir) = p.parent().filter(|d| !d.as_os_str().is_empty()) {
        anyhow::ensure!(
            dir.is_dir(),
            "{}: output folder does not exist",
            dir.display()
        );
    }
    Ok(())
}
