use std::process::ExitCode;

use super::{InfoArgs, SceneArgs};

pub fn run(args: &InfoArgs) -> anyhow::Result<ExitCode> {
    if args.json {
        let scene = brume::scene::load(&args.scene.scene, &args.scene.sets)?;
        let (value, _) = brume::scene::info::info_json(&scene)?;
        outln!("{}", serde_json::to_string_pretty(&value)?)?;
        return Ok(ExitCode::SUCCESS);
    }
    text(&args.scene)
}

fn text(args: &SceneArgs) -> anyhow::Result<ExitCode> {
    let scene = brume::scene::load(&args.scene, &args.sets)?;
    // The summary first (it builds each medium on its own, so a medium is described even when
    // something else in the scene fails); then building reads every texture, mesh and
    // spectrum file, so info reports their errors too.
    let s = brume::scene::summary::summarise(&scene);
    out!("{s}")?;
    let (built, warnings) = brume::scene::build_with_warnings(&scene)?;
    let names: Vec<&str> = scene.desc.media.keys().map(String::as_str).collect();
    for line in brume::scene::density_report::density_report(&built, &names) {
        outln!("{line}")?;
    }
    // The radius "auto" resolves to, and any radius in pixel footprints (the unit the
    // auto rule and the studies of docs/performance.md use).
    let footprint = brume::integrator::radius::pixel_footprint(&built.camera, &built.geometry);
    let integrator = brume::scene::build_integrator(&scene, &built)?;
    let r0 = integrator.radius.r0;
    outln!(
        "radius:       {r0:.5} m = {:.2} x the median pixel footprint ({footprint:.5} m)",
        r0 / footprint
    )?;
    let schedule = match integrator.radius.shrink {
        brume::integrator::Shrink::Fixed => "fixed (every pass)".to_string(),
        brume::integrator::Shrink::Progressive { alpha } => {
            format!("progressive, alpha {alpha} (R^2 x (p + alpha) / (p + 1) each pass)")
        }
        brume::integrator::Shrink::Consistent { after } => format!(
            "consistent: fixed for {after} passes, then x (n / {after})^(-1/6) at pass n \
             (0.5 x at {} passes)",
            after.saturating_mul(64)
        ),
    };
    outln!("radius schedule: {schedule}")?;
    if integrator.indirect_scale != 1.0 {
        let ri = integrator.radii(0).indirect;
        outln!(
            "radius_indirect: {ri:.5} m = {:.2} x the median pixel footprint",
            ri / footprint
        )?;
    }
    for w in &warnings {
        eprintln!("brume: warning: {w}");
    }
    Ok(ExitCode::SUCCESS)
}
