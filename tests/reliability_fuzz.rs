//! The fuzz target's entry point (scene text -> load -> build, see fuzz/) as a bounded property
//! test: mutated scene files and overrides give a scene or an error, never a panic.

use std::path::{Path, PathBuf};

use proptest::prelude::*;

fn corpus() -> Vec<String> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("fuzz/corpus/scene");
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap()
        .filter_map(|e| e.ok().map(|e| e.path()))
        .collect();
    files.sort();
    files
        .iter()
        .map(|p| std::fs::read_to_string(p).unwrap())
        .collect()
}

fn scene_file() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/fuzz.toml")
}

/// The fuzz target's body.
fn load_and_build(text: &str, sets: &[String]) {
    if let Ok(loaded) = brume::scene::load_str(text, &scene_file(), sets) {
        let _ = brume::scene::build(&loaded);
    }
}

const KEYS: &[&str] = &[
    "camera.width",
    "camera.height",
    "camera.fov",
    "camera.position",
    "camera.up",
    "film.bins",
    "film.lambda_min",
    "film.lambda_max",
    "integrator.q",
    "integrator.radius",
    "integrator.alpha",
    "integrator.volume",
    "integrator.camera_samples",
    "media.fog.g",
    "media.fog.sigma_s",
    "media.fog.sigma_a",
    "lights.0.direction",
    "lights.0.irradiance",
    "shapes.0.size",
    "shapes.0.transform.scale",
    "materials.wall.albedo",
    "materials.wall.texture",
    "materials.floor.weight",
    "materials.coat.texture.wrap",
    "lights.0.type",
];

const VALUES: &[&str] = &[
    "0",
    "-1",
    "1",
    "1e-45",
    "1e38",
    "nan",
    "inf",
    "-inf",
    "0.999999",
    "-0.999999",
    "65",
    "4294967295",
    "18446744073709551615",
    "\"\"",
    "\"cylinder-long\"",
    "\"../../../../etc/passwd\"",
    "[0, 0, 0]",
    "[1e30, -1e30, nan]",
    "[]",
    "{}",
    "true",
    "\"D65\"",
];

const SNIPPETS: &[&str] = &[
    "[[shapes]]\n",
    "[media.x]\n",
    "type = \"mesh\"\n",
    "= [",
    "]]",
    "\"",
    "\n",
    "#",
    "\u{0}",
    "1e999",
    "{ translate = [",
    "interior = \"nope\"\n",
];

proptest! {
    #![proptest_config(ProptestConfig { cases: 400, failure_persistence: None, ..ProptestConfig::default() })]

    #[test]
    fn mutated_scenes_never_panic(
        which in 0usize..16,
        cut in (0usize..4096, 0usize..64),
        insert in (0usize..4096, 0usize..SNIPPETS.len()),
        sets in proptest::collection::vec((0usize..KEYS.len(), 0usize..VALUES.len()), 0..4),
    ) {
        let corpus = corpus();
        let mut text = corpus[which % corpus.len()].clone().into_bytes();
        let at = cut.0 % (text.len() + 1);
        let end = (at + cut.1).min(text.len());
        text.drain(at..end);
        let at = insert.0 % (text.len() + 1);
        text.splice(at..at, SNIPPETS[insert.1].bytes());
        let text = String::from_utf8_lossy(&text).into_owned();
        let sets: Vec<String> = sets.iter().map(|(k, v)| format!("{}={}", KEYS[*k], VALUES[*v])).collect();
        load_and_build(&text, &sets);
    }

    #[test]
    fn arbitrary_text_never_panics(text in "\\PC{0,300}") {
        load_and_build(&text, &[]);
    }
}

#[test]
fn the_corpus_loads() {
    for text in corpus() {
        let loaded = brume::scene::load_str(&text, &scene_file(), &[]).expect("corpus scene loads");
        brume::scene::build(&loaded).expect("corpus scene builds");
    }
}
