//! `brume study`: equal-time comparison of scene variants against a reference.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use anyhow::Context;
use clap::Args;

use super::SceneArgs;
use super::progress::Progress;
use brume::film::output;
use brume::study::{self, Event, Reference, StudyConfig};

#[derive(Debug, Args)]
pub struct StudyArgs {
    #[command(flatten)]
    pub scene: SceneArgs,
    /// A key and the values it takes, e.g. `--vary integrator.q=1,0.3,0.1`. Repeatable: the
    /// variants are the cartesian product.
    #[arg(long = "vary", value_name = "KEY=V1,V2,...")]
    pub vary: Vec<String>,
    /// Seconds of rendering per run (every variant gets the same).
    #[arg(long, value_name = "SECONDS", default_value_t = 5.0)]
    pub time: f64,
    /// Independent runs (seeds) per variant.
    #[arg(long, value_name = "K", default_value_t = 2)]
    pub runs: u32,
    /// Reference to measure against: a `reference.bin` written by an earlier study. Default:
    /// render one (see --reference-time and --reference-set) and save it in DIR.
    #[arg(long, value_name = "REF.bin")]
    pub reference: Option<PathBuf>,
    /// Seconds for the reference when it is rendered (default: 10 x --time).
    #[arg(long, value_name = "SECONDS")]
    pub reference_time: Option<f64>,
    /// Overrides of the reference render, after --set (default: integrator.volume=cylinder).
    #[arg(long = "reference-set", value_name = "KEY=VALUE")]
    pub reference_sets: Vec<String>,
    /// Base seed.
    #[arg(long, value_name = "N", default_value_t = 0)]
    pub seed: u64,
    /// Worker threads (default: all cores).
    #[arg(long, value_name = "N")]
    pub threads: Option<usize>,
    /// Output folder (created): study.csv, summary.json, error-vs-time.svg,
    /// efficiency-vs-q.svg, reference.bin, PNG images of each variant's first run.
    #[arg(short = 'o', long = "output", value_name = "DIR")]
    pub dir: PathBuf,
    /// Print nothing but errors and the final table.
    #[arg(long, short = 'q')]
    pub quiet: bool,
}

fn slug(label: &str) -> String {
    label
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '.' {
                c
            } else {
                '-'
            }
        })
        .collect()
}

pub fn run(args: &StudyArgs) -> anyhow::Result<ExitCode> {
    anyhow::ensure!(
        args.time.is_finite() && args.time > 0.0,
        "--time must be a positive number of seconds"
    );
    anyhow::ensure!(args.runs >= 1, "--runs must be at least 1");
    let varies = args
        .vary
        .iter()
        .map(|v| study::parse_vary(v))
        .collect::<Result<Vec<_>, _>>()?;
    let variants = study::expand(&varies);
    let loaded = brume::scene::load(&args.scene.scene, &args.scene.sets)?;
    let opts = loaded.desc.film.output_options();
    std::fs::create_dir_all(&args.dir)
        .with_context(|| format!("{}: cannot create output folder", args.dir.display()))?;
    let pool = super::thread_pool(args.threads)?;
    let cfg = StudyConfig {
        scene: args.scene.scene.clone(),
        sets: args.scene.sets.clone(),
        variants: variants.clone(),
        seconds: args.time,
        runs: args.runs,
        seed: args.seed,
    };
    let ref_time = args.reference_time.unwrap_or(10.0 * args.time);
    let rendering_ref = args.reference.is_none();
    // Progress in tenths of a second of budgeted rendering.
    let study_total = variants.len() as f64 * args.runs as f64 * args.time;
    let total = ((study_total + if rendering_ref { ref_time } else { 0.0 }) * 10.0).ceil() as u64;
    let mut progress = Progress::new("study", total, args.quiet);

    let (reference, ref_name) = pool.install(|| reference(args, ref_time, &opts, &mut progress))?;
    let offset = if rendering_ref { ref_time } else { 0.0 };
    let (rows, invalid) =
        pool.install(|| run_variants(args, &cfg, &reference, &opts, offset, &mut progress))?;
    progress.finish();
    let summary = study::summarise(
        &cfg,
        &ref_name,
        (reference.passes, reference.seconds, reference.noise_mse()),
        &rows,
        &invalid,
    );
    write_results(&args.dir, &variants, &rows, &summary)?;
    print_table(&summary, &args.dir);
    Ok(ExitCode::SUCCESS)
}

