//! References from OpenEXR files: brume's own (spectral channels `S0.<centre>nm` when they
//! match the study's grid, with the `medium.` / `surface.` layers and `noise.` standard error)
//! or any renderer's scene-linear RGB (e.g. Mitsuba's converged image).
//!
//! RGB is converted to the film's working space through brume's colour module, so that it means
//! what brume's own RGB output of the same radiance would: the source space's RGB goes to the
//! scene's absolute XYZ by the inverse of what brume would write in that space (white D65, the
//! film's chromatic adaptation), then to the working space. A file in a space brume does not
//! write (other primaries) goes through its own primaries and white, adapted to D65. The source
//! space is the one stated (`--reference-space`), else the file's `chromaticities` attribute;
//! with neither the file is refused rather than guessed.

use std::path::Path;

use exr::meta::attribute::Chromaticities;
use exr::prelude::read_all_flat_layers_from_file;

use super::{Layers, Reference, ReferenceOptions, Values, space_name};
use crate::colour::matrix::{self, IDENTITY, Mat3};
use crate::colour::{ColourSpace, D65_XY};
use crate::film::output::spectral_channel_name;
use crate::study::StudyError;

/// An EXR's channels by full name (`layer.channel` in multi-part files), all of one size.
struct Channels {
    width: usize,
    height: usize,
    list: Vec<(String, Vec<f32>)>,
}

impl Channels {
    fn get(&self, name: &str) -> Option<&[f32]> {
        self.list
            .iter()
            .find(|(n, _)| n == name)
            .map(|(_, v)| v.as_slice())
    }

    /// `prefix` + R, G, B interleaved per pixel, when all three are present.
    fn rgb(&self, prefix: &str) -> Option<Vec<f32>> {
        let [r, g, b] = ["R", "G", "B"].map(|c| self.get(&format!("{prefix}{c}")));
        let (r, g, b) = (r?, g?, b?);
        Some(
            r.iter()
                .zip(g)
                .zip(b)
                .flat_map(|((r, g), b)| [*r, *g, *b])
                .collect(),
        )
    }

    /// `prefix` + one spectral channel per bin of `grid`, interleaved per pixel (the film's
    /// layout), when every bin is present.
    fn spectral(&self, prefix: &str, grid: &crate::spectrum::SpectralGrid) -> Option<Vec<f32>> {
        let bins: Vec<&[f32]> = (0..grid.n)
            .map(|i| {
                self.get(&format!(
                    "{prefix}{}",
                    spectral_channel_name(grid.centre(i))
                ))
            })
            .collect::<Option<_>>()?;
        let pixels = self.width * self.height;
        let mut out = Vec::with_capacity(pixels * grid.n);
        for p in 0..pixels {
            out.extend(bins.iter().map(|b| b[p]));
        }
        Some(out)
    }
}

fn exr_err(path: &Path, message: impl std::fmt::Display) -> StudyError {
    StudyError::Reference {
        path: path.to_path_buf(),
        message: message.to_string(),
    }
}

fn read_channels(path: &Path) -> Result<(Channels, Option<Chromaticities>), StudyError> {
    let image = read_all_flat_layers_from_file(path).map_err(|e| exr_err(path, e))?;
    let mut size = None;
    let mut list = Vec::new();
    for layer in &image.layer_data {
        let (w, h) = (layer.size.0, layer.size.1);
        if *size.get_or_insert((w, h)) != (w, h) {
            return Err(exr_err(path, "its parts have different sizes"));
        }
        let prefix = layer
            .attributes
            .layer_name
            .as_ref()
            .map(|n| format!("{n}."))
            .unwrap_or_default();
        for ch in &layer.channel_data.list {
            let values: Vec<f32> = ch.sample_data.values_as_f32().collect();
            if values.len() != w * h {
                return Err(exr_err(path, format!("channel {} is subsampled", ch.name)));
            }
            list.push((format!("{prefix}{}", ch.name), values));
        }
    }
    let (width, height) = size.ok_or_else(|| exr_err(path, "no image in the file"))?;
    let chroma = image.attributes.chromaticities;
    Ok((
        Channels {
            width,
            height,
            list,
        },
        chroma,
    ))
}

