//! Range and reference checks on a scene description, before anything heavy is allocated:
//! the sections without kinds here, each kind of light, shape, material and the camera beside
//! its own description.

use super::check::{Checker, Names, Problem};
use super::desc::{FilmDesc, SceneDesc};
use super::loaded::LoadedScene;
use crate::film::output::Exposure;
use crate::integrator::VolumeKind;
use crate::spectrum::MAX_BINS;

pub fn validate(scene: &LoadedScene) -> Vec<Problem> {
    let d = &scene.desc;
    let names = Names {
        spectra: &d.spectra,
        materials: d.materials.keys().map(String::as_str).collect(),
        media: d.media.keys().map(String::as_str).collect(),
    };
    let mut c = Checker::new(scene.source(), names);
    film(&mut c, &d.film);
    let film_ok = c.problems.is_empty();
    d.camera.check(&mut c, "camera");
    d.integrator.check(|k, m| c.fail(k, m));
    // Integration volumes are boxed in f32 like shapes: a radius of 1e20 m overflowed the
    // gather BVH's build (a stack overflow, or obvhs indexing out of bounds).
    if let Some(r) = d.integrator.radius.value() {
        c.within_geometry("integrator.radius", r);
    }
    if let Some(r) = d.integrator.radius_indirect_value() {
        c.within_geometry("integrator.radius_indirect", r);
    }
    for (name, s) in &d.spectra {
        c.named_spectrum(&format!("spectra.{name}"), s);
    }
    for (name, m) in &d.materials {
        m.check(&mut c, &format!("materials.{name}"));
    }
    super::materials::check_blends(&mut c, &d.materials);
    media(&mut c, d);
    for (i, s) in d.shapes.iter().enumerate() {
        s.check(&mut c, &format!("shapes.{i}"));
    }
    for (i, l) in d.lights.iter().enumerate() {
        l.check(&mut c, &format!("lights.{i}"));
    }
    // Lines the spectral grid cannot hold (outside the range, too many bins); a line already
    // refused at its key (not a wavelength) is not reported twice.
    if film_ok
        && let Err(p) = super::lines::scene_grid(d)
        && !c.problems.iter().any(|q| q.key == p.key)
    {
        c.problems.push(p);
    }
    super::sensors::check_all(&mut c, &d.sensors, (d.camera.width, d.camera.height));
    if c.problems.is_empty() {
        gather_budget(&mut c, d);
    }
    c.problems
}

/// A gather budget that cannot hold one camera path's records (a tiny q) is refused here, before
/// anything is built or rendered, with the estimate (issue 31).
fn gather_budget(c: &mut Checker, d: &SceneDesc) {
    let bins = super::lines::scene_grid(d).map_or(d.film.bins, |g| g.n);
    let size = (d.camera.width, d.camera.height);
    let est =
        crate::integrator::MemoryEstimate::new(&d.integrator, size, bins, !d.media.is_empty());
    if let Some(m) = est.path_over_budget(&d.integrator) {
        let key = match d.integrator.q.value() {
            Some(_) => "integrator.q",
            None => "integrator.max_gather_bytes",
        };
        c.fail(key, m);
    }
}

fn film(c: &mut Checker, f: &FilmDesc) {
    if !(1..=MAX_BINS).contains(&f.bins) {
        c.fail(
            "film.bins",
            format!("must be in 1..={MAX_BINS}, got {}", f.bins),
        );
    }
    c.range(
        "film.lambda_min",
        f.lambda_min,
        200.0,
        2000.0,
        "in [200, 2000] nm",
    );
    c.range(
        "film.lambda_max",
        f.lambda_max,
        200.0,
        2000.0,
        "in [200, 2000] nm",
    );
    if f.lambda_max <= f.lambda_min {
        c.fail("film.lambda_max", "must be greater than film.lambda_min");
    }
    if let Some(Exposure::Stops(e)) = f.exposure {
        c.range(
            "film.exposure",
            e as f64,
            -64.0,
            64.0,
            "in [-64, 64] stops (or \"auto\")",
        );
    }
    if let Some([lo, hi]) = f.false_colour_range
        && !(lo > 0.0 && hi > lo && hi.is_finite())
    {
        c.fail(
            "film.false_colour_range",
            format!("must be [low, high] cd/m² with 0 < low < high, got [{lo}, {hi}]"),
        );
    }
    for (i, o) in f.outputs.iter().enumerate() {
        if crate::film::output::format_of(std::path::Path::new(o)).is_err() {
            c.fail(
                format!("film.outputs.{i}"),
                format!("`{o}`: use a .exr or .png extension"),
            );
        }
    }
}

// Media are validated as before (their description is being reworked separately).
fn media(c: &mut Checker, d: &SceneDesc) {
    for (name, m) in &d.media {
        let key = format!("media.{name}");
        if let Some(s) = &m.sigma_s {
            c.spectrum_ref(&format!("{key}.sigma_s"), s);
        }
        c.spectrum_ref(&format!("{key}.sigma_a"), &m.sigma_a);
        let source = c.source;
        for (k, message) in m.check(&|f| source.resolve(f).is_file()) {
            let at = if k.is_empty() {
                key.clone()
            } else {
                format!("{key}.{k}")
            };
            c.fail(at, message);
        }
        let tracked = matches!(
            m.tracking,
            Some(crate::medium::Tracking::Delta | crate::medium::Tracking::DeltaGlobal)
        );
        if m.density.is_some() && tracked && d.integrator.volume != VolumeKind::Spheres {
            // The cylinders' gather weights integrate the camera's transmittance along the
            // axis, which needs the optical depth at every point of it: the exact transport
            // has it, null-collision tracking only estimates it at the points it visits.
            c.fail(
                "integrator.volume",
                format!(
                    "{key}.tracking: cylinders integrate the camera's transmittance along their \
                     axis, which needs the optical depth at every point of it; delta tracking \
                     only estimates it at the points it visits. Use `volume = \"spheres\"` or \
                     `tracking = \"exact\"` (docs/media.md)"
                ),
            );
        }
    }
    if let Some(m) = &d.medium {
        c.medium("medium", m);
    }
}
