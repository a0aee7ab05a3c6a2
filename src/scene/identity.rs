//! What a render of a loaded scene is and what its outputs hold: the film identity (`FilmId`)
//! and the output settings recorded in it. The command line and the Python package both call
//! these, so a film or image written by either is the same bytes.

use std::ops::Range;
use std::path::Path;

use crate::film::output::OutputOptions;
use crate::film::{Blend, Film, FilmId, IdentityError, Mismatch, Sampling};
use crate::integrator::{IntegratorDesc, Shrink};

use super::desc::FilmDesc;
use super::loaded::LoadedScene;

/// Extension of film files (checkpoints and parts).
pub const FILM_EXT: &str = "brume";

/// Whether `p` names a film file (`.brume`, any case) rather than an image.
pub fn is_film_path(p: &Path) -> bool {
    p.extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case(FILM_EXT))
}

/// The identity of rendering `scene` with `seed` on this machine: the description, and the
/// gather budget the renderer will resolve `integrator.max_gather_bytes` to (the same call).
pub fn film_id(scene: &LoadedScene, seed: u64) -> Result<FilmId, IdentityError> {
    let budget = scene.desc.integrator.gather_budget() as u64;
    let sampling = Sampling {
        gather_budget: budget,
        machine_memory: machine_memory().unwrap_or(0),
        version: env!("CARGO_PKG_VERSION").to_string(),
    };
    FilmId::new(&scene.desc, seed, sampling)
}

/// Total memory of this machine in bytes, when the system says (Linux).
pub fn machine_memory() -> Option<u64> {
    let info = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = info.lines().find(|l| l.starts_with("MemTotal:"))?;
    let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib * 1024)
}

/// A film file whose recorded `[film]` table cannot be read back.
#[derive(Debug, thiserror::Error)]
#[error("the film file's output settings are unreadable: {0}")]
pub struct FilmSettingsError(#[from] serde_json::Error);

/// The `[film]` table recorded in a film's identity.
pub fn film_desc(id: &FilmId) -> Result<FilmDesc, FilmSettingsError> {
    let film = id.section("film").cloned().unwrap_or_default();
    Ok(serde_json::from_value(film)?)
}

/// The output settings of a film's images: the scene's `[film]` table, the automatic
/// settings' choice (`Film::auto_settings`, `Choice::report`) as the EXR attribute
/// `brumeAutoSettings` when the render made one, and the blend of the two radii for scattered
/// light (`Film::blend`) as `brumeRadiusBlend` when the film has one.
pub fn output_options(id: &FilmId, film: &Film) -> Result<OutputOptions, FilmSettingsError> {
    let mut opts = film_desc(id)?.output_options();
    if !film.auto_settings.is_empty() {
        opts.attributes
            .push(("brumeAutoSettings".into(), film.auto_settings.join("; ")));
    }
    if let Some(b) = film.blend() {
        opts.attributes
            .push(("brumeRadiusBlend".into(), blend_report(&b)));
    }
    Ok(opts)
}

/// The blend of a film's two radii for scattered light, as `--verbose` and the EXR attribute
/// `brumeRadiusBlend` report it.
pub fn blend_report(b: &Blend) -> String {
    format!(
        "the direct radius's weight for scattered light {:.4} (blur {:.4e}, noise {:.4e}, \
         covariance {:.4e}: the sums over pixels and bins that choose it)",
        b.w, b.blur, b.noise, b.cross
    )
}

/// Why `memory_check` refuses a render.
#[derive(Debug, thiserror::Error)]
pub enum MemoryCheckError {
    /// The scene's spectral grid is invalid (the film's bins cannot be counted).
    #[error(transparent)]
    Scene(#[from] super::SceneError),
    /// The memory estimate exceeds the machine's memory (the sizes, formatted).
    #[error(
        "the render needs about {needs} (film {film}, gather {gather} per tile) but the machine \
         has {has}; lower camera.width/height or film.bins"
    )]
    Over {
        needs: String,
        film: String,
        gather: String,
        has: String,
    },
}

/// Refuses a render of `scene` whose memory estimate (`MemoryEstimate`, the figures
/// `brume info` prints) exceeds this machine's memory; Ok where the system does not say how
/// much it has. The command line and the Python package both check it before rendering.
pub fn memory_check(scene: &LoadedScene) -> Result<(), MemoryCheckError> {
    let Some(ram) = machine_memory() else {
        return Ok(());
    };
    let desc = &scene.desc;
    // Every bin the film holds, a narrow one per spectral line included.
    let bins = scene.grid()?.n;
    let est = crate::integrator::MemoryEstimate::new(
        &desc.integrator,
        (desc.camera.width, desc.camera.height),
        bins,
        !desc.media.is_empty(),
    );
    let ram = ram as f64;
    if est.total() > ram {
        let f = crate::integrator::format_bytes;
        return Err(MemoryCheckError::Over {
            needs: f(est.total()),
            film: f(est.film_bytes),
            gather: f(est.gather_held()),
            has: f(ram),
        });
    }
    Ok(())
}

