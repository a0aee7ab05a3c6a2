//! Which passes a render computes, decided and checked before anything is built: `--passes`,
//! `--time`, `--pass-range` and `--resume` must agree, and a request that would silently give
//! another pass range than the one asked for is refused with the command that does what was
//! meant.

use std::path::Path;

use brume::film::FilmFile;
use brume::integrator::{Budget, MAX_PASS_END};

use super::super::RenderArgs;
use super::super::command_line::CommandLine;

/// Options that choose the passes (replaced in the hints).
const PASS_OPTIONS: [&str; 4] = ["--passes", "--time", "--pass-range", "--resume"];

#[derive(Debug, PartialEq)]
pub struct Plan {
    pub budget: Budget,
    /// First pass of a fresh film (ignored when resuming: the film says).
    pub first: u64,
    /// The range asked for with `--pass-range`.
    pub range: Option<(u64, u64)>,
}

/// `A..B`: passes A (inclusive) to B (exclusive) of the seed's sequence.
pub fn parse_range(s: &str) -> anyhow::Result<(u64, u64)> {
    let bad = || anyhow::anyhow!("--pass-range {s:?}: expected A..B with whole numbers A < B");
    let (a, b) = s.split_once("..").ok_or_else(bad)?;
    let a: u64 = a.trim().parse().map_err(|_| bad())?;
    let b: u64 = b.trim().parse().map_err(|_| bad())?;
    anyhow::ensure!(a < b, bad());
    anyhow::ensure!(
        b <= MAX_PASS_END,
        "--pass-range {s}: pass indices end at {MAX_PASS_END} (no render has more passes)"
    );
    Ok((a, b))
}

/// The plan for `args`; `scene_passes` is the scene's `integrator.passes`.
pub fn plan(
    args: &RenderArgs,
    scene_passes: u32,
    resumed: Option<(&Path, &FilmFile)>,
    cmd: &CommandLine,
) -> anyhow::Result<Plan> {
    let range = args.pass_range.as_deref().map(parse_range).transpose()?;
    let budget = match (range, args.time, args.passes) {
        // b - a <= MAX_PASS_END = u32::MAX.
        (Some((a, b)), _, _) => Budget::Passes((b - a) as u32),
        (None, Some(t), _) => Budget::Time(t),
        (None, None, Some(p)) => Budget::Passes(p),
        (None, None, None) => Budget::Passes(scene_passes),
    };
    let plan = Plan {
        budget,
        first: range.map_or(0, |(a, _)| a),
        range,
    };
    if let Some((path, file)) = resumed {
        check_resume(&plan, args, path, file, cmd)?;
    }
    Ok(plan)
}

/// A resume continues the checkpoint's range: a part (first pass > 0) only with the
/// `--pass-range` it belongs to, a full render up to at least the passes it holds.
fn check_resume(
    plan: &Plan,
    args: &RenderArgs,
    path: &Path,
    file: &FilmFile,
    cmd: &CommandLine,
) -> anyhow::Result<()> {
    let f = &file.film;
    let (first, end) = (f.first, f.end());
    let name = path.display();
    let holds = format!("{name} holds passes {first}..{end}");
    let continue_with = |b: String| {
        cmd.replacing(
            &PASS_OPTIONS,
            &[
                ("--pass-range", format!("{first}..{b}")),
                ("--resume", path.display().to_string()),
            ],
        )
        .shell()
    };
    anyhow::ensure!(
        end <= MAX_PASS_END,
        "{holds}: beyond the last pass index {MAX_PASS_END}"
    );
    match (plan.range, plan.budget) {
        (Some((a, b)), _) => {
            let target = b.max(end);
            anyhow::ensure!(
                a == first && b >= end,
                "{holds}, which --pass-range {a}..{b} does not continue; continue it with `{}`",
                continue_with(target.to_string())
            );
        }
        (None, _) if first > 0 => {
            // The hint is a command that runs: --passes when it asks for more than the part
            // holds, else as many passes again as it holds (the end is the user's to choose).
            let asked = args.passes.map(u64::from).filter(|p| *p > end);
            let b = asked.unwrap_or_else(|| (end + (end - first)).min(MAX_PASS_END));
            anyhow::bail!(
                "{holds} (a part of a distributed render): it continues only with its own \
                 --pass-range; continue it with `{}`{}",
                continue_with(b.to_string()),
                if asked.is_none() {
                    format!(" (or any end above {end})")
                } else {
                    String::new()
                }
            );
        }
        (None, Budget::Passes(p)) => {
            let asked = if args.passes.is_some() {
                format!("--passes {p}")
            } else {
                format!("the scene's integrator.passes = {p}")
            };
            anyhow::ensure!(
                u64::from(p) >= end,
                "{holds}, more than the {asked} asked for (--passes counts every pass, those \
                 already done included); ask for at least {end}, e.g. for {p} more: `{}`",
                cmd.replacing(
                    &["--passes"],
                    &[("--passes", (end + u64::from(p)).to_string())]
                )
                .shell()
            );
        }
        (None, Budget::Time(_)) => {}
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ranges_are_bounded_and_ordered() {
        assert_eq!(parse_range("3..7").unwrap(), (3, 7));
        for bad in ["7..3", "3..3", "a..b", "3", "-1..2"] {
            assert!(parse_range(bad).is_err(), "{bad}");
        }
        let e = parse_range("9007199254740990..9007199254740993").unwrap_err();
        assert!(e.to_string().contains("pass indices end at"), "{e}");
        assert!(parse_range(&format!("0..{MAX_PASS_END}")).is_ok());
    }
}
