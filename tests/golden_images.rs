//! Bit-exact regression: every scene in scenes/ with every estimator and gather mode, rendered
//! tiny at a fixed seed, hashes to the value recorded before the estimator-architecture refactor
//! (issue 14). A refactor must not change a single bit; a change of the algorithms updates the
//! table on purpose and says why in its commit.
//!
//! The hash covers the image and both component layers (f32 bits, from the film's exact integer
//! sums), so any change in sampling, weights or sum order shows.

use brume::integrator::{Budget, Renderer};

/// FNV-1a over bytes (stable across Rust versions, unlike `DefaultHasher`).
fn fnv(bytes: impl IntoIterator<Item = u8>) -> u64 {
    let mut h = 0xcbf2_9ce4_8422_2325u64;
    for b in bytes {
        h ^= b as u64;
        h = h.wrapping_mul(0x0100_0000_01b3);
    }
    h
}

const ESTIMATORS: [(&str, &[&str]); 5] = [
    (
        "spheres-q1",
        &["integrator.volume=\"spheres\"", "integrator.q=1.0"],
    ),
    (
        "spheres-q0.1",
        &["integrator.volume=\"spheres\"", "integrator.q=0.1"],
    ),
    ("cylinder", &["integrator.volume=\"cylinder\""]),
    (
        "cylinder-truncated",
        &["integrator.volume=\"cylinder-truncated\""],
    ),
    ("cylinder-long", &["integrator.volume=\"cylinder-long\""]),
];

const MODES: [&str; 2] = ["first-extinction", "see-through"];

/// Settings that pin the paper's pure method and a tiny, fast render.
const COMMON: [&str; 6] = [
    "integrator.direct=\"photons\"",
    "camera.width=16",
    "camera.height=12",
    "integrator.forward_rays=3000",
    "integrator.camera_samples=1",
    "integrator.max_gather_bytes=100000000",
];

fn render_hash(scene: &std::path::Path, sets: &[String]) -> u64 {
    let loaded = brume::scene::load(scene, sets).unwrap_or_else(|e| panic!("{e}"));
    let built = brume::scene::build(&loaded).unwrap_or_else(|e| panic!("{e}"));
    let integrator =
        brume::scene::build_integrator(&loaded, &built).unwrap_or_else(|e| panic!("{e}"));
    let mut r = Renderer::new(&built, integrator, 11);
    r.run(Budget::Passes(2), |_, _| {});
    let img = r.image();
    let words = img
        .data
        .iter()
        .chain(img.layers.iter().flat_map(|(_, l)| l))
        .flat_map(|v| v.to_bits().to_le_bytes());
    fnv(words)
}

