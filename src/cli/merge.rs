//! `brume merge`: combines film part files (from `brume render --pass-range`) into the image a
//! single run of all their passes gives, bit for bit.
//!
//! Every part's header is read and checked (same render, adjacent ranges, outputs writable)
//! before any sums are loaded; the sums are then added one part at a time, so a merge holds
//! two films in memory whatever the number of parts.

use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::Context;

use super::MergeArgs;
use super::film_files::{self, is_film_path};
use super::outputs;
use brume::film::checkpoint::{self, FilmHeader};
use brume::film::output;

pub fn run(args: &MergeArgs) -> anyhow::Result<ExitCode> {
    anyhow::ensure!(!args.parts.is_empty(), "no part files given");
    for p in &args.outputs {
        if !is_film_path(p) {
            output::format_of(p)?;
        }
    }
    outputs::check_distinct(&outputs::named(&args.outputs))?;
    let mut parts = Vec::with_capacity(args.parts.len());
    for p in &args.parts {
        parts.push((p.clone(), checkpoint::read_header(p)?));
    }
    // Integer sums make the order irrelevant to the result; sorting only makes gaps and
    // overlaps easy to report.
    parts.sort_by_key(|(_, h)| h.first);
    check_parts(&parts)?;
    let film_desc = film_files::film_desc(&parts[0].1.id)?;
    let derived = film_files::derived(&args.outputs, &film_desc, has_sensors(&parts[0].1.id));
    let mut named = outputs::named(&args.outputs);
    named.extend(derived.named());
    outputs::check_distinct(&named)?;
    let all: Vec<PathBuf> = named.into_iter().map(|(p, _)| p).collect();
    outputs::prepare(&all)?;

    let (first_path, first) = &parts[0];
    let mut film = checkpoint::read(first_path)?.film;
    for (path, _) in &parts[1..] {
        let part = checkpoint::read(path)?;
        film.merge(&part.film)
            .with_context(|| format!("{}: cannot merge", path.display()))?;
    }
    let id = &first.id;
    let opts = film_files::output_options(id, &film)?;
    let failed = film_files::write_outputs(&args.outputs, &derived, &film, id, &opts);
    if let Some(e) = failed.into_iter().next() {
        // The parts are untouched: the merge can simply be run again.
        return Err(e.context("merge not written (the parts are unchanged)"));
    }
    if !args.quiet {
        eprintln!(
            "brume: merged {} parts: passes {}..{} of seed {}{}; wrote {}",
            parts.len(),
            film.first,
            film.end(),
            id.seed,
            if film.dropped > 0 {
                format!(", {} non-finite samples dropped", film.dropped)
            } else {
                String::new()
            },
            film_files::list(&all)
        );
    }
    film_files::report_extras(&film, args.quiet)?;
    if film.first != 0 {
        eprintln!(
            "brume: warning: the merged passes start at {}, not 0: parts are missing",
            film.first
        );
    }
    Ok(ExitCode::SUCCESS)
}

/// Whether the render's description has `[[sensors]]`.
fn has_sensors(id: &brume::film::FilmId) -> bool {
    id.section("sensors")
        .and_then(|s| s.as_array())
        .is_some_and(|a| !a.is_empty())
}

/// Same render, same film shape, adjacent pass ranges, and enough memory for two films.
fn check_parts(parts: &[(PathBuf, FilmHeader)]) -> anyhow::Result<()> {
    let (first_path, first) = &parts[0];
    let first_name = first_path.display().to_string();
    let shape = |h: &FilmHeader| (h.width, h.height, h.grid.clone());
    for w in parts.windows(2) {
        let ((pa, a), (pb, b)) = (&w[0], &w[1]);
        // The merged film carries the first part's identity: every part's passes must be
        // rendered alike under both descriptions.
        let passes = first.first.min(b.first)..first.end().max(b.end());
        film_files::check_same_render(
            (&b.id, &pb.display().to_string()),
            (&first.id, &first_name),
            passes,
        )?;
        anyhow::ensure!(
            shape(a) == shape(b),
            "{} and {}: films differ in size or spectral grid",
            pa.display(),
            pb.display()
        );
        anyhow::ensure!(
            a.end() == b.first,
            "{} (passes {}..{}) and {} (passes {}..{}): pass ranges are not adjacent",
            pa.display(),
            a.first,
            a.end(),
            pb.display(),
            b.first,
            b.end()
        );
    }
    let largest = parts.iter().map(|(_, h)| h.file_bytes).max().unwrap_or(0);
    if let Some(ram) = film_files::machine_memory() {
        anyhow::ensure!(
            largest.saturating_mul(2) <= ram,
            "{first_name}: merging needs two films in memory ({largest} bytes each) but the \
             machine has {ram} bytes"
        );
    }
    Ok(())
}
