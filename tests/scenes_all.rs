//! Every scene in scenes/ loads, validates, builds and renders at a tiny size with finite pixels.

use brume::integrator::{Budget, Renderer};

#[test]
fn every_scene_builds_and_renders_tiny() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes");
    let mut files: Vec<_> = std::fs::read_dir(&dir)
        .expect("scenes/ exists")
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    files.sort();
    // The scenes issue 7 asks for must all be there.
    for want in [
        "fog-cube",
        "fog-room-laser",
        "chromatic-fog",
        "translucent-plate",
        "glass-sphere-fog",
        "colour-checker",
    ] {
        assert!(
            files
                .iter()
                .any(|f| f.file_stem().is_some_and(|s| s == want)),
            "scenes/{want}.toml missing"
        );
    }
    let sets: Vec<String> = [
        "camera.width=12",
        "camera.height=8",
        "integrator.forward_rays=3000",
    ]
    .iter()
    .map(|s| s.to_string())
    .collect();
    for f in &files {
        let loaded = brume::scene::load(f, &sets).unwrap_or_else(|e| panic!("{e}"));
        let scene = brume::scene::build(&loaded).unwrap_or_else(|e| panic!("{e}"));
        let integrator =
            brume::scene::build_integrator(&loaded, &scene).unwrap_or_else(|e| panic!("{e}"));
        let mut r = Renderer::new(&scene, integrator, 7);
        r.run(Budget::Passes(1), |_, _| {});
        let img = r.image();
        assert_eq!(img.data.len(), 12 * 8 * scene.grid.n);
        assert!(
            img.data.iter().all(|v| v.is_finite() && *v >= 0.0),
            "{}: non-finite or negative pixel",
            f.display()
        );
        assert!(
            img.data.iter().any(|v| *v > 0.0),
            "{}: the image is black",
            f.display()
        );
        eprintln!("{}: ok", f.display());
    }
}