/// (scene, estimator, mode, hash) recorded on main at a4b5773, before issue 14.
const GOLDEN: &[(&str, &str, &str, u64)] = &[
    (
        "chromatic-fog",
        "spheres-q1",
        "first-extinction",
        0x32f96fa249dc91d5,
    ),
    (
        "chromatic-fog",
        "spheres-q1",
        "see-through",
        0xcf93899dc956e581,
    ),
    (
        "chromatic-fog",
        "spheres-q0.1",
        "first-extinction",
        0xdfeb1c12cd675111,
    ),
    (
        "chromatic-fog",
        "spheres-q0.1",
        "see-through",
        0xc1254493e23fcec9,
    ),
    (
        "chromatic-fog",
        "cylinder",
        "first-extinction",
        0xb20e72f1cb696b43,
    ),
    (
        "chromatic-fog",
        "cylinder",
        "see-through",
        0xcdadb26083bca3aa,
    ),
    (
        "chromatic-fog",
        "cylinder-truncated",
        "first-extinction",
        0x04c80f2bd73e5a87,
    ),
    (
        "chromatic-fog",
        "cylinder-truncated",
        "see-through",
        0xb4a547c7673709be,
    ),
    (
        "chromatic-fog",
        "cylinder-long",
        "first-extinction",
        0x517cf49c97c98bca,
    ),
    (
        "chromatic-fog",
        "cylinder-long",
        "see-through",
        0x92c00c579cd0d087,
    ),
    (
        "colour-checker",
        "spheres-q1",
        "first-extinction",
        0xaaf34b1bdea9fdc1,
    ),
    (
        "colour-checker",
        "spheres-q1",
        "see-through",
        0xaaf34b1bdea9fdc1,
    ),
    (
        "colour-checker",
        "spheres-q0.1",
        "first-extinction",
        0xaaf34b1bdea9fdc1,
    ),
    (
        "colour-checker",
        "spheres-q0.1",
        "see-through",
        0xaaf34b1bdea9fdc1,
    ),
    (
        "colour-checker",
        "cylinder",
        "first-extinction",
        0xaaf34b1bdea9fdc1,
    ),
    (
        "colour-checker",
        "cylinder",
        "see-through",
        0xaaf34b1bdea9fdc1,
    ),
    (
        "colour-checker",
        "cylinder-truncated",
        "first-extinction",
        0xaaf34b1bdea9fdc1,
    ),
    (
        "colour-checker",
        "cylinder-truncated",
        "see-through",
        0xaaf34b1bdea9fdc1,
    ),
    (
        "colour-checker",
        "cylinder-long",
        "first-extinction",
        0xaaf34b1bdea9fdc1,
    ),
    (
        "colour-checker",
        "cylinder-long",
        "see-through",
        0xaaf34b1bdea9fdc1,
    ),
    (
        "fog-cube",
        "spheres-q1",
        "first-extinction",
        0x14abff6083bacc51,
    ),
    ("fog-cube", "spheres-q1", "see-through", 0x5806e11bebebfc81),
    (
        "fog-cube",
        "spheres-q0.1",
        "first-extinction",
        0xe8b923b5e3db6f24,
    ),
    (
        "fog-cube",
        "spheres-q0.1",
        "see-through",
        0xb8fa7aedffd8a945,
    ),
    (
        "fog-cube",
        "cylinder",
        "first-extinction",
        0x353f61efbd8acd56,
    ),
    ("fog-cube", "cylinder", "see-through", 0xcf72bfa623fadbe3),
    (
        "fog-cube",
        "cylinder-truncated",
        "first-extinction",
        0x3a8bd5b3f62b967a,
    ),
    (
        "fog-cube",
        "cylinder-truncated",
        "see-through",
        0x01facf9c300e0973,
    ),
    (
        "fog-cube",
        "cylinder-long",
        "first-extinction",
        0xe84f6f2ea9d1afcc,
    ),
    (
        "fog-cube",
        "cylinder-long",
        "see-through",
        0x8154f85dbffe3639,
    ),
    (
        "fog-room-laser",
        "spheres-q1",
        "first-extinction",
        0x0d89cbd9b73f795a,
    ),
    (
        "fog-room-laser",
        "spheres-q1",
        "see-through",
        0x3da365cb7a03082f,
    ),
    (
        "fog-room-laser",
        "spheres-q0.1",
        "first-extinction",
        0x0392db73a850ccaf,
    ),
    (
        "fog-room-laser",
        "spheres-q0.1",
        "see-through",
        0x564925f193b45ac4,
    ),
    (
        "fog-room-laser",
        "cylinder",
        "first-extinction",
        0x84e0b507d7333efa,
    ),
    (
        "fog-room-laser",
        "cylinder",
        "see-through",
        0x215484daccd9db77,
    ),
    (
        "fog-room-laser",
        "cylinder-truncated",
        "first-extinction",
        0x1c2ecfe36377e791,
    ),
    (
        "fog-room-laser",
        "cylinder-truncated",
        "see-through",
        0xf92b5b405a94a379,
    ),
    (
        "fog-room-laser",
        "cylinder-long",
        "first-extinction",
        0x1a6d7a0335cee344,
    ),
    (
        "fog-room-laser",
        "cylinder-long",
        "see-through",
        0xa1a746c362da13ef,
    ),
    (
        "glass-sphere-fog",
        "spheres-q1",
        "first-extinction",
        0x49a782caadd23715,
    ),
    (
        "glass-sphere-fog",
        "spheres-q1",
        "see-through",
        0x95c01690f240ad1f,
    ),
    (
        "glass-sphere-fog",
        "spheres-q0.1",
        "first-extinction",
        0xd356a5e3a1fa85e6,
    ),
    (
        "glass-sphere-fog",
        "spheres-q0.1",
        "see-through",
        0x11474e702ef8043f,
    ),
    (
        "glass-sphere-fog",
        "cylinder",
        "first-extinction",
        0x115e996cd4b3cef2,
    ),
    (
        "glass-sphere-fog",
        "cylinder",
        "see-through",
        0xebe424561a9f2388,
    ),
    (
        "glass-sphere-fog",
        "cylinder-truncated",
        "first-extinction",
        0xc0e5db80e75848f2,
    ),
    (
        "glass-sphere-fog",
        "cylinder-truncated",
        "see-through",
        0x52c39ee2c69b0062,
    ),
    (
        "glass-sphere-fog",
        "cylinder-long",
        "first-extinction",
        0x3f5f0724d4bb3682,
    ),
    (
        "glass-sphere-fog",
        "cylinder-long",
        "see-through",
        0x7a66aea86b0d0814,
    ),
    (
        "translucent-plate",
        "spheres-q1",
        "first-extinction",
        0xe2cdfc6b628a2226,
    ),
    (
        "translucent-plate",
        "spheres-q1",
        "see-through",
        0x486d7e8d339778f9,
    ),
    (
        "translucent-plate",
        "spheres-q0.1",
        "first-extinction",
        0xabf9e9de599d9a04,
    ),
    (
        "translucent-plate",
        "spheres-q0.1",
        "see-through",
        0xf691904e8692594b,
    ),
    (
        "translucent-plate",
        "cylinder",
        "first-extinction",
        0xe8f76f9240087a14,
    ),
    (
        "translucent-plate",
        "cylinder",
        "see-through",
        0x65b021619a168857,
    ),
    (
        "translucent-plate",
        "cylinder-truncated",
        "first-extinction",
        0x38a612fc4d2ee791,
    ),
    (
        "translucent-plate",
        "cylinder-truncated",
        "see-through",
        0x209ea75ce7e589fe,
    ),
    (
        "translucent-plate",
        "cylinder-long",
        "first-extinction",
        0xc308b4af4e4f58fd,
    ),
    (
        "translucent-plate",
        "cylinder-long",
        "see-through",
        0x942e7af799f30667,
    ),
];

