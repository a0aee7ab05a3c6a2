//! Scene text -> load (parse, overrides, validation) -> build: any input must give a scene or
//! an error, never a panic, a hang or an unbounded allocation.
#![no_main]

use std::path::Path;

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    // Relative paths (textures, meshes) resolve from brume's scenes folder.
    let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes/fuzz.toml");
    if let Ok(loaded) = brume::scene::load_str(text, &file, &[]) {
        let _ = brume::scene::build(&loaded);
    }
});