/// Reads an EXR reference: spectrally when it has channels on the study's grid, else its RGB
/// converted to the working space.
pub(super) fn read(path: &Path, opts: &ReferenceOptions) -> Result<Reference, StudyError> {
    let (ch, chroma) = read_channels(path)?;
    let mut r = Reference {
        width: ch.width,
        height: ch.height,
        values: Values::Spectral(opts.grid.clone()),
        passes: 0,
        seconds: 0.0,
        total: Vec::new(),
        layers: None,
        noise: None,
        notes: Vec::new(),
    };
    if let Some(total) = ch.spectral("", &opts.grid) {
        r.total = total;
        r.layers = layers(|p| ch.spectral(p, &opts.grid));
        r.noise = ch.spectral("noise.", &opts.grid);
        r.notes.push(format!(
            "EXR with spectral channels on the study's grid ({} bins): compared bin by bin",
            opts.grid.n
        ));
        return Ok(r);
    }
    let Some(rgb) = ch.rgb("") else {
        let names: Vec<&str> = ch.list.iter().take(12).map(|(n, _)| n.as_str()).collect();
        return Err(exr_err(
            path,
            format!(
                "no R, G, B channels (nor spectral channels on the study's {}-bin grid); \
                 channels: {}",
                opts.grid.n,
                names.join(", ")
            ),
        ));
    };
    let (source, note) = source_space(path, opts.space, chroma)?;
    r.notes.push(note);
    let m = to_working(source, opts);
    r.values = Values::Rgb(opts.working);
    r.total = convert(&rgb, &m);
    r.layers = layers(|p| ch.rgb(p).map(|v| convert(&v, &m)));
    // Standard errors through the same matrix, channels taken as independent.
    let m2 = m.map(|row| row.map(|v| v * v));
    r.noise = ch.rgb("noise.").map(|n| {
        let var: Vec<f32> = n.iter().map(|s| s * s).collect();
        convert(&var, &m2).into_iter().map(|v| v.sqrt()).collect()
    });
    Ok(r)
}

fn layers(get: impl Fn(&str) -> Option<Vec<f32>>) -> Option<Layers> {
    Some(Layers {
        medium: get("medium.")?,
        surface: get("surface.")?,
    })
}

/// Where an RGB file's values come from.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Source {
    /// One of brume's working spaces, as brume writes it.
    Known(ColourSpace),
    /// Other primaries and white (from the file's chromaticities).
    Primaries([[f64; 2]; 3], [f64; 2]),
}

const SPACES: [ColourSpace; 3] = [ColourSpace::Srgb, ColourSpace::Acescg, ColourSpace::Xyz];

fn chromaticities(c: &Chromaticities) -> ([[f64; 2]; 3], [f64; 2]) {
    let v = |p: exr::math::Vec2<f32>| [p.0 as f64, p.1 as f64];
    ([v(c.red), v(c.green), v(c.blue)], v(c.white))
}

/// The working space whose chromaticities these are (to the precision files store them).
fn known_space(p: [[f64; 2]; 3], w: [f64; 2]) -> Option<ColourSpace> {
    let near = |a: [f64; 2], b: [f64; 2]| (a[0] - b[0]).abs() < 2e-4 && (a[1] - b[1]).abs() < 2e-4;
    SPACES.into_iter().find(|s| {
        let (sp, sw) = s.chromaticities();
        near(sw, w) && (0..3).all(|i| near(sp[i], p[i]))
    })
}

fn source_space(
    path: &Path,
    stated: Option<ColourSpace>,
    chroma: Option<Chromaticities>,
) -> Result<(Source, String), StudyError> {
    let file = chroma.as_ref().map(chromaticities);
    match (stated, file) {
        (Some(s), None) => Ok((
            Source::Known(s),
            format!("RGB reference stated to be in {}", space_name(s)),
        )),
        (Some(s), Some((p, w))) => {
            let note = match known_space(p, w) {
                Some(f) if f == s => format!(
                    "RGB reference in {} (stated; the file agrees)",
                    space_name(s)
                ),
                Some(f) => format!(
                    "warning: the file's chromaticities say {}, but it was stated to be in {}: \
                     read as {}",
                    space_name(f),
                    space_name(s),
                    space_name(s)
                ),
                None => format!(
                    "warning: the file's chromaticities ({p:?}, white {w:?}) are not {}'s, as \
                     stated: read as {}",
                    space_name(s),
                    space_name(s)
                ),
            };
            Ok((Source::Known(s), note))
        }
        (None, Some((p, w))) => Ok(match known_space(p, w) {
            Some(s) => (
                Source::Known(s),
                format!(
                    "RGB reference in {} (from the file's chromaticities)",
                    space_name(s)
                ),
            ),
            None => (
                Source::Primaries(p, w),
                format!("RGB reference with primaries {p:?} and white {w:?} (from the file)"),
            ),
        }),
        (None, None) => Err(exr_err(
            path,
            "the file has no chromaticities attribute: state its colour space with \
             --reference-space srgb|acescg|xyz (OpenEXR's default would be srgb primaries)",
        )),
    }
}

/// The matrix from the source's RGB to the working space's.
fn to_working(source: Source, opts: &ReferenceOptions) -> Mat3 {
    let to_rgb = opts.working.xyz_to_rgb(D65_XY, opts.cat);
    let to_xyz = match source {
        Source::Known(s) if s == opts.working => return IDENTITY,
        Source::Known(s) => matrix::invert(&s.xyz_to_rgb(D65_XY, opts.cat)),
        Source::Primaries(p, w) => {
            matrix::mul(&opts.cat.matrix(w, D65_XY), &matrix::rgb_to_xyz(p, w))
        }
    };
    matrix::mul(&to_rgb, &to_xyz)
}