/// The reference given with --reference, or one rendered (and saved) for the study.
fn reference(
    args: &StudyArgs,
    ref_time: f64,
    opts: &output::OutputOptions,
    progress: &mut Progress,
) -> anyhow::Result<(Reference, String)> {
    if let Some(p) = &args.reference {
        anyhow::ensure!(
            !p.extension().is_some_and(|e| e.eq_ignore_ascii_case("exr")),
            "{}: EXR references are not supported yet; pass a reference.bin written \
             by `brume study`",
            p.display()
        );
        return Ok((Reference::load(p)?, p.display().to_string()));
    }
    let mut sets = args.scene.sets.clone();
    if args.reference_sets.is_empty() {
        sets.push("integrator.volume=cylinder".into());
    } else {
        sets.extend(args.reference_sets.iter().cloned());
    }
    let r = study::render_reference(&args.scene.scene, &sets, ref_time, args.seed, |t| {
        progress.set(((t.min(ref_time)) * 10.0) as u64, "reference");
    })?;
    let path = args.dir.join("reference.bin");
    r.save(&path)?;
    output::write(&args.dir.join("reference.png"), &image_of(&r), opts)?;
    Ok((r, format!("{} ({})", path.display(), sets.join(" "))))
}

/// Every variant's runs, with progress; the first run of each is saved as PNG.
fn run_variants(
    args: &StudyArgs,
    cfg: &StudyConfig,
    reference: &Reference,
    opts: &output::OutputOptions,
    offset: f64,
    progress: &mut Progress,
) -> anyhow::Result<(Vec<study::Row>, study::InvalidVariants)> {
    let mut done_runs = 0usize;
    let mut write_err: Option<anyhow::Error> = None;
    let result = study::run_study(cfg, reference, |ev| match ev {
        Event::Pass {
            variant,
            run,
            seconds,
        } => {
            let t = offset + args.time * done_runs as f64 + seconds.min(args.time);
            progress.set(
                (t * 10.0) as u64,
                &format!("{} run {}", variant.label, run + 1),
            );
        }
        Event::RunDone {
            variant,
            run,
            image,
        } => {
            done_runs += 1;
            if run == 0 {
                let p = args.dir.join(format!("{}.png", slug(&variant.label)));
                if let Err(e) = output::write(&p, image, opts) {
                    write_err.get_or_insert(e.into());
                }
            }
        }
        Event::Invalid { variant, message } => {
            done_runs += args.runs as usize;
            eprintln!("brume: variant {} skipped: {message}", variant.label);
        }
    })?;
    match write_err {
        Some(e) => Err(e),
        None => Ok(result),
    }
}

/// study.csv, summary.json and the two plots.
fn write_results(
    dir: &Path,
    variants: &[study::Variant],
    rows: &[study::Row],
    summary: &study::Summary,
) -> anyhow::Result<()> {
    study::write_csv(&dir.join("study.csv"), variants, rows)?;
    let json = serde_json::to_string_pretty(summary)?;
    brume::film::atomic::replace(&dir.join("summary.json"), |tmp| std::fs::write(tmp, &json))
        .with_context(|| format!("{}: cannot write summary.json", dir.display()))?;
    study::plot_error_vs_time(&dir.join("error-vs-time.svg"), variants, rows)?;
    study::plot_efficiency(
        &dir.join("efficiency-vs-q.svg"),
        variants,
        &summary.variants,
        "integrator.q",
    )?;
    Ok(())
}

fn image_of(r: &Reference) -> brume::film::SpectralImage {
    let mut img = brume::film::SpectralImage::new(r.width, r.height, r.grid.clone());
    img.data = r.total.clone();
    img
}

fn print_table(s: &study::Summary, dir: &Path) {
    println!(
        "{:<32} {:>6} {:>7} {:>11} {:>11} {:>11} {:>11} {:>7} {:>11}",
        "variant",
        "passes",
        "secs",
        "MSE",
        "medium MSE",
        "surface MSE",
        "1/(MSE*t)",
        "gain",
        "mean err"
    );
    for v in &s.variants {
        println!(
            "{:<32} {:>6.1} {:>7.2} {:>11.4e} {:>11.4e} {:>11.4e} {:>11.4e} {:>7.3} {:>11.3e}",
            v.label,
            v.mean_passes,
            v.mean_seconds,
            v.mse,
            v.medium_mse,
            v.surface_mse,
            v.efficiency,
            v.gain_vs_first,
            v.mean_error
        );
    }
    println!(
        "reference noise floor (mean squared standard error): {:.4e}; best: {}; outputs in {}",
        s.reference_noise_mse,
        s.best,
        dir.display()
    );
}
