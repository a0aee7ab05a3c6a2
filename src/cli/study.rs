//! `brume study`: equal-time comparison of scene variants against a reference.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use anyhow::Context;
use clap::Args;

use super::SceneArgs;
use super::progress::Progress;
use brume::colour::ColourSpace;
use brume::film::output;
use brume::study::{self, Budget, Event, Reference, ReferenceOptions, StudyConfig};

/// The colour space of an RGB reference (`--reference-space`).
#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum ReferenceSpace {
    /// Linear Rec.709 / sRGB primaries, D65 white (Mitsuba's and most renderers' RGB).
    Srgb,
    /// ACEScg (AP1 primaries, ACES white).
    Acescg,
    /// CIE XYZ.
    Xyz,
}

impl ReferenceSpace {
    fn colour_space(self) -> ColourSpace {
        match self {
            ReferenceSpace::Srgb => ColourSpace::Srgb,
            ReferenceSpace::Acescg => ColourSpace::Acescg,
            ReferenceSpace::Xyz => ColourSpace::Xyz,
        }
    }
}

#[derive(Debug, Args)]
pub struct StudyArgs {
    #[command(flatten)]
    pub scene: SceneArgs,
    /// A key and the values it takes, e.g. `--vary integrator.q=1,0.3,0.1` or
    /// `--vary integrator.direct=nee,photons`; any value the scene accepts. Repeatable: the
    /// variants are the cartesian product. A value the scene refuses is reported and skipped.
    #[arg(long = "vary", value_name = "KEY=V1,V2,...")]
    pub vary: Vec<String>,
    /// Wall-clock seconds of rendering per run (every variant gets the same). Default 5 when
    /// --cpu-time is not given.
    #[arg(long, value_name = "SECONDS")]
    pub time: Option<f64>,
    /// Process CPU seconds of rendering per run (user + system time of all threads, from
    /// getrusage); efficiencies are then per CPU second. With --time too, a run stops at
    /// whichever budget it spends first.
    #[arg(long = "cpu-time", value_name = "SECONDS")]
    pub cpu_time: Option<f64>,
    /// Independent runs (seeds) per variant.
    #[arg(long, value_name = "K", default_value_t = 2)]
    pub runs: u32,
    /// Reference to measure against: a `reference.bin` from an earlier study, a film file
    /// (.brume), or an EXR (brume's, or another renderer's RGB image; see --reference-space).
    /// Default: render one (see --reference-time and --reference-set) and save it in DIR.
    #[arg(long, value_name = "FILE")]
    pub reference: Option<PathBuf>,
    /// Colour space of an RGB EXR reference; overrides the file's chromaticities attribute,
    /// and is required when the file has none. Converted to the film's working space.
    #[arg(long = "reference-space", value_enum, value_name = "SPACE")]
    pub reference_space: Option<ReferenceSpace>,
    /// Also fit the reference's scale: the least-squares k with k x reference closest to each
    /// image, reported (CSV, JSON) beside the unscaled error, and the error with k applied.
    #[arg(long = "fit-scale")]
    pub fit_scale: bool,
    /// Seconds for the reference when it is rendered (default: 10 x --time, or 10 x
    /// --cpu-time).
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
    /// Output folder (created): study.csv, summary.json, plots (SVG and PNG), reference.bin,
    /// PNG images of each variant's first run.
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

/// The budget of each run from --time and --cpu-time (5 s of wall clock when neither).
fn budget(args: &StudyArgs) -> anyhow::Result<Budget> {
    let b = match (args.time, args.cpu_time) {
        (None, None) => Budget::wall(5.0),
        (wall, cpu) => Budget { wall, cpu },
    };
    b.check()?;
    Ok(b)
}

pub fn run(args: &StudyArgs) -> anyhow::Result<ExitCode> {
    let budget = budget(args)?;
    anyhow::ensure!(args.runs >= 1, "--runs must be at least 1");
    let varies = args
        .vary
        .iter()
        .map(|v| study::parse_vary(v))
        .collect::<Result<Vec<_>, _>>()?;
    let variants = study::expand(&varies);
    let loaded = brume::scene::load(&args.scene.scene, &args.scene.sets)?;
    let grid = brume::scene::build(&loaded)?.grid;
    let opts = loaded.desc.film.output_options();
    std::fs::create_dir_all(&args.dir)
        .with_context(|| format!("{}: cannot create output folder", args.dir.display()))?;
    let pool = super::thread_pool(args.threads)?;
    let cfg = StudyConfig {
        scene: args.scene.scene.clone(),
        sets: args.scene.sets.clone(),
        variants: variants.clone(),
        budget,
        runs: args.runs,
        seed: args.seed,
        fit_scale: args.fit_scale,
    };
    // Every variant is loaded and built before anything renders, so that a value the scene
    // refuses is reported now, not after the reference.
    let early = study::check_variants(&cfg)?;
    for (i, message) in &early {
        eprintln!("brume: variant {} skipped: {message}", variants[*i].label);
    }
    let per_run = budget.wall.or(budget.cpu).unwrap_or(5.0);
    let ref_time = args.reference_time.unwrap_or(10.0 * per_run);
    // Progress: the reference in tenths of a second, each run in thousandths of its budget.
    let ref_units = if args.reference.is_none() {
        (ref_time * 10.0).ceil() as u64
    } else {
        0
    };
    let total = ref_units + variants.len() as u64 * args.runs as u64 * 1000;
    let mut progress = Progress::new("study", total, args.quiet);

    let ref_opts = ReferenceOptions {
        space: args.reference_space.map(ReferenceSpace::colour_space),
        working: opts.colour_space,
        cat: opts.cat,
        grid,
    };
    // One exposure for every image the study writes, so that they compare: the scene's
    // stops, or when it meters, the reference's metered stops (else the first variant's).
    let mut display = Display::new(opts.clone());
    let (reference, ref_name) =
        pool.install(|| reference(args, ref_time, &ref_opts, &mut display, &mut progress))?;
    let (rows, invalid) = pool.install(|| {
        run_variants(
            args,
            &cfg,
            &reference,
            &mut display,
            ref_units,
            &mut progress,
        )
    })?;
    progress.finish();
    let summary = study::summarise(&cfg, &reference, &ref_name, &rows, &invalid);
    let plots = write_results(&args.dir, &variants, &rows, &summary)?;
    print_summary(&summary, &args.dir, plots.len())?;
    Ok(ExitCode::SUCCESS)
}

/// The display options of the study's images: the film's, with the exposure fixed by the first
/// image they are asked for (a metered exposure is measured once, on the reference when it has
/// a spectral image, and then shared: images at one exposure compare).
struct Display {
    opts: output::OutputOptions,
    fixed: bool,
}

impl Display {
    fn new(opts: output::OutputOptions) -> Self {
        Self { opts, fixed: false }
    }

