use std::process::ExitCode;

use super::SceneArgs;

pub fn run(args: &SceneArgs) -> anyhow::Result<ExitCode> {
    let scene = brume::scene::load(&args.scene, &args.sets)?;
    // Building reads every texture, mesh and spectrum file: info reports their errors too.
    let (_, warnings) = brume::scene::build_with_warnings(&scene)?;
    for w in &warnings {
        eprintln!("brume: warning: {w}");
    }
    let s = brume::scene::summary::summarise(&scene);
    print!("{s}");
    Ok(ExitCode::SUCCESS)
}
