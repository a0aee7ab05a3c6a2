use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

use anyhow::Context;

use super::RenderArgs;
use super::progress::Progress;
use brume::film::output;
use brume::integrator::{Budget, Renderer};

pub fn run(args: &RenderArgs) -> anyhow::Result<ExitCode> {
    let loaded = brume::scene::load(&args.scene.scene, &args.scene.sets)?;
    let outputs = output_paths(args, &loaded)?;
    if let Some(t) = args.time {
        anyhow::ensure!(
            t.is_finite() && t > 0.0,
            "--time must be a positive number of seconds"
        );
    }
    if args.passes == Some(0) {
        anyhow::bail!("--passes must be at least 1");
    }
    let threads = args.threads.unwrap_or(0);
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .context("cannot start worker threads")?;
    let budget = match (args.passes, args.time) {
        (_, Some(t)) => Budget::Time(t),
        (Some(p), None) => Budget::Passes(p),
        (None, None) => Budget::Passes(loaded.desc.integrator.passes),
    };
    let seed = args.seed.unwrap_or(loaded.desc.integrator.seed);

    let start = Instant::now();
    let image = pool.install(|| -> anyhow::Result<_> {
        let scene = brume::scene::build(&loaded)?;
        let mut renderer = Renderer::new(&scene, seed);
        let total = match budget {
            Budget::Passes(p) => p as u64,
            Budget::Time(t) => t.ceil() as u64,
        };
        let mut progress = Progress::new("render", total, args.quiet);
        renderer.run(budget, |done, elapsed| {
            let shown = match budget {
                Budget::Passes(_) => done,
                Budget::Time(_) => (elapsed as u64).min(total),
            };
            progress.set(shown, &format!("{done} passes"));
        });
        progress.finish();
        Ok((
            renderer.image(),
            renderer.film().passes,
            renderer.film().dropped,
        ))
    })?;
    let (image, passes, dropped) = image;
    let opts = loaded.desc.film.output_options();
    for path in &outputs {
        output::write(path, &image, &opts)?;
    }
    if !args.quiet {
        eprintln!(
            "brume: {passes} passes in {:.2} s{}; wrote {}",
            start.elapsed().as_secs_f64(),
            if dropped > 0 {
                format!(", {dropped} non-finite samples dropped")
            } else {
                String::new()
            },
            outputs
                .iter()
                .map(|p| p.display().to_string())
                .collect::<Vec<_>>()
                .join(", ")
        );
    }
    Ok(ExitCode::SUCCESS)
}

fn output_paths(
    args: &RenderArgs,
    scene: &brume::scene::LoadedScene,
) -> anyhow::Result<Vec<PathBuf>> {
    let paths: Vec<PathBuf> = if !args.outputs.is_empty() {
        args.outputs.clone()
    } else if !scene.desc.film.outputs.is_empty() {
        scene.desc.film.outputs.iter().map(PathBuf::from).collect()
    } else {
        let stem = args
            .scene
            .scene
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_else(|| "render".into());
        vec![
            PathBuf::from(format!("{stem}.exr")),
            PathBuf::from(format!("{stem}.png")),
        ]
    };
    for p in &paths {
        output::format_of(p)?;
        if let Some(dir) = p.parent().filter(|d| !d.as_os_str().is_empty()) {
            anyhow::ensure!(
                dir.is_dir(),
                "{}: output folder does not exist",
                dir.display()
            );
        }
    }
    Ok(paths)
}
