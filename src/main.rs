//! The `brume` command line: argument parsing and reporting only; the work is in the library.

mod cli;

use std::process::ExitCode;

use clap::Parser;

fn main() -> ExitCode {
    let args = cli::Cli::parse();
    match cli::run(args) {
        Ok(code) => code,
        Err(e) => {
            // One clear line: the chain of causes joined, no backtrace.
            eprintln!("brume: error: {e:#}");
            ExitCode::FAILURE
        }
    }
}