/// The keys of the radius schedule. Films that differ only in them are of one render over
/// the passes where both schedules keep the starting radius.
const SCHEDULE_KEYS: [&str; 2] = ["integrator.radius_schedule", "integrator.shrink_after"];

/// The radius schedule a film's description records. A film from before the schedule keys
/// (no `integrator.shrink_after` recorded) kept its starting radius at every pass when
/// `alpha` was 1: its schedule is fixed, not today's default.
fn recorded_shrink(id: &FilmId) -> Option<Shrink> {
    let recorded = id.section("integrator")?;
    let desc: IntegratorDesc = serde_json::from_value(recorded.clone()).ok()?;
    if desc.alpha >= 1.0 && recorded.get("shrink_after").is_none() {
        return Some(Shrink::Fixed);
    }
    Some(desc.shrink())
}

/// `Ok` when the film `ours` continues or completes the film `reference` exactly (as
/// [`FilmId::check`]), where `passes` are the pass indices whose sums the two films share or
/// hand on (a resumed checkpoint's, or the union of two parts' ranges). Films whose radius
/// schedules differ (another `radius_schedule` or `shrink_after`, or a film written before
/// those keys existed) are of one render when every one of those passes has the starting
/// radius under both schedules: their sums are then the same bits. A film of 300 passes at a
/// fixed radius is refused by a render whose radius shrinks from pass 256, naming the key.
pub fn same_render(ours: &FilmId, reference: &FilmId, passes: Range<u64>) -> Result<(), Mismatch> {
    let agree = match (recorded_shrink(ours), recorded_shrink(reference)) {
        (Some(a), Some(b)) => {
            a == b || passes.end <= a.unchanged_passes().min(b.unchanged_passes())
        }
        _ => false,
    };
    if agree {
        ours.check_except(reference, &SCHEDULE_KEYS)
    } else {
        ours.check(reference)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    fn id(integrator: serde_json::Value) -> FilmId {
        let sampling = Sampling {
            gather_budget: 1,
            machine_memory: 0,
            version: "t".into(),
        };
        let desc = json!({ "integrator": integrator, "film": { "bins": 8 } });
        FilmId::new(&desc, 3, sampling).unwrap()
    }

    fn key_named(r: Result<(), Mismatch>, key: &str) -> bool {
        matches!(r, Err(Mismatch::Settings(d)) if d.iter().any(|d| d.key == key))
    }

    /// A film from before the schedule keys (fixed radius) joins today's default render
    /// while every pass it holds is before the shrink starts, and any render that asks for
    /// the fixed schedule; past the onset it is refused, naming the key.
    #[test]
    fn films_before_the_schedule_keys_are_fixed_radius_films() {
        let legacy = id(json!({ "alpha": 1.0, "q": 0.5 }));
        let today = id(json!({ "alpha": 1.0, "q": 0.5, "shrink_after": 256 }));
        let fixed = id(json!({
            "alpha": 1.0, "q": 0.5, "shrink_after": 256, "radius_schedule": "fixed"
        }));
        assert_eq!(recorded_shrink(&legacy), Some(Shrink::Fixed));
        assert_eq!(
            recorded_shrink(&today),
            Some(Shrink::Consistent { after: 256 })
        );
        assert_eq!(same_render(&legacy, &today, 0..256), Ok(()));
        assert_eq!(same_render(&today, &legacy, 100..256), Ok(()));
        assert!(key_named(
            same_render(&legacy, &today, 0..257),
            "integrator.shrink_after"
        ));
        assert_eq!(same_render(&legacy, &fixed, 0..100_000), Ok(()));
        // Other keys are still compared.
        let other_q = id(json!({ "alpha": 1.0, "q": 0.25, "shrink_after": 256 }));
        assert!(key_named(
            same_render(&legacy, &other_q, 0..10),
            "integrator.q"
        ));
    }

    /// Two consistent schedules agree before the earlier onset; a progressive one only on
    /// pass 0.
    #[test]
    fn schedules_agree_before_either_shrinks() {
        let a = id(json!({ "alpha": 1.0, "shrink_after": 64 }));
        let b = id(json!({ "alpha": 1.0, "shrink_after": 256 }));
        assert_eq!(same_render(&a, &b, 0..64), Ok(()));
        assert!(same_render(&a, &b, 0..65).is_err());
        let p = id(json!({ "alpha": 0.7, "shrink_after": 256 }));
        let p_later = id(json!({ "alpha": 0.7, "shrink_after": 64 }));
        assert_eq!(same_render(&p, &p_later, 0..1000), Ok(()));
        assert!(key_named(same_render(&p, &b, 0..1), "integrator.alpha"));
    }
}