#[test]
fn every_scene_and_estimator_is_bit_identical_to_the_recorded_images() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes");
    let mut files: Vec<_> = std::fs::read_dir(&dir)
        .expect("scenes/ exists")
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    files.sort();
    let mut got = Vec::new();
    for f in &files {
        let name = f.file_stem().unwrap().to_string_lossy().into_owned();
        for (est, est_sets) in ESTIMATORS {
            for mode in MODES {
                let mut sets: Vec<String> = COMMON.iter().map(|s| s.to_string()).collect();
                sets.extend(est_sets.iter().map(|s| s.to_string()));
                sets.push(format!("integrator.mode=\"{mode}\""));
                got.push((name.clone(), est, mode, render_hash(f, &sets)));
            }
        }
    }
    let table: String = got
        .iter()
        .map(|(s, e, m, h)| format!("    (\"{s}\", \"{e}\", \"{m}\", 0x{h:016x}),\n"))
        .collect();
    eprintln!("{table}");
    let mut wrong = Vec::new();
    for (s, e, m, want) in GOLDEN {
        match got
            .iter()
            .find(|(gs, ge, gm, _)| gs == s && ge == e && gm == m)
        {
            Some((.., h)) if h == want => {}
            Some((.., h)) => wrong.push(format!("{s} {e} {m}: 0x{h:016x}, recorded 0x{want:016x}")),
            None => wrong.push(format!("{s} {e} {m}: not rendered")),
        }
    }
    assert!(!GOLDEN.is_empty(), "no recorded hashes");
    assert!(wrong.is_empty(), "images changed:\n{}", wrong.join("\n"));
}
