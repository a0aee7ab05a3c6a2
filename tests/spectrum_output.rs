//! Film output: atomic writing, errors, and the EXR's values read back.

use brume::colour::{ColourSpace, FilmToRgb, Observer};
use brume::film::SpectralImage;
use brume::film::output::{OutputError, OutputOptions, spectral_channel_name, write};
use brume::spectrum::SpectralGrid;

fn image() -> SpectralImage {
    let g = SpectralGrid::new(8, 380.0, 780.0);
    let mut img = SpectralImage::new(3, 2, g);
    for (k, v) in img.data.iter_mut().enumerate() {
        *v = (k % 7) as f32 * 0.25;
    }
    img
}

#[test]
fn channel_names_follow_the_spectral_layout() {
    assert_eq!(spectral_channel_name(550.0), "S0.550,000000nm");
    assert_eq!(spectral_channel_name(392.5), "S0.392,500000nm");
}

#[test]
fn writes_exr_and_png_without_leaving_temporaries() {
    let dir = tempfile::tempdir().unwrap();
    let img = image();
    let opts = OutputOptions {
        spectral_layers: true,
        ..Default::default()
    };
    for name in ["a.exr", "a.png"] {
        write(&dir.path().join(name), &img, &opts).unwrap();
    }
    let mut names: Vec<_> = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .collect();
    names.sort();
    assert_eq!(names, ["a.exr", "a.png"]);

    // Read the EXR back: RGB equals the film-to-RGB conversion of each pixel.
    use exr::prelude::*;
    let read = read()
        .no_deep_data()
        .largest_resolution_level()
        .all_channels()
        .all_layers()
        .all_attributes()
        .from_file(dir.path().join("a.exr"))
        .unwrap();
    let layer = &read.layer_data[0];
    let conv = FilmToRgb::new(
        ColourSpace::Srgb,
        Observer::Cie1931,
        &img.grid,
        Default::default(),
    )
    .unwrap();
    let get = |name: &str| {
        let c = layer
            .channel_data
            .list
            .iter()
            .find(|c| c.name.to_string() == name)
            .unwrap();
        match &c.sample_data {
            FlatSamples::F32(v) => v.clone(),
            _ => panic!("expected f32"),
        }
    };
    let r = get("R");
    let s0 = get(&spectral_channel_name(img.grid.centre(0)));
    for p in 0..6 {
        let want = conv.rgb(&img.data[p * 8..p * 8 + 8]);
        assert!((r[p] - want[0]).abs() < 1e-6);
        assert_eq!(s0[p], img.data[p * 8]);
    }
}

#[test]
fn bad_extension_and_bad_sizes_are_errors() {
    let dir = tempfile::tempdir().unwrap();
    let img = image();
    let e = write(&dir.path().join("a.tif"), &img, &OutputOptions::default()).unwrap_err();
    assert!(matches!(e, OutputError::Extension { .. }));
    let mut bad = image();
    bad.data.pop();
    let e = write(&dir.path().join("a.exr"), &bad, &OutputOptions::default()).unwrap_err();
    assert!(e.to_string().contains("expected 48"), "{e}");
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0);
}

#[path = "spectrum_output/photometric.rs"]
mod photometric;
