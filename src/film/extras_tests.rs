//! The film's extras with synthetic splats: sensors' sums and statistics, light layers, merges
//! in any grouping and the film file, all bit for bit.

use super::checkpoint;
use super::fixed::{SQ_SCALE, SUM_SCALE};
use super::sensor::{RELIABLE_PASSES, weights};
use super::*;
use crate::spectrum::SpectralGrid;

const W: usize = 4;
const H: usize = 3;

fn grid() -> SpectralGrid {
    SpectralGrid::new(3, 400.0, 700.0)
}

fn extras() -> FilmExtras {
    FilmExtras {
        sensors: vec![
            Sensor {
                name: "patch".into(),
                kind: SensorKind::Luminance {
                    region: [1, 0, 3, 2],
                },
            },
            Sensor {
                name: "meter".into(),
                kind: SensorKind::Illuminance {
                    position: [0.0, 0.0, 0.0],
                    normal: [0.0, 1.0, 0.0],
                },
            },
        ],
        light_layers: vec!["light0.point".into(), "light1.spot".into()],
    }
}

/// A deterministic pseudo-random value in [0, 1).
fn hash(k: u64) -> f32 {
    let x = k.wrapping_mul(0x9E37_79B9_7F4A_7C15) ^ (k >> 7);
    ((x >> 40) as f32) / (1u64 << 24) as f32
}

/// Pass `p`: splats from two lights (some through a chunk log, some directly), an
/// unattributed one, and the illuminance sensor's value.
fn pass(film: &Film, p: u64) -> PassBuffer {
    let mut buf = film.pass_buffer();
    let mut chunk = super::ChunkSplats::for_buffer(&buf);
    let n = film.grid.n;
    for k in 0..40u64 {
        let s = p * 1000 + k;
        let pixel = (hash(s) * (W * H) as f32) as usize;
        let w: Vec<f32> = (0..n).map(|b| hash(s + 7 * b as u64)).collect();
        let f: Vec<f32> = (0..n).map(|b| 1.0 + hash(s + 13 * b as u64)).collect();
        let light = Some((k % 2) as u32);
        let layer = if k % 3 == 0 {
            Layer::Surface
        } else {
            Layer::Medium
        };
        if k % 4 == 0 {
            buf.splat_scaled_from(layer, pixel, light, &w, 0.5);
        } else {
            chunk.splat_from(layer, pixel, light, &w, &f, 0.25);
        }
    }
    let v: Vec<f32> = (0..n).map(|b| 2.0 + hash(p * 31 + b as u64)).collect();
    chunk.splat_sensor(1, &v, 0.5);
    buf.splat_sensor(1, &v, 0.5);
    chunk.drain_into(&mut buf);
    buf
}

fn film_of(passes: std::ops::Range<u64>) -> Film {
    let mut f = Film::with_extras(W, H, grid(), passes.start, extras());
    for p in passes {
        let b = pass(&f, p);
        f.add_pass(&b);
    }
    f
}

#[test]
fn sensors_read_their_pass_values() {
    let film = film_of(0..5);
    let w = weights(&film.grid);
    let n = film.grid.n;
    // Independent recomputation: per pass, the region's mean (luminance) and the splatted
    // value (illuminance), their photometric values, mean and sample standard error.
    let mut per_pass = [vec![], vec![]];
    for p in 0..5 {
        let b = pass(&Film::with_extras(W, H, grid(), 0, extras()), p);
        let px = W * H * n;
        let mut region = vec![0.0f64; n];
        for (x, y) in [(1, 0), (2, 0), (1, 1), (2, 1)] {
            for (bin, r) in region.iter_mut().enumerate() {
                let i = (y * W + x) * n + bin;
                *r += (b.data[i] as f64 + b.data[px + i] as f64) / 4.0;
            }
        }
        let y = |v: &[f64]| v.iter().zip(&w).map(|(v, w)| v * w).sum::<f64>();
        per_pass[0].push(y(&region));
        let splat: Vec<f64> = b.sensor_data[n..2 * n].iter().map(|v| *v as f64).collect();
        per_pass[1].push(y(&splat));
    }
    let readings = film.sensor_readings();
    for (r, values) in readings.iter().zip(&per_pass) {
        let mean = values.iter().sum::<f64>() / 5.0;
        let var = values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / 4.0;
        assert!((r.value - mean).abs() < 1e-9 * mean.abs().max(1.0), "{r:?}");
        let se = r.std_error.expect("5 passes");
        assert!(
            (se - (var / 5.0).sqrt()).abs() < 1e-6 * se.max(1e-9),
            "{se} vs {var}"
        );
        let [lo, hi] = r.ci95.expect("5 passes");
        // Student's t, 4 degrees of freedom: 2.776 (when the interval stays above zero).
        if r.value - 2.776_445 * se >= 0.0 {
            assert!(((hi - lo) / (2.0 * se) - 2.776_445).abs() < 1e-4);
        }
        assert!(lo >= 0.0 && lo <= r.value && hi >= r.value, "{r:?}");
        assert!(!r.ci95_reliable, "5 passes are below {RELIABLE_PASSES}");
    }
    assert_eq!(readings[1].unit, "lx");
    assert_eq!(readings[0].unit, "cd/m2");
}

