use std::process::ExitCode;

use super::SceneArgs;

pub fn run(args: &SceneArgs) -> anyhow::Result<ExitCode> {
    let scene = brume::scene::load(&args.scene, &args.sets)?;
    // The summary first (it builds each medium on its own, so a medium is described even when
    // something else in the scene fails); then building reads every texture, mesh and
    // spectrum file, so info reports their errors too.
    let s = brume::scene::summary::summarise(&scene);
    print!("{s}");
    let (_, warnings) = brume::scene::build_with_warnings(&scene)?;
    for w in &warnings {
        eprintln!("brume: warning: {w}");
    }
    Ok(ExitCode::SUCCESS)
}
