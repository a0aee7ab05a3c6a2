//! clap definitions of brume's subcommands and their dispatch.

/// `print!` to standard output that returns the write's error instead of panicking: a reader
/// that closes the pipe early (`brume info --json | head`) ends the command quietly
/// (`main` treats a broken pipe as done), and a failed write is reported, not a panic.
macro_rules! out {
    ($($t:tt)*) => {{
        use std::io::Write as _;
        write!(std::io::stdout().lock(), $($t)*)
    }};
}

/// `println!` that returns the write's error (see `out!`).
macro_rules! outln {
    ($($t:tt)*) => {{
        use std::io::Write as _;
        writeln!(std::io::stdout().lock(), $($t)*)
    }};
}

mod command_line;
mod film_files;
mod info;
mod merge;
mod outputs;
mod probe;
mod progress;
mod render;
mod spectrum;
mod study;

use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Args, Parser, Subcommand};

/// brume: a spectral renderer for light in fog, smoke and other scattering media
/// (bidirectional Monte-Carlo ray tracing with integration spheres, multiple spheres and cylinders).
#[derive(Debug, Parser)]
#[command(name = "brume", version, about, long_about = None)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Command,
}

#[derive(Debug, Subcommand)]
pub enum Command {
    /// Render a scene file to images (format by extension: .exr scene-linear, .png display sRGB).
    Render(RenderArgs),
    /// Combine film part files (from `render --pass-range`) into the image of all their passes,
    /// bit-identical to a single run (see docs/distributed.md).
    Merge(MergeArgs),
    /// Validate a scene file and summarise it (counts, spectral bins, memory estimate).
    Info(InfoArgs),
    /// Print the colour (XYZ, xy, sRGB) of a spectrum: a reflectance under an illuminant, or an
    /// emission spectrum.
    Spectrum(spectrum::SpectrumArgs),
    /// Read luminance and its standard error back from an EXR output, at a pixel (`--px X,Y`)
    /// or over a region (`--region X0,Y0,X1,Y1`).
    Probe(probe::ProbeArgs),
    /// Render variants of a scene (`--vary KEY=V1,V2`) for equal time against a reference and
    /// measure their error: CSV, JSON summary and plots.
    Study(study::StudyArgs),
}

/// A scene file and overrides of its values.
#[derive(Debug, Args)]
pub struct SceneArgs {
    /// Scene file (TOML; see docs/scene-format.md).
    pub scene: PathBuf,
    /// Override a scene value by its dotted path, e.g. `--set integrator.q=0.1` or
    /// `--set camera.width=64`; VALUE is TOML. Validated exactly like the file. Repeatable.
    /// `--set media=none` switches every medium off (`media.NAME=none`: one medium).
    #[arg(long = "set", value_name = "KEY=VALUE")]
    pub sets: Vec<String>,
}

#[derive(Debug, Args)]
pub struct InfoArgs {
    #[command(flatten)]
    pub scene: SceneArgs,
    /// Print the summary as JSON (bins, media per bin with visibility, radius, memory): what
    /// the Python package's `Scene.info()` returns.
    #[arg(long)]
    pub json: bool,
}

#[derive(Debug, Args)]
pub struct RenderArgs {
    #[command(flatten)]
    pub scene: SceneArgs,
    /// Output file; repeat for several (e.g. `-o out.exr -o out.png`). Default: the scene's
    /// `film.outputs` (in the scene file's folder), else SCENE-NAME.exr and SCENE-NAME.png in
    /// the current folder.
    #[arg(short = 'o', long = "output", value_name = "FILE")]
    pub outputs: Vec<PathBuf>,
    /// Number of passes to render (default: the scene's `integrator.passes`).
    #[arg(long, value_name = "N", conflicts_with = "time")]
    pub passes: Option<u32>,
    /// Render for this many seconds of wall-clock time (whole passes; at least one).
    #[arg(long, value_name = "SECONDS")]
    pub time: Option<f64>,
    /// Seed of all random streams (default: the scene's `integrator.seed`). The image is
    /// bit-identical for a given seed and pass count whatever the thread count.
    #[arg(long, value_name = "N")]
    pub seed: Option<u64>,
    /// Worker threads (default or 0: all cores; at most 1024).
    #[arg(long, value_name = "N")]
    pub threads: Option<usize>,
    /// Print nothing but errors.
    #[arg(long, short = 'q')]
    pub quiet: bool,
    /// Also print what the automatic settings chose and the estimates behind it.
    #[arg(long, short = 'v', conflicts_with = "quiet")]
    pub verbose: bool,
    /// Save the film state to FILE at the end (and on interrupt, and every
    /// --checkpoint-every minutes), to continue later with --resume.
    #[arg(long, value_name = "FILE")]
    pub checkpoint: Option<PathBuf>,
    /// Minutes between periodic checkpoints (needs --checkpoint).
    #[arg(long, value_name = "MINUTES", requires = "checkpoint")]
    pub checkpoint_every: Option<f64>,
    /// Continue the render saved in FILE (a checkpoint) up to --passes in total, or a part file
    /// with its own --pass-range; the image is bit-identical to an uninterrupted run.
    #[arg(long, value_name = "FILE")]
    pub resume: Option<PathBuf>,
    /// Render only passes A..B (A inclusive, B exclusive) of the seed's sequence, for a
    /// distributed render; write a film part file (`-o NAME.brume`) and combine the parts with
    /// `brume merge`.
    #[arg(long, value_name = "A..B", conflicts_with_all = ["time", "passes"])]
    pub pass_range: Option<String>,
    /// Render even when the memory estimate exceeds the machine's memory.
    #[arg(long)]
    pub force: bool,
}

#[derive(Debug, Args)]
pub struct MergeArgs {
    /// Film part files written by `brume render --pass-range` (any order).
    #[arg(required = true)]
    pub parts: Vec<PathBuf>,
    /// Output file (.exr, .png, or .brume for a merged film file); repeatable.
    #[arg(short = 'o', long = "output", value_name = "FILE", required = true)]
    pub outputs: Vec<PathBuf>,
    /// Print nothing but errors.
    #[arg(long, short = 'q')]
    pub quiet: bool,
}

pub fn run(cli: Cli) -> anyhow::Result<ExitCode> {
    match cli.command {
        Command::Render(a) => render::run(&a),
        Command::Merge(a) => merge::run(&a),
        Command::Info(a) => info::run(&a),
        Command::Study(a) => study::run(&a),
        Command::Spectrum(a) => spectrum::run(&a),
        Command::Probe(a) => probe::run(&a),
    }
}

/// More worker threads than this is a typo, not a machine: each thread reserves a stack, and
/// 100 000 of them exhaust the memory before the first pass.
const MAX_THREADS: usize = 1024;

/// The worker pool for `--threads` (None or 0: one thread per core).
pub fn thread_pool(threads: Option<usize>) -> anyhow::Result<rayon::ThreadPool> {
    let n = threads.unwrap_or(0);
    anyhow::ensure!(
        n <= MAX_THREADS,
        "--threads {n}: at most {MAX_THREADS} worker threads (this machine has {} cores)",
        std::thread::available_parallelism().map_or(1, |c| c.get())
    );
    rayon::ThreadPoolBuilder::new()
        .num_threads(n)
        .build()
        .map_err(|e| anyhow::anyhow!("cannot start {n} worker threads: {e}"))
}