/// Issue 31: a 2-pass illuminance printed [-0.45, 19.9] lx. The interval respects the sign and
/// is marked unreliable below `RELIABLE_PASSES` passes.
#[test]
fn sensor_intervals_stay_positive_with_few_passes() {
    // value 9.725 lx, standard error 0.8 at 2 passes: t(1) = 12.706 reaches -0.44.
    let [lo, hi] = super::sensor::interval(9.725, 0.8, 2);
    assert!(lo > 0.0 && hi > 9.725, "[{lo}, {hi}]");
    // On the log scale: 9.725 x exp(+-12.706 x 0.8 / 9.725).
    let h: f64 = 12.706_2 * 0.8 / 9.725;
    assert!((lo / (9.725 * (-h).exp()) - 1.0).abs() < 1e-4, "{lo}");
    assert!((hi / (9.725 * h.exp()) - 1.0).abs() < 1e-4, "{hi}");
    // Many passes, small error: the usual symmetric interval (t(39) = 2.0227).
    let [lo, hi] = super::sensor::interval(16.03, 0.19, 40);
    assert!((lo - (16.03 - 2.022_69 * 0.19)).abs() < 1e-4, "{lo}");
    assert!((hi - (16.03 + 2.022_69 * 0.19)).abs() < 1e-4, "{hi}");
    // A zero reading stays [0, t se].
    assert_eq!(super::sensor::interval(0.0, 0.0, 3), [0.0, 0.0]);
}

#[test]
fn light_layers_sum_to_the_image() {
    let film = film_of(0..4);
    let img = film.image();
    assert_eq!(img.layers.len(), 4);
    assert_eq!(img.layers[2].0, "light0.point");
    for (i, v) in img.data.iter().enumerate() {
        let sum = img.layers[2].1[i] + img.layers[3].1[i];
        assert!(
            (sum - v).abs() <= 1e-6 * v.abs().max(1e-6),
            "{i}: {sum} vs {v}"
        );
    }
    assert!(film.unattributed().expect("layers").abs() < 1e-6);
    // A splat without its light reaches the image but no layer.
    let mut f = Film::with_extras(W, H, grid(), 0, extras());
    let mut b = f.pass_buffer();
    b.splat_scaled(Layer::Medium, 0, &[1.0, 1.0, 1.0], 1.0);
    b.splat_scaled_from(Layer::Medium, 1, Some(1), &[1.0, 1.0, 1.0], 1.0);
    f.add_pass(&b);
    assert!((f.unattributed().expect("layers") - 0.5).abs() < 1e-12);
}

#[test]
fn merges_in_any_grouping_and_the_file_are_exact() {
    let straight = film_of(0..6);
    let mut merged = film_of(4..6);
    merged.merge(&film_of(1..4)).expect("adjacent");
    merged.merge(&film_of(0..1)).expect("adjacent");
    assert_eq!(merged, straight);
    assert_eq!(merged.sensor_readings(), straight.sensor_readings());
    // Resume: a film read back from its file continues bit for bit.
    let dir = tempfile::tempdir().expect("tempdir");
    let path = dir.path().join("a.brume");
    let sampling = Sampling {
        gather_budget: 1,
        machine_memory: 1,
        version: "t".into(),
    };
    let id = FilmId::new(&serde_json::json!({"s": 1}), 3, sampling).expect("id");
    checkpoint::write(&path, &film_of(0..3), &id).expect("write");
    let mut resumed = checkpoint::read(&path).expect("read").film;
    for p in 3..6 {
        let b = pass(&resumed, p);
        resumed.add_pass(&b);
    }
    assert_eq!(resumed, straight);
    // Every byte of the file is covered: a flip anywhere is refused.
    let good = std::fs::read(&path).expect("bytes");
    for i in (0..good.len()).step_by(7) {
        let mut bad = good.clone();
        bad[i] ^= 0x04;
        std::fs::write(&path, &bad).expect("write");
        assert!(checkpoint::read(&path).is_err(), "flipped byte {i}");
    }
    // Films of other sensors or layers do not merge.
    let mut other = Film::with_extras(W, H, grid(), 6, FilmExtras::default());
    other.add_pass(&other.pass_buffer());
    assert_eq!(straight.clone().merge(&other), Err(MergeError::Shape));
}

#[test]
fn sensor_sums_use_the_film_scales() {
    let film = film_of(0..2);
    let n = film.grid.n;
    let r = &film.sensor_readings()[1];
    for (b, s) in r.spectrum.iter().enumerate() {
        assert_eq!(*s, film.sensor_sum[n + b] as f64 / SUM_SCALE / 2.0);
    }
    assert!(film.sensor_sq[1] as f64 / SQ_SCALE > 0.0);
    // Non-finite sensor values are dropped and counted, not summed.
    let mut f = Film::with_extras(W, H, grid(), 0, extras());
    let mut b = f.pass_buffer();
    b.splat_sensor(1, &[f32::NAN, 1.0, 1.0], 1.0);
    b.splat_sensor(7, &[1.0, 1.0, 1.0], 1.0);
    f.add_pass(&b);
    assert_eq!(f.dropped, 1);
    assert!(f.sensor_sum.iter().all(|v| *v == 0));
}