    /// The options, their exposure measured on `img` if it is not fixed yet.
    fn fix(
        &mut self,
        img: &brume::film::SpectralImage,
    ) -> Result<&output::OutputOptions, output::OutputError> {
        if !self.fixed {
            self.opts = output::with_exposure_of(&self.opts, img)?;
            self.fixed = true;
        }
        Ok(&self.opts)
    }
}

/// The reference given with --reference, or one rendered (and saved) for the study.
fn reference(
    args: &StudyArgs,
    ref_time: f64,
    ref_opts: &ReferenceOptions,
    display: &mut Display,
    progress: &mut Progress,
) -> anyhow::Result<(Reference, String)> {
    let is_exr = |p: &Path| p.extension().is_some_and(|e| e.eq_ignore_ascii_case("exr"));
    if args.reference_space.is_some() {
        anyhow::ensure!(
            args.reference.as_deref().is_some_and(is_exr),
            "--reference-space applies to an EXR given with --reference"
        );
    }
    if let Some(p) = &args.reference {
        let r = Reference::open(p, ref_opts)?;
        if let Some(img) = r.to_image() {
            display.fix(&img)?;
        }
        return Ok((r, p.display().to_string()));
    }
    let mut sets = args.scene.sets.clone();
    if args.reference_sets.is_empty() {
        sets.push("integrator.volume=cylinder".into());
    } else {
        sets.extend(args.reference_sets.iter().cloned());
    }
    let r = study::render_reference(&args.scene.scene, &sets, ref_time, args.seed, |t| {
        progress.set((t.min(ref_time) * 10.0) as u64, "reference");
    })?;
    let path = args.dir.join("reference.bin");
    r.save(&path)?;
    if let Some(img) = r.to_image() {
        output::write(&args.dir.join("reference.png"), &img, display.fix(&img)?)?;
    }
    Ok((r, format!("{} ({})", path.display(), sets.join(" "))))
}

/// Every variant's runs, with progress; the first run of each is saved as PNG.
fn run_variants(
    args: &StudyArgs,
    cfg: &StudyConfig,
    reference: &Reference,
    display: &mut Display,
    offset: u64,
    progress: &mut Progress,
) -> anyhow::Result<(Vec<study::Row>, study::InvalidVariants)> {
    let mut done_runs = 0u64;
    let mut write_err: Option<anyhow::Error> = None;
    let result = study::run_study(cfg, reference, |ev| match ev {
        Event::Pass {
            variant,
            run,
            fraction,
            ..
        } => {
            let at = offset + 1000 * done_runs + (1000.0 * fraction) as u64;
            progress.set(at, &format!("{} run {}", variant.label, run + 1));
        }
        Event::RunDone {
            variant,
            run,
            image,
        } => {
            done_runs += 1;
            if run == 0 {
                let p = args.dir.join(format!("{}.png", slug(&variant.label)));
                let written = display
                    .fix(image)
                    .and_then(|opts| output::write(&p, image, opts));
                if let Err(e) = written {
                    write_err.get_or_insert(e.into());
                }
            }
        }
        // Already reported by `check_variants`, before the reference.
        Event::Invalid { .. } => done_runs += args.runs as u64,
    })?;
    match write_err {
        Some(e) => Err(e),
        None => Ok(result),
    }
}

/// study.csv, summary.json and the plots; returns the plot files.
fn write_results(
    dir: &Path,
    variants: &[study::Variant],
    rows: &[study::Row],
    summary: &study::Summary,
) -> anyhow::Result<Vec<PathBuf>> {
    study::write_csv(&dir.join("study.csv"), variants, rows)?;
    let json = serde_json::to_string_pretty(summary)?;
    brume::film::atomic::replace(&dir.join("summary.json"), |tmp| std::fs::write(tmp, &json))
        .with_context(|| format!("{}: cannot write summary.json", dir.display()))?;
    Ok(study::write_plots(dir, variants, rows, summary)?)
}

/// A value that may not be measured, in a column of `width`.
fn cell(v: Option<f64>, width: usize) -> String {
    match v {
        Some(v) => format!("{v:>width$.4e}"),
        None => format!("{:>width$}", "-"),
    }
}

fn print_summary(s: &study::Summary, dir: &Path, plots: usize) -> std::io::Result<()> {
    let eff = match s.clock {
        study::Clock::Wall => "1/(MSE*t)",
        study::Clock::Cpu => "1/(MSE*cpu)",
    };
    outln!(
        "{:<32} {:>6} {:>7} {:>7} {:>11} {:>11} {:>11} {:>11} {:>7} {:>11}{}",
        "variant",
        "passes",
        "secs",
        "cpu s",
        "MSE",
        "medium MSE",
        "surface MSE",
        eff,
        "gain",
        "mean err",
        if s.fit_scale { "           k" } else { "" }
    )?;
    for v in &s.variants {
        let k = match (&v.k, s.fit_scale) {
            (Some(k), true) => format!(" {:>11.5}", k.mean),
            (None, true) => format!(" {:>11}", "-"),
            (_, false) => String::new(),
        };
        let over = if v.over_budget { "  OVER BUDGET" } else { "" };
        outln!(
            "{:<32} {:>6.1} {:>7.2} {:>7.2} {:>11.4e} {} {} {:>11.4e} {:>7.3} {:>11.3e}{k}{over}",
            v.label,
            v.mean_passes,
            v.mean_seconds,
            v.mean_cpu_seconds,
            v.mse,
            cell(v.medium_mse, 11),
            cell(v.surface_mse, 11),
            v.efficiency,
            v.gain_vs_first,
            v.mean_error,
        )?;
    }
    for b in &s.best_per_layer {
        outln!("{}", b.describe())?;
    }
    let floor = s
        .reference_noise_mse
        .map_or("unknown".to_string(), |f| format!("{f:.4e}"));
    outln!("reference: {}; {}", s.reference, s.reference_values)?;
    for n in &s.notes {
        outln!("note: {n}")?;
    }
    outln!(
        "reference noise floor (mean squared standard error): {floor}; outputs in {} \
         (study.csv, summary.json, {plots} plot files)",
        dir.display()
    )
}