fn convert(rgb: &[f32], m: &Mat3) -> Vec<f32> {
    if *m == IDENTITY {
        return rgb.to_vec();
    }
    rgb.chunks_exact(3)
        .flat_map(|p| {
            let v = matrix::apply(m, [p[0] as f64, p[1] as f64, p[2] as f64]);
            v.map(|c| c as f32)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::colour::{Cat, FilmToRgb, Observer};
    use crate::film::SpectralImage;
    use crate::film::output::{OutputOptions, write};
    use crate::spectrum::SpectralGrid;

    fn image() -> SpectralImage {
        let grid = SpectralGrid::new(8, 380.0, 780.0);
        let mut img = SpectralImage::new(3, 2, grid);
        img.data = (0..48)
            .map(|i| 0.05 + ((i * 37) % 11) as f32 * 0.1)
            .collect();
        img.layers = vec![
            ("medium".into(), img.data.iter().map(|v| v * 0.25).collect()),
            (
                "surface".into(),
                img.data.iter().map(|v| v * 0.75).collect(),
            ),
        ];
        img
    }

    fn opts(grid: SpectralGrid, space: Option<ColourSpace>) -> ReferenceOptions {
        ReferenceOptions {
            space,
            working: ColourSpace::Srgb,
            cat: Cat::Bradford,
            grid,
        }
    }

    /// brume's RGB EXR in any space, read back, equals its sRGB output (to f32 rounding):
    /// the conversion inverts exactly what the writer did.
    #[test]
    fn brume_exr_in_any_space_reads_back_as_its_srgb() {
        let img = image();
        let dir = tempfile::tempdir().expect("tempdir");
        let srgb = FilmToRgb::new(
            ColourSpace::Srgb,
            Observer::Cie1931,
            &img.grid,
            Cat::Bradford,
        )
        .expect("conv");
        let want: Vec<f32> = img.data.chunks_exact(8).flat_map(|p| srgb.rgb(p)).collect();
        let other = SpectralGrid::new(4, 400.0, 700.0); // no spectral match: RGB path
        for space in SPACES {
            let p = dir.path().join(format!("{}.exr", space_name(space)));
            let o = OutputOptions {
                colour_space: space,
                ..OutputOptions::default()
            };
            write(&p, &img, &o).expect("write");
            let r = read(&p, &opts(other.clone(), None)).expect("read");
            assert_eq!(r.values, Values::Rgb(ColourSpace::Srgb));
            assert!(r.notes[0].contains(space_name(space)), "{:?}", r.notes);
            for (a, b) in r.total.iter().zip(&want) {
                assert!(
                    (a - b).abs() <= 1e-5 * b.abs().max(1.0),
                    "{space:?}: {a} vs {b}"
                );
            }
            let layers = r.layers.expect("brume's layers");
            assert!((layers.medium[4] - 0.25 * want[4]).abs() < 1e-5);
            // Stating another space than the file's is obeyed, with a warning.
            let wrong = if space == ColourSpace::Srgb {
                ColourSpace::Acescg
            } else {
                ColourSpace::Srgb
            };
            let r2 = read(&p, &opts(other.clone(), Some(wrong))).expect("read");
            assert!(r2.notes[0].starts_with("warning"), "{:?}", r2.notes);
        }
    }

    #[test]
    fn spectral_exr_is_compared_bin_by_bin() {
        let img = image();
        let dir = tempfile::tempdir().expect("tempdir");
        let p = dir.path().join("s.exr");
        let o = OutputOptions {
            spectral_layers: true,
            ..OutputOptions::default()
        };
        write(&p, &img, &o).expect("write");
        let r = read(&p, &opts(img.grid.clone(), None)).expect("read");
        assert_eq!(r.values, Values::Spectral(img.grid));
        assert_eq!(r.total, img.data);
        assert_eq!(r.layers.expect("layers").surface, img.layers[1].1);
        assert!(r.noise.is_none());
    }

    #[test]
    fn unknown_primaries_go_through_xyz_and_missing_space_is_refused() {
        // P3-like primaries with a D65 white: converting pure red gives sRGB red > 1 with
        // negative green and blue (P3 red is outside sRGB).
        let p3 = [[0.680, 0.320], [0.265, 0.690], [0.150, 0.060]];
        let m = to_working(
            Source::Primaries(p3, D65_XY),
            &opts(SpectralGrid::default(), None),
        );
        let red = matrix::apply(&m, [1.0, 0.0, 0.0]);
        assert!(red[0] > 1.0 && red[1] < 0.0 && red[2] < 0.0, "{red:?}");
        // White stays white.
        let white = matrix::apply(&m, [1.0, 1.0, 1.0]);
        for c in white {
            assert!((c - 1.0).abs() < 1e-9, "{white:?}");
        }
        let e = source_space(Path::new("x.exr"), None, None).unwrap_err();
        assert!(e.to_string().contains("--reference-space"), "{e}");
    }
}
