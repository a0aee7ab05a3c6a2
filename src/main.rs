use clap::{Parser, Subcommand};

/// Minimal CLI wiring for `brume spectrum` (the lead merges it into the full CLI).
#[derive(Parser)]
#[command(name = "brume", version)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Print the colour (XYZ, xy, sRGB) of a spectrum.
    Spectrum(brume::colour::cli::SpectrumArgs),
}

fn main() -> std::process::ExitCode {
    match Cli::parse().command {
        Command::Spectrum(args) => match brume::colour::cli::run(&args) {
            Ok(out) => {
                println!("{out}");
                std::process::ExitCode::SUCCESS
            }
            Err(e) => {
                eprintln!("error: {e}");
                std::process::ExitCode::FAILURE
            }
        },
    }
}
