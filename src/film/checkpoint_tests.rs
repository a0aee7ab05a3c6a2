//! Tests of the film file: round trips, versions, damaged and hostile files.

use super::*;
use crate::film::{PassBuffer, Sampling};

fn sample() -> FilmFile {
    sample_on(SpectralGrid::new(3, 380.0, 730.0))
}

fn sample_on(grid: SpectralGrid) -> FilmFile {
    let n = grid.n;
    let mut film = Film::starting_at(2, 2, grid, 7);
    let mut b = PassBuffer::new(4, n);
    b.data
        .iter_mut()
        .enumerate()
        .for_each(|(i, v)| *v = i as f32 * 0.37 - 3.0);
    film.add_pass(&b);
    film.add_pass(&b);
    film.dropped = 5;
    let sampling = Sampling {
        gather_budget: 1 << 30,
        machine_memory: 1 << 34,
        version: "0.1.0".into(),
    };
    let id = FilmId::new(&serde_json::json!({"x": 1}), 42, sampling).unwrap();
    FilmFile { film, id }
}

#[test]
fn round_trip_is_exact() {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("a.brume");
    let f = sample();
    write(&p, &f.film, &f.id).unwrap();
    assert_eq!(read(&p).unwrap(), f);
    let h = read_header(&p).unwrap();
    assert_eq!((h.first, h.end(), h.dropped), (7, 9, 5));
    assert_eq!(h.id, f.id);
    assert_eq!(h.file_bytes, std::fs::metadata(&p).unwrap().len());
}

#[test]
fn a_grid_with_lines_round_trips() {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("a.brume");
    let grid = SpectralGrid::with_lines(3, 380.0, 730.0, &[532.0, 633.0]).unwrap();
    let f = sample_on(grid);
    write(&p, &f.film, &f.id).unwrap();
    let back = read(&p).unwrap();
    assert_eq!(back, f);
    assert_eq!(back.film.grid.lines(), [532.0, 633.0]);
    let version =
        |p: &Path| u32::from_le_bytes(std::fs::read(p).unwrap()[8..12].try_into().unwrap());
    // A film without difference layers is written as before the blend: version 3.
    assert_eq!(version(&p), PLAIN);
}

/// A film with the blend's difference layers (`film::blend`).
fn sample_blended() -> FilmFile {
    let mut f = sample();
    let mut film = Film::starting_at(2, 2, f.film.grid.clone(), 7);
    let n = film.grid.n;
    let mut b = PassBuffer::new(4, n).with_blend(true);
    b.fold_blend();
    for (i, v) in b.data.iter_mut().enumerate() {
        *v = i as f32 * 0.37 - 3.0;
    }
    for (i, v) in b.blend.iter_mut().enumerate() {
        *v = (i as f32 * 0.11).sin();
    }
    film.add_pass(&b);
    film.add_pass(&b);
    assert!(film.blend.is_some());
    f.film = film;
    f
}

#[test]
fn a_blended_film_round_trips_as_version_4() {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("a.brume");
    let f = sample_blended();
    write(&p, &f.film, &f.id).unwrap();
    let back = read(&p).unwrap();
    assert_eq!(back, f);
    assert_eq!(back.film.image().data, f.film.image().data);
    let bytes = std::fs::read(&p).unwrap();
    assert_eq!(u32::from_le_bytes(bytes[8..12].try_into().unwrap()), 4);
    assert_eq!(read_header(&p).unwrap().file_bytes, bytes.len() as u64);
}

#[test]
fn damaged_files_are_refused_not_panicked_on() {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("a.brume");
    let lines = SpectralGrid::with_lines(3, 380.0, 730.0, &[532.0]).unwrap();
    for f in [sample(), sample_on(lines), sample_blended()] {
        write(&p, &f.film, &f.id).unwrap();
        let good = std::fs::read(&p).unwrap();
        // Every truncation and a flipped byte at every position is an error, never a panic.
        for cut in 0..good.len() {
            std::fs::write(&p, &good[..cut]).unwrap();
            assert!(read(&p).is_err(), "truncated at {cut}");
        }
        for i in 0..good.len() {
            let mut bad = good.clone();
            bad[i] ^= 0x10;
            std::fs::write(&p, &bad).unwrap();
            assert!(read(&p).is_err(), "flipped byte {i}");
        }
    }
}

#[test]
fn a_header_announcing_a_huge_film_is_refused_before_allocating() {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("a.brume");
    let f = sample();
    write(&p, &f.film, &f.id).unwrap();
    let mut bytes = std::fs::read(&p).unwrap();
    // width = height = 2^31: 2^62 pixels.
    let at = 8 + 4 + 5 * 8;
    bytes[at..at + 8].copy_from_slice(&[0, 0, 0, 0x80, 0, 0, 0, 0x80]);
    std::fs::write(&p, &bytes).unwrap();
    let err = read(&p).unwrap_err().to_string();
    assert!(err.contains("absurd film size"), "{err}");
}

/// Every number a scene description can hold (f32 values as the scene stores them, widened to
/// f64, and f64 and integer values) survives the film file: the identity read back equals the
/// one written, so a checkpoint or part of any scene can be resumed and merged. Before
/// serde_json's exact float parsing was enabled, f32 values such as `g = 0.03` came back one
/// ulp off and the file was refused as damaged.
#[test]
fn every_number_in_the_description_reads_back_exactly() {
    use proptest::prelude::*;
    use proptest::test_runner::{Config, TestRunner};
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("a.brume");
    let f = sample();
    let mut runner = TestRunner::new_with_rng(
        Config {
            cases: 2000,
            ..Config::default()
        },
        proptest::test_runner::TestRng::deterministic_rng(
            proptest::test_runner::RngAlgorithm::ChaCha,
        ),
    );
    let value = (
        any::<f32>().prop_filter("finite", |v| v.is_finite()),
        any::<f64>().prop_filter("finite", |v| v.is_finite()),
        any::<u64>(),
        any::<i64>(),
    );
    runner
        .run(&value, |(a, b, c, d)| {
            let desc = serde_json::json!({
                "media": {"fog": {"g": a as f64, "sigma_s": [a as f64, b]}},
                "integrator": {"q": b, "count": c, "offset": d},
            });
            let id = FilmId::new(&desc, 3, f.id.sampling.clone()).unwrap();
            write(&p, &f.film, &id).unwrap();
            let back = read_header(&p).unwrap();
            prop_assert_eq!(back.id, id);
            Ok(())
        })
        .unwrap();
    // The values of the report, on their own.
    for g in [0.03f32, 0.015, 0.98] {
        let id = FilmId::new(&serde_json::json!({"g": g}), 3, f.id.sampling.clone()).unwrap();
        write(&p, &f.film, &id).unwrap();
        assert_eq!(read_header(&p).unwrap().id, id, "g = {g}");
    }
}
