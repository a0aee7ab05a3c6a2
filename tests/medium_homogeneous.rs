//! Homogeneous media: validation, derived coefficients, and power-law spectra (bin averages).

#[path = "estimator_stats.rs"]
mod stats;

use brume::medium::{ChannelPick, Medium, MediumError, power_law};
use brume::spectrum::{SpectralGrid, Spectrum};
use stats::simpson;

#[test]
fn validates_and_derives_sigma_t() {
    let ss = Spectrum::from_slice(&[0.5, 1.0, 2.0, 99.0]);
    let sa = Spectrum::from_slice(&[0.1, 0.0, 1.0, 99.0]);
    let m = Medium::new(&ss, &sa, 0.3, 3).unwrap();
    assert_eq!(m.sigma_t.as_slice(4), &[0.6, 1.0, 3.0, 0.0]);
    assert!((m.albedo()[0] - 0.5 / 0.6).abs() < 1e-6);
    assert_eq!(m.g(), 0.3);
    let bad = Spectrum::from_slice(&[0.5, -1.0]);
    assert!(matches!(
        Medium::new(&bad, &sa, 0.0, 2),
        Err(MediumError::Coefficient {
            what: "sigma_s",
            bin: 1,
            ..
        })
    ));
    let nan = Spectrum::from_slice(&[f32::NAN]);
    assert!(Medium::new(&ss, &nan, 0.0, 1).is_err());
    assert!(Medium::new(&ss, &sa, 1.0, 2).is_err());
    assert!(Medium::new(&ss, &sa, 0.0, 0).is_err());
    assert!(Medium::new(&ss, &sa, 0.0, 65).is_err());
}

#[test]
fn power_law_bins_are_exact_bin_averages() {
    let grid = SpectralGrid::new(8, 400.0, 720.0);
    for p in [0.0f32, 1.0, 1.3, 4.0] {
        let s = power_law(&grid, 0.02, 550.0, p).unwrap();
        for i in 0..grid.n {
            let (a, b) = grid.edges(i);
            let want = simpson(a, b, 2000, |x| 0.02 * (x / 550.0).powf(-(p as f64))) / (b - a);
            assert!(
                (s[i] as f64 - want).abs() < 1e-6 * want,
                "p={p} bin {i}: {} vs {want}",
                s[i]
            );
        }
        assert!(s.0[grid.n..].iter().all(|&x| x == 0.0));
    }
    assert!(power_law(&grid, -1.0, 550.0, 4.0).is_err());
    assert!(power_law(&grid, 1.0, 0.0, 4.0).is_err());
    assert!(power_law(&grid, 1.0, 550.0, f32::NAN).is_err());
}

#[test]
fn channel_pick_parses_from_scene_strings() {
    let t: ChannelPick = serde_json::from_str("\"throughput\"").unwrap();
    let u: ChannelPick = serde_json::from_str("\"uniform\"").unwrap();
    assert_eq!((t, u), (ChannelPick::Throughput, ChannelPick::Uniform));
    assert!(serde_json::from_str::<ChannelPick>("\"other\"").is_err());
}
